//! The window's own responsiveness: frames drawn in the last second, the
//! time the UI thread spends building one and what painting it costs, shown
//! in the statistics so a user can see the render never starves the window;
//! and the pace at which render progress may ask for a redraw, so drawing
//! never starves the render.

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The span over which frames are counted.
const WINDOW: Duration = Duration::from_secs(1);
/// Fastest refresh of the progressive image: 30 Hz.
pub const MIN_PROGRESS_INTERVAL: Duration = Duration::from_millis(33);
/// Slowest refresh of the progressive image, however costly drawing is.
const MAX_PROGRESS_INTERVAL: Duration = Duration::from_secs(1);
/// Progress redraws may take at most 1 / PAINT_SHARE of the time: painting
/// on a software rasterizer takes every core while it runs.
const PAINT_SHARE: u32 = 8;

#[derive(Debug, Default)]
pub struct FrameMeter {
    /// Start times of the frames of the last [`WINDOW`].
    starts: VecDeque<Instant>,
    current: Option<Instant>,
    /// Smoothed time spent building a frame, seconds.
    work: f32,
    /// The last frame's own work, to tell painting from it.
    last_work: f32,
    /// Smoothed time spent tessellating and painting a frame, seconds: a
    /// software rasterizer takes tens of milliseconds, a GPU well under one.
    paint: f32,
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
    /// the UI's work, tessellation and painting, waiting for vsync aside).
    pub fn begin(&mut self, now: Instant, previous_cost: Option<f32>) {
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
    }

    /// Marks the end, at `now`, of the frame begun last.
    pub fn end(&mut self, now: Instant) {
        if let Some(start) = self.current.take() {
            self.last_work = now.duration_since(start).as_secs_f32();
            self.work = smooth(self.work, self.last_work);
        }
    }

    /// Frames begun during the last second. The window redraws only when
    /// something changes, so an idle window shows a low rate.
    pub fn frames_per_second(&self) -> usize {
        self.starts.len()
    }

    /// Smoothed time the UI thread spends on one frame, seconds.
    pub fn work_per_frame(&self) -> f32 {
        self.work
    }

    /// What drawing one frame costs besides the UI's work.
    pub fn paint_time(&self) -> Duration {
        Duration::from_secs_f32(self.paint)
    }

    /// How long render progress should wait before asking for a redraw:
    /// 30 Hz when drawing is cheap, slower when it is costly, so that
    /// redraws take at most 1 / [`PAINT_SHARE`] of the time.
    pub fn progress_interval(&self) -> Duration {
        let frame = Duration::from_secs_f32(self.work + self.paint);
        (frame * PAINT_SHARE).clamp(MIN_PROGRESS_INTERVAL, MAX_PROGRESS_INTERVAL)
    }
}

/// The progress interval, shared with the render threads that ask for
/// redraws.
#[derive(Debug, Clone)]
pub struct ProgressPace(Arc<AtomicU64>);

impl Default for ProgressPace {
    fn default() -> Self {
        ProgressPace(Arc::new(AtomicU64::new(
            MIN_PROGRESS_INTERVAL.as_micros() as u64
        )))
    }
}

impl ProgressPace {
    pub fn set(&self, interval: Duration) {
        self.0.store(interval.as_micros() as u64, Ordering::Relaxed);
    }

    pub fn get(&self) -> Duration {
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
            meter.begin(start, None);
            meter.end(start + 2 * MS);
        }
        assert_eq!(meter.frames_per_second(), 5);
        assert!((meter.work_per_frame() - 0.002).abs() < 1e-4);
        // Later, only the frames of the last second count (at 400 ms and
        // this one).
        meter.begin(t0 + 1350 * MS, None);
        assert_eq!(meter.frames_per_second(), 2);
    }

    #[test]
    fn costly_painting_slows_progress_redraws_down_to_a_limit() {
        let mut meter = FrameMeter::default();
        assert_eq!(meter.progress_interval(), MIN_PROGRESS_INTERVAL);
        // Frames of 5 ms of work painted in 45 ms more.
        let t0 = Instant::now();
        for i in 0..20 {
            let start = t0 + 500 * MS * i;
            meter.begin(start, (i > 0).then_some(0.050));
            meter.end(start + 5 * MS);
        }
        let paint = meter.paint_time();
        assert!(paint > 44 * MS && paint < 46 * MS, "{paint:?}");
        let interval = meter.progress_interval().as_secs_f32();
        assert!(
            (interval - 0.050 * PAINT_SHARE as f32).abs() < 1e-3,
            "{interval}"
        );
        // Painting even slower reaches the limit.
        for i in 20..60 {
            let start = t0 + 500 * MS * i;
            meter.begin(start, Some(0.400));
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
            meter.begin(start, (i > 0).then_some(0.004));
            meter.end(start + 3 * MS);
        }
        assert!(meter.paint_time() < 2 * MS, "{:?}", meter.paint_time());
        assert_eq!(meter.progress_interval(), MIN_PROGRESS_INTERVAL);
    }
}
