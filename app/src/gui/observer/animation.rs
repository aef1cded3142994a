//! Rays growing out of the camera, as Virtual Ray Tracer shows them: eye
//! rays first, then each bounce generation, then the shadow rays; play,
//! pause, step and speed; at rest the whole tree.

use web_time::Instant;

/// Where the animation is.
#[derive(Debug, Clone)]
pub struct Animation {
    /// Phases (ray generations) drawn per second.
    pub(crate) speed: f32,
    /// How far it got, in phases; `None` at rest (everything drawn).
    time: Option<f32>,
    playing: bool,
    /// When it last advanced, while playing (`None` until the first
    /// [`Animation::advance`] after play or resume).
    advanced_at: Option<Instant>,
}

impl Default for Animation {
    fn default() -> Self {
        Self {
            speed: 1.0,
            time: None,
            playing: false,
            advanced_at: None,
        }
    }
}

impl Animation {
    /// Starts again from the eye rays.
    pub(crate) fn play(&mut self) {
        self.time = Some(0.0);
        self.playing = true;
        self.advanced_at = None;
    }

    /// Holds where it is (or, at rest, stays at rest).
    pub(crate) fn pause(&mut self) {
        self.playing = false;
    }

    /// Goes on from where it was paused.
    pub(crate) fn resume(&mut self) {
        if self.time.is_some() {
            self.playing = true;
            self.advanced_at = None;
        }
    }

    pub fn is_playing(&self) -> bool {
        self.playing
    }

    /// Shows the next generation whole, paused; after the last, the whole
    /// tree at rest.
    pub(crate) fn step(&mut self, phases: u32) {
        self.playing = false;
        let next = self.time.map_or(1.0, |t| t.floor() + 1.0);
        self.time = (next < phases as f32).then_some(next);
    }

    /// The animation at rest: every ray whole.
    pub(crate) fn rest(&mut self) {
        self.time = None;
        self.playing = false;
    }

    /// Moves time on to `now` (the window's clock; the first call after
    /// play or resume starts counting from it); at the end of `phases` it
    /// comes to rest. True while it still plays (the window asks for
    /// another frame).
    pub(crate) fn advance(&mut self, now: Instant, phases: u32) -> bool {
        let (true, Some(time)) = (self.playing, self.time) else {
            return false;
        };
        let since = *self.advanced_at.get_or_insert(now);
        let time = time + (now - since).as_secs_f32() * self.speed;
        self.advanced_at = Some(now);
        if time >= phases as f32 {
            self.rest();
            return false;
        }
        self.time = Some(time);
        true
    }

    /// How much of a segment of `phase` is drawn: 0 before its turn, 1
    /// once it is whole.
    pub(crate) fn fraction(&self, phase: u32) -> f32 {
        self.time
            .map_or(1.0, |t| (t - phase as f32).clamp(0.0, 1.0))
    }

    /// The generation being drawn, for the label; `None` at rest.
    pub fn phase(&self) -> Option<u32> {
        self.time.map(|t| t.floor() as u32)
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    #[test]
    fn generations_grow_one_after_another_then_rest() {
        let mut animation = Animation {
            speed: 2.0,
            ..Animation::default()
        };
        assert_eq!(animation.fraction(5), 1.0, "at rest everything shows");
        animation.play();
        assert_eq!((animation.fraction(0), animation.fraction(1)), (0.0, 0.0));
        let start = Instant::now();
        assert!(animation.advance(start, 3), "playing from here");
        assert_eq!(animation.fraction(0), 0.0);
        // Half a second at two phases a second: the eye rays are whole,
        // the first bounce has not started.
        assert!(animation.advance(start + Duration::from_millis(500), 3));
        assert!((animation.fraction(0) - 1.0).abs() < 1e-6);
        assert_eq!(animation.fraction(1), 0.0);
        assert!(animation.advance(start + Duration::from_millis(750), 3));
        assert!((animation.fraction(1) - 0.5).abs() < 1e-4);
        assert!(!animation.advance(start + Duration::from_secs(2), 3));
        assert_eq!(animation.phase(), None, "at rest after the last phase");
    }

    #[test]
    fn steps_show_one_more_generation_each() {
        let mut animation = Animation::default();
        animation.play();
        animation.step(3);
        assert_eq!(animation.phase(), Some(1));
        assert_eq!(animation.fraction(0), 1.0);
        assert_eq!(animation.fraction(1), 0.0);
        assert!(!animation.is_playing());
        animation.step(3);
        assert_eq!(animation.phase(), Some(2));
        animation.step(3);
        assert_eq!(animation.phase(), None, "past the last: the whole tree");
    }
}
