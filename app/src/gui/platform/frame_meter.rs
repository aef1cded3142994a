//! The window's own responsiveness: frames drawn in the last second, the
//! time the UI thread spends building one and what a frame costs in CPU,
//! shown in the statistics so a user can see the render never starves the
//! window; and the pace at which render progress may ask for a redraw, so
//! drawing never starves the render.
//!
//! What a frame costs is measured as the process's CPU time minus the render
//! threads' ([`super::cpu_clock`]).

use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use web_time::Instant;

pub(crate) use super::cpu_clock::CpuTimes;

/// The span over which frames are counted.
const WINDOW: Duration = Duration::from_secs(1);
/// Fastest refresh of the progressive image: 30 Hz.
pub(crate) const MIN_PROGRESS_INTERVAL: Duration = Duration::from_millis(33);
/// Slowest refresh of the progressive image, however costly drawing is.
const MAX_PROGRESS_INTERVAL: Duration = Duration::from_secs(2);
/// Progress redraws may take at most 1 / PAINT_SHARE of the CPU the render
/// gets, so the window renders nearly as fast as a headless render.
const PAINT_SHARE: u32 = 10;
/// The span over which the CPU cost of frames is averaged: a software
/// rasterizer finishes a frame well after the UI thread handed it over.
const CPU_SPAN: Duration = Duration::from_secs(2);

/// The frame meter and the progress pace it sets, frame by frame.
#[derive(Default)]
pub(crate) struct Pacing {
    pub(crate) frame_meter: FrameMeter,
    /// How often render progress may redraw the window.
    pub(crate) progress_pace: ProgressPace,
}

impl Pacing {
    /// A frame starts; `cpu_usage` is eframe's measure of the previous one.
    pub(crate) fn begin(&mut self, cpu_usage: Option<f32>) {
        self.frame_meter
            .begin(Instant::now(), cpu_usage, CpuTimes::now());
    }

    /// The frame is drawn: the pace follows what frames cost.
    pub(crate) fn end(&mut self) {
        self.frame_meter.end(Instant::now());
        self.progress_pace.set(self.frame_meter.progress_interval());
    }
}

#[derive(Debug, Default, Clone)]
pub(crate) struct FrameMeter {
    /// Start times of the frames of the last [`WINDOW`].
    starts: VecDeque<Instant>,
    current: Option<Instant>,
    /// Smoothed time spent building a frame, seconds.
    work: f32,
    /// The last frame's own work, to tell painting from it.
    last_work: f32,
    /// Smoothed time the UI thread spends tessellating and painting a
    /// frame, seconds (eframe's measure, without the rasterizer's threads).
    paint: f32,
    /// CPU times at the starts of the frames of the last [`CPU_SPAN`] (and
    /// one before it), where the OS tells them.
    cpu_marks: VecDeque<(Instant, CpuTimes)>,
}

/// Cores the render and the window share.
fn cores() -> u32 {
    static CORES: OnceLock<u32> = OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get() as u32))
}

/// Moves a smoothed value towards `sample`.
fn smooth(value: f32, sample: f32) -> f32 {
    if value == 0.0 {
        sample
    } else {
        0.9 * value + 0.1 * sample
    }
}

impl FrameMeter {
    /// Marks the start of a frame at `now`. `previous_cost` is what the
    /// previous frame took from start to painted (eframe's `cpu_usage`:
    /// the UI's work, tessellation and painting, waiting for vsync aside);
    /// `cpu` the CPU times now ([`CpuTimes::now`]).
    pub(crate) fn begin(
        &mut self,
        now: Instant,
        previous_cost: Option<f32>,
        cpu: Option<CpuTimes>,
    ) {
        while self
            .starts
            .front()
            .is_some_and(|&t| now.duration_since(t) > WINDOW)
        {
            self.starts.pop_front();
        }
        self.starts.push_back(now);
        self.current = Some(now);
        if let Some(cost) = previous_cost {
            self.paint = smooth(self.paint, (cost - self.last_work).max(0.0));
        }
        match cpu {
            Some(cpu) => {
                self.cpu_marks.push_back((now, cpu));
                // The frames of the last CPU_SPAN and the one before them.
                while self
                    .cpu_marks
                    .get(1)
                    .is_some_and(|&(t, _)| now.duration_since(t) > CPU_SPAN)
                {
                    self.cpu_marks.pop_front();
                }
            }
            None => self.cpu_marks.clear(),
        }
    }

    /// Marks the end, at `now`, of the frame begun last.
    pub(crate) fn end(&mut self, now: Instant) {
        if let Some(start) = self.current.take() {
            self.last_work = now.duration_since(start).as_secs_f32();
            self.work = smooth(self.work, self.last_work);
        }
    }

    /// Frames begun during the last second. The window redraws only when
    /// something changes, so an idle window shows a low rate.
    pub(crate) fn frames_per_second(&self) -> usize {
        self.starts.len()
    }

    /// Smoothed time the UI thread spends on one frame, seconds.
    pub(crate) fn work_per_frame(&self) -> f32 {
        self.work
    }

    /// The CPU time one frame costs, on every thread but the render's
    /// (the UI's work, tessellation, the rasterizer's threads), averaged
    /// over the frames of the last two seconds; `None` until measured (or
    /// where the OS has no CPU clocks).
    pub(crate) fn cpu_per_frame(&self) -> Option<Duration> {
        let (first, last, frames) = self.cpu_span()?;
        let process = last.process.saturating_sub(first.process);
        let render = last.render.saturating_sub(first.render);
        Some(process.saturating_sub(render) / frames)
    }

    /// The CPU the render threads got over the last two seconds, in cores
    /// (less than the machine's when other programs run too), counted from
    /// the first frame after which they worked: a render started after an
    /// idle spell read 0.06 cores over the whole span, which paced its
    /// progress at 2 s, and with no redraw the estimate never caught up
    /// (a 1.5 s render showed its first pass until it was done).
    fn render_cores(&self) -> Option<f32> {
        let marks = &self.cpu_marks;
        let active = marks
            .iter()
            .zip(marks.iter().skip(1))
            .position(|((_, a), (_, b))| b.render > a.render)?;
        let (&(start, first), &(end, last)) = (marks.get(active)?, marks.back()?);
        let wall = end.duration_since(start).as_secs_f32();
        let render = last.render.saturating_sub(first.render).as_secs_f32();
        (wall > 0.0).then(|| render / wall)
    }

    /// The first and last CPU marks and the frames between them.
    fn cpu_span(&self) -> Option<(CpuTimes, CpuTimes, u32)> {
        let frames = u32::try_from(self.cpu_marks.len().checked_sub(1)?).ok()?;
        let (_, first) = self.cpu_marks.front()?;
        let (_, last) = self.cpu_marks.back()?;
        (frames > 0).then_some((*first, *last, frames))
    }

    /// What a frame costs: [`FrameMeter::cpu_per_frame`] where measured,
    /// else the UI thread's time to build and paint it.
    pub(crate) fn frame_cost(&self) -> Duration {
        self.cpu_per_frame()
            .unwrap_or_else(|| Duration::from_secs_f32(self.work + self.paint))
    }

    /// How long render progress should wait before asking for a redraw:
    /// 30 Hz when drawing is cheap, slower when it is costly, so that
    /// redraws take at most 1 / [`PAINT_SHARE`] of the CPU the render gets
    /// (all cores on an idle machine, less when other programs run).
    pub(crate) fn progress_interval(&self) -> Duration {
        let interval = match self.cpu_per_frame() {
            Some(cpu) => {
                let cores = self
                    .render_cores()
                    .filter(|&c| c > 0.05)
                    .unwrap_or(cores() as f32);
                cpu.mul_f32(PAINT_SHARE as f32 / cores)
            }
            // Without CPU clocks, painting is assumed to hold every core.
            None => Duration::from_secs_f32(self.work + self.paint) * PAINT_SHARE,
        };
        interval.clamp(MIN_PROGRESS_INTERVAL, MAX_PROGRESS_INTERVAL)
    }
}

/// The progress interval, shared with the render threads that ask for
/// redraws.
#[derive(Debug, Clone)]
pub(crate) struct ProgressPace(Arc<AtomicU64>);

impl Default for ProgressPace {
    fn default() -> Self {
        ProgressPace(Arc::new(AtomicU64::new(
            MIN_PROGRESS_INTERVAL.as_micros() as u64
        )))
    }
}

impl ProgressPace {
    pub(crate) fn set(&self, interval: Duration) {
        self.0.store(interval.as_micros() as u64, Ordering::Relaxed);
    }

    pub(crate) fn get(&self) -> Duration {
        Duration::from_micros(self.0.load(Ordering::Relaxed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn counts_the_frames_of_the_last_second_and_their_work() {
        let mut meter = FrameMeter::default();
        let t0 = Instant::now();
        for i in 0..5 {
            let start = t0 + 100 * MS * i;
            meter.begin(start, None, None);
            meter.end(start + 2 * MS);
        }
        assert_eq!(meter.frames_per_second(), 5);
        assert!((meter.work_per_frame() - 0.002).abs() < 1e-4);
        // Later, only the frames of the last second count (at 400 ms and
        // this one).
        meter.begin(t0 + 1350 * MS, None, None);
        assert_eq!(meter.frames_per_second(), 2);
    }

    #[test]
    fn costly_painting_slows_progress_redraws_down_to_a_limit() {
        // Without CPU clocks: the UI thread's time, painting holding every
        // core.
        let mut meter = FrameMeter::default();
        assert_eq!(meter.progress_interval(), MIN_PROGRESS_INTERVAL);
        // Frames of 5 ms of work painted in 45 ms more.
        let t0 = Instant::now();
        for i in 0..20 {
            let start = t0 + 500 * MS * i;
            meter.begin(start, (i > 0).then_some(0.050), None);
            meter.end(start + 5 * MS);
        }
        let paint = meter.frame_cost() - 5 * MS;
        assert!(paint > 44 * MS && paint < 46 * MS, "{paint:?}");
        let interval = meter.progress_interval().as_secs_f32();
        assert!(
            (interval - 0.050 * PAINT_SHARE as f32).abs() < 1e-3,
            "{interval}"
        );
        // Painting even slower reaches the limit.
        for i in 20..60 {
            let start = t0 + 500 * MS * i;
            meter.begin(start, Some(0.800), None);
            meter.end(start + 5 * MS);
        }
        assert_eq!(meter.progress_interval(), MAX_PROGRESS_INTERVAL);
    }

    #[test]
    fn idle_time_between_frames_is_not_painting() {
        // An idle window draws a frame every few seconds: the gaps are not
        // what painting costs.
        let mut meter = FrameMeter::default();
        let t0 = Instant::now();
        for i in 0..10 {
            let start = t0 + Duration::from_secs(5) * i;
            meter.begin(start, (i > 0).then_some(0.004), None);
            meter.end(start + 3 * MS);
        }
        assert!(meter.frame_cost() < 5 * MS, "{:?}", meter.frame_cost());
        assert!(meter.progress_interval() < 2 * MIN_PROGRESS_INTERVAL);
    }

    #[test]
    fn a_frame_costs_the_cpu_of_every_thread_but_the_render() {
        let mut meter = FrameMeter::default();
        let t0 = Instant::now();
        let mut cpu = CpuTimes::default();
        // Frames `frames` every 500 ms; between two, the process uses
        // `process` of CPU, of which the render threads `render`.
        let mut run = |frames: std::ops::Range<u32>, process: Duration, render: Duration| {
            for i in frames {
                let start = t0 + 500 * MS * i;
                meter.begin(start, Some(0.010), Some(cpu));
                meter.end(start + 5 * MS);
                cpu.process += process;
                cpu.render += render;
            }
            meter.clone()
        };
        // The rest of the process (the UI thread, the rasterizer's threads)
        // takes 150 ms a frame.
        let meter = run(0..10, 1050 * MS, 900 * MS);
        assert_eq!(meter.cpu_per_frame(), Some(150 * MS));
        assert_eq!(meter.frame_cost(), 150 * MS);
        // The render got 1.8 cores: a frame may come every 150 ms * 10 /
        // 1.8, so that redraws take a tenth of what the render gets.
        let interval = meter.progress_interval().as_secs_f32();
        assert!((interval - 0.150 * 10.0 / 1.8).abs() < 1e-3, "{interval}");

        // On a busy machine the render gets 0.6 cores: redraws come less
        // often, down to the limit.
        let meter = run(10..20, 450 * MS, 300 * MS);
        assert_eq!(meter.progress_interval(), MAX_PROGRESS_INTERVAL);

        // The render alone taking CPU costs the window nothing.
        let meter = run(20..30, 900 * MS, 900 * MS);
        assert_eq!(meter.cpu_per_frame(), Some(Duration::ZERO));
        assert_eq!(meter.progress_interval(), MIN_PROGRESS_INTERVAL);
    }

    #[test]
    fn a_render_after_an_idle_spell_is_paced_by_the_cores_it_gets() {
        let mut meter = FrameMeter::default();
        let t0 = Instant::now();
        let mut cpu = CpuTimes::default();
        let mut frame = |at: Duration, cpu: CpuTimes| {
            meter.begin(t0 + at, Some(0.010), Some(cpu));
            meter.end(t0 + at + 5 * MS);
        };
        // An idle window: a frame now and then, 20 ms of CPU each.
        for i in 0..4 {
            frame(500 * MS * i, cpu);
            cpu.process += 20 * MS;
        }
        // Then a render on two cores, a frame every 100 ms.
        for i in 0..3 {
            frame(2000 * MS + 100 * MS * i, cpu);
            cpu.process += 220 * MS;
            cpu.render += 200 * MS;
        }
        frame(2300 * MS, cpu);
        assert_eq!(meter.cpu_per_frame(), Some(20 * MS));
        // 20 ms * 10 / 2 cores, not the 20 ms * 10 / 0.26 cores of the whole
        // span (a 770 ms wait).
        let interval = meter.progress_interval().as_secs_f32();
        assert!((interval - 0.100).abs() < 2e-3, "{interval}");
    }
}
