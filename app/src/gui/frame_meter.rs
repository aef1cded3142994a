//! The window's own responsiveness: frames drawn in the last second and the
//! time the UI thread spends building one, shown in the statistics so a
//! user can see the render never starves the window; and the pace at which
//! render progress may ask for a redraw, so drawing never starves the render.

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The span over which frames are counted.
const WINDOW: Duration = Duration::from_secs(1);
/// Fastest refresh of the progressive image: 30 Hz.
pub const MIN_PROGRESS_INTERVAL: Duration = Duration::from_millis(33);
/// Slowest refresh of the progressive image, however costly drawing is.
const MAX_PROGRESS_INTERVAL: Duration = Duration::from_millis(500);
/// Progress redraws may take at most 1 / PAINT_SHARE of the time.
const PAINT_SHARE: u32 = 4;

#[derive(Debug, Default)]
pub struct FrameMeter {
    /// Start times of the frames of the last [`WINDOW`].
    starts: VecDeque<Instant>,
    current: Option<Instant>,
    /// Smoothed time spent building a frame, seconds.
    work: f32,
    ended: Option<Instant>,
    /// Shortest time between the end of one frame and the start of the next
    /// during the last [`WINDOW`]: when frames come back to back, that is
    /// what painting and presenting cost (a software rasterizer takes tens
    /// of milliseconds; a GPU well under one).
    paint: Duration,
    paint_window_start: Option<Instant>,
    paint_in_window: Option<Duration>,
}

impl FrameMeter {
    /// Marks the start of a frame.
    pub fn begin(&mut self) {
        let now = Instant::now();
        while self
            .starts
            .front()
            .is_some_and(|&t| now.duration_since(t) > WINDOW)
        {
            self.starts.pop_front();
        }
        self.starts.push_back(now);
        self.current = Some(now);
        if let Some(ended) = self.ended {
            let gap = now.duration_since(ended);
            self.paint_in_window = Some(self.paint_in_window.map_or(gap, |p| p.min(gap)));
        }
        let window_start = *self.paint_window_start.get_or_insert(now);
        if now.duration_since(window_start) > WINDOW {
            if let Some(paint) = self.paint_in_window.take() {
                self.paint = paint;
            }
            self.paint_window_start = Some(now);
        }
    }

    /// Marks the end of the frame begun last.
    pub fn end(&mut self) {
        self.ended = Some(Instant::now());
        if let Some(start) = self.current.take() {
            let work = start.elapsed().as_secs_f32();
            self.work = if self.work == 0.0 {
                work
            } else {
                0.9 * self.work + 0.1 * work
            };
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

    /// What drawing one frame costs besides the UI's work (see `paint`).
    pub fn paint_time(&self) -> Duration {
        self.paint
    }

    /// How long render progress should wait before asking for a redraw:
    /// 30 Hz when drawing is cheap, slower when it is costly, so that
    /// redraws take at most a quarter of the time.
    pub fn progress_interval(&self) -> Duration {
        let work = Duration::from_secs_f32(self.work);
        ((self.paint + work) * PAINT_SHARE).clamp(MIN_PROGRESS_INTERVAL, MAX_PROGRESS_INTERVAL)
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

    #[test]
    fn counts_the_frames_of_the_last_second_and_their_work() {
        let mut meter = FrameMeter::default();
        for _ in 0..5 {
            meter.begin();
            std::thread::sleep(Duration::from_millis(2));
            meter.end();
        }
        assert_eq!(meter.frames_per_second(), 5);
        assert!(meter.work_per_frame() >= 0.002);
    }

    #[test]
    fn costly_painting_slows_progress_redraws_down_to_a_limit() {
        let mut meter = FrameMeter::default();
        assert_eq!(meter.progress_interval(), MIN_PROGRESS_INTERVAL);
        // Frames back to back with 60 ms between them, for over a second.
        for _ in 0..20 {
            meter.begin();
            meter.end();
            std::thread::sleep(Duration::from_millis(60));
        }
        assert!(meter.paint_time() >= Duration::from_millis(60));
        let interval = meter.progress_interval();
        assert!(interval >= Duration::from_millis(240), "{interval:?}");
        assert!(interval <= MAX_PROGRESS_INTERVAL);
    }
}
