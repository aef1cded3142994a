//! The clock for what the window times itself: a notice's fade, edits of
//! one field merging into one undo step, the observer's animation, when
//! the scene list starts counting. The wall clock in the window; a
//! stopped clock in tests, which moves only when the test moves it, so a
//! test steps time instead of sleeping and a stalled frame on a loaded
//! machine changes nothing.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use web_time::Instant;

/// The wall clock, or a stopped one ([`Clock::stopped`]); clones share it.
#[derive(Debug, Clone, Default)]
pub struct Clock {
    /// The stopped clock's time; `None` for the wall clock.
    stopped: Option<Arc<Mutex<Instant>>>,
}

impl Clock {
    /// The wall clock.
    pub(crate) fn wall() -> Self {
        Self::default()
    }

    /// A clock standing at the present until [`Clock::advance`] moves it.
    pub fn stopped() -> Self {
        Self {
            stopped: Some(Arc::new(Mutex::new(Instant::now()))),
        }
    }

    pub(crate) fn now(&self) -> Instant {
        match &self.stopped {
            Some(time) => *time.lock().unwrap_or_else(PoisonError::into_inner),
            None => Instant::now(),
        }
    }

    /// Moves a stopped clock on by `by`, for every clone of it.
    ///
    /// # Panics
    /// On the wall clock, which no one moves.
    pub fn advance(&self, by: Duration) {
        let time = self
            .stopped
            .as_ref()
            .expect("only a stopped clock is moved by hand");
        *time.lock().unwrap_or_else(PoisonError::into_inner) += by;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stopped_clock_moves_only_when_moved_and_its_clones_with_it() {
        let clock = Clock::stopped();
        let copy = clock.clone();
        let start = clock.now();
        std::thread::sleep(Duration::from_millis(2));
        assert_eq!(copy.now(), start);
        clock.advance(Duration::from_secs(5));
        assert_eq!(copy.now() - start, Duration::from_secs(5));
    }
}
