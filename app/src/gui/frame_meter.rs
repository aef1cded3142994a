//! The window's own responsiveness: frames drawn in the last second and the
//! time the UI thread spends building one, shown in the statistics so a
//! user can see the render never starves the window.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// The span over which frames are counted.
const WINDOW: Duration = Duration::from_secs(1);

#[derive(Debug, Default)]
pub struct FrameMeter {
    /// Start times of the frames of the last [`WINDOW`].
    starts: VecDeque<Instant>,
    current: Option<Instant>,
    /// Smoothed time spent building a frame, seconds.
    work: f32,
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
    }

    /// Marks the end of the frame begun last.
    pub fn end(&mut self) {
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
}
