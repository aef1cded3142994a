//! A buffered reader that counts what its user consumed: the bytes, for a
//! progress message, and the lines, so an error from a reader that does not
//! say where it stopped (tobj) can still name the line.

use std::io::{BufRead, BufReader, Read};

use super::LoadProgress;

/// Progress is reported after every this many bytes.
const REPORT_EVERY: u64 = 4 << 20;

pub(super) struct Tracked<'p, R> {
    inner: BufReader<R>,
    total: u64,
    bytes: u64,
    newlines: u64,
    /// Whether bytes after the last newline were consumed (a line has
    /// started).
    in_line: bool,
    next_report: u64,
    on_progress: &'p mut dyn FnMut(LoadProgress),
}

impl<'p, R: Read> Tracked<'p, R> {
    pub fn new(inner: R, total: u64, on_progress: &'p mut dyn FnMut(LoadProgress)) -> Self {
        Self {
            inner: BufReader::with_capacity(1 << 16, inner),
            total,
            bytes: 0,
            newlines: 0,
            in_line: false,
            next_report: REPORT_EVERY,
            on_progress,
        }
    }

    /// The 1-based line the last consumed byte belongs to: the line being
    /// read when the user stopped.
    pub fn line(&self) -> u64 {
        self.newlines + u64::from(self.in_line || self.newlines == 0)
    }

    fn count(&mut self, bytes: &[u8]) {
        self.record(Consumed::of(bytes));
    }

    fn record(&mut self, consumed: Option<Consumed>) {
        let Some(consumed) = consumed else {
            return;
        };
        self.newlines += consumed.newlines;
        self.in_line = consumed.ends_in_line;
        self.bytes += consumed.bytes;
        if self.bytes >= self.next_report {
            self.next_report = self.bytes + REPORT_EVERY;
            (self.on_progress)(LoadProgress {
                bytes_read: self.bytes,
                total_bytes: self.total,
            });
        }
    }
}

/// What a run of consumed bytes adds to the counts.
struct Consumed {
    bytes: u64,
    newlines: u64,
    ends_in_line: bool,
}

impl Consumed {
    /// `None` for no bytes (they change nothing).
    fn of(bytes: &[u8]) -> Option<Consumed> {
        let last = *bytes.last()?;
        Some(Consumed {
            bytes: bytes.len() as u64,
            newlines: bytes.iter().filter(|&&b| b == b'\n').count() as u64,
            ends_in_line: last != b'\n',
        })
    }
}

impl<R: Read> Read for Tracked<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count(&buf[..n]);
        Ok(n)
    }
}

impl<R: Read> BufRead for Tracked<'_, R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        // The buffer is already filled (`amount` bytes of it were handed
        // out), so this returns it without reading.
        let consumed = Consumed::of(self.inner.buffer().get(..amount).unwrap_or_default());
        self.record(consumed);
        self.inner.consume(amount);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_counted_as_they_are_consumed() {
        let mut reports = Vec::new();
        let mut on_progress = |p: LoadProgress| reports.push(p);
        let mut reader = Tracked::new(&b"one\ntwo\nthree"[..], 13, &mut on_progress);
        assert_eq!(reader.line(), 1);
        let mut line = String::new();
        reader.read_line(&mut line).unwrap();
        assert_eq!((line.as_str(), reader.line()), ("one\n", 1));
        line.clear();
        reader.read_line(&mut line).unwrap();
        assert_eq!(reader.line(), 2);
        line.clear();
        reader.read_line(&mut line).unwrap();
        assert_eq!((line.as_str(), reader.line()), ("three", 3));
        assert!(reports.is_empty(), "no report below {REPORT_EVERY} bytes");
    }
}
