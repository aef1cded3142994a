//! How far a fetch of a file from the page's site has come: the bytes
//! received of the total the response announced, written by the fetch
//! as chunks arrive and read by the window each frame for its progress
//! bar; and the window's word that it no longer wants the file (a later
//! pick won), which stops the fetch at its next chunk.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// One fetch's progress, shared by the fetch and the window (cloning
/// shares it). Atomics, not a lock: the page's thread must never wait.
#[derive(Debug, Clone, Default)]
pub(crate) struct Transfer(Arc<State>);

#[derive(Debug, Default)]
struct State {
    received: AtomicU64,
    /// The response's `Content-Length`; 0 while unknown.
    total: AtomicU64,
    cancelled: AtomicBool,
}

impl Transfer {
    /// The size the response announced (`None`: it did not say).
    #[cfg_attr(
        not(any(target_family = "wasm", test)),
        expect(dead_code, reason = "the page's fetch calls it")
    )]
    pub(crate) fn set_total(&self, total: Option<u64>) {
        self.0.total.store(total.unwrap_or(0), Ordering::Relaxed);
    }

    /// `bytes` more arrived.
    #[cfg_attr(
        not(any(target_family = "wasm", test)),
        expect(dead_code, reason = "the page's fetch calls it")
    )]
    pub(crate) fn add(&self, bytes: u64) {
        self.0.received.fetch_add(bytes, Ordering::Relaxed);
    }

    pub(crate) fn received(&self) -> u64 {
        self.0.received.load(Ordering::Relaxed)
    }

    /// The announced size, once the response said it.
    pub(crate) fn total(&self) -> Option<u64> {
        Some(self.0.total.load(Ordering::Relaxed)).filter(|&t| t > 0)
    }

    /// The share received, from 0 to 1; `None` while the total is
    /// unknown. At most 1: a compressed response announces fewer bytes
    /// than its body gives.
    pub(crate) fn fraction(&self) -> Option<f32> {
        let total = self.total()?;
        Some((self.received() as f64 / total as f64).min(1.0) as f32)
    }

    /// "212.0 kB of 423.7 kB", or "212.0 kB" while the total is unknown.
    pub(crate) fn describe(&self) -> String {
        match self.total() {
            Some(total) => format!("{} of {}", bytes(self.received()), bytes(total)),
            None => bytes(self.received()),
        }
    }

    /// The window no longer wants the file: the fetch stops at its next
    /// chunk.
    pub(crate) fn cancel(&self) {
        self.0.cancelled.store(true, Ordering::Relaxed);
    }

    #[cfg_attr(
        not(any(target_family = "wasm", test)),
        expect(dead_code, reason = "the page's fetch calls it")
    )]
    pub(crate) fn is_cancelled(&self) -> bool {
        self.0.cancelled.load(Ordering::Relaxed)
    }
}

/// A size in bytes as the scene list says it: "980 B", "423.7 kB",
/// "8.6 MB" (decimal units, as a browser's downloads say them).
pub(crate) fn bytes(n: u64) -> String {
    match n {
        n if n < 1000 => format!("{n} B"),
        n if n < 1_000_000 => format!("{:.1} kB", n as f64 / 1e3),
        n => format!("{:.1} MB", n as f64 / 1e6),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_counts_chunks_against_the_announced_total() {
        let transfer = Transfer::default();
        assert_eq!(transfer.fraction(), None, "no total announced yet");
        assert_eq!(transfer.describe(), "0 B");
        transfer.set_total(Some(423_667));
        let seen_by_window = transfer.clone();
        transfer.add(65_536);
        transfer.add(65_536);
        assert_eq!(seen_by_window.received(), 131_072);
        let fraction = seen_by_window.fraction().unwrap();
        assert!(
            (fraction - 131_072.0 / 423_667.0).abs() < 1e-6,
            "{fraction}"
        );
        assert_eq!(seen_by_window.describe(), "131.1 kB of 423.7 kB");
        transfer.add(292_595);
        assert_eq!(seen_by_window.fraction(), Some(1.0));
    }

    #[test]
    fn a_body_longer_than_announced_is_full_not_more() {
        let transfer = Transfer::default();
        transfer.set_total(Some(100));
        transfer.add(350);
        assert_eq!(transfer.fraction(), Some(1.0));
    }

    #[test]
    fn an_unannounced_size_gives_no_fraction() {
        let transfer = Transfer::default();
        transfer.set_total(None);
        transfer.add(5_000);
        assert_eq!(transfer.fraction(), None);
        assert_eq!(transfer.describe(), "5.0 kB");
    }

    #[test]
    fn cancelling_is_seen_by_every_clone() {
        let transfer = Transfer::default();
        let fetch = transfer.clone();
        assert!(!fetch.is_cancelled());
        transfer.cancel();
        assert!(fetch.is_cancelled());
    }

    #[test]
    fn sizes_read_in_decimal_units() {
        assert_eq!(bytes(980), "980 B");
        assert_eq!(bytes(1000), "1.0 kB");
        assert_eq!(bytes(423_667), "423.7 kB");
        assert_eq!(bytes(8_573_610), "8.6 MB");
    }
}
