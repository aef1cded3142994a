//! Splits scene text into whitespace-separated tokens with line and column.
//! Commands may spill over lines, so the parser sees a token stream, never
//! lines. A token that starts with `#` starts a comment to the end of line.

/// A 1-based line and column (counted in characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Pos {
    pub line: u32,
    pub column: u32,
}

/// One word of the input and where it starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Token<'a> {
    pub text: &'a str,
    pub pos: Pos,
}

/// An iterator over the tokens of a text. It is `Copy`, so the parser looks
/// ahead by copying it, without buffering tokens.
#[derive(Debug, Clone, Copy)]
pub(super) struct Lexer<'a> {
    text: &'a str,
    offset: usize,
    pos: Pos,
}

impl<'a> Lexer<'a> {
    pub fn new(text: &'a str) -> Self {
        Self {
            text,
            offset: 0,
            pos: Pos { line: 1, column: 1 },
        }
    }

    /// Where the lexer stands: after the input has run out, the end of it.
    pub fn pos(&self) -> Pos {
        self.pos
    }

    fn peek_byte(&self) -> Option<u8> {
        self.text.as_bytes().get(self.offset).copied()
    }

    /// Moves past the next `n` bytes, counting their lines and characters
    /// in bulk (a byte at a time, this was the largest part of parsing a
    /// 250 kB mesh).
    fn advance(&mut self, n: usize) {
        let run = &self.text.as_bytes()[self.offset..self.offset + n];
        self.offset += n;
        let chars = |bytes: &[u8]| bytes.iter().filter(|&&b| b & 0xC0 != 0x80).count() as u32;
        match run.iter().rposition(|&b| b == b'\n') {
            Some(last) => {
                let lines = run.iter().filter(|&&b| b == b'\n').count() as u32;
                self.pos.line = self.pos.line.saturating_add(lines);
                self.pos.column = chars(&run[last + 1..]).saturating_add(1);
            }
            None => self.pos.column = self.pos.column.saturating_add(chars(run)),
        }
    }

    fn skip_while(&mut self, keep_going: impl Fn(u8) -> bool) {
        let rest = &self.text.as_bytes()[self.offset..];
        let n = rest
            .iter()
            .position(|&b| !keep_going(b))
            .unwrap_or(rest.len());
        self.advance(n);
    }
}

impl<'a> Iterator for Lexer<'a> {
    type Item = Token<'a>;

    fn next(&mut self) -> Option<Token<'a>> {
        loop {
            self.skip_while(|b| b.is_ascii_whitespace());
            match self.peek_byte()? {
                b'#' => self.skip_while(|b| b != b'\n'),
                _ => break,
            }
        }
        let start = self.offset;
        let pos = self.pos;
        self.skip_while(|b| !b.is_ascii_whitespace());
        // Token boundaries are ASCII bytes, hence always char boundaries.
        let text = self.text.get(start..self.offset).unwrap_or_default();
        Some(Token { text, pos })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tokens(text: &str) -> Vec<(&str, u32, u32)> {
        Lexer::new(text)
            .map(|t| (t.text, t.pos.line, t.pos.column))
            .collect()
    }

    #[test]
    fn splits_on_any_whitespace_and_skips_comments() {
        assert_eq!(
            tokens("s 1\t2\r\n#c x y\n  é 3 #gpl 4\n5"),
            vec![
                ("s", 1, 1),
                ("1", 1, 3),
                ("2", 1, 5),
                ("é", 3, 3),
                ("3", 3, 5),
                ("5", 4, 1)
            ]
        );
    }

    #[test]
    fn columns_count_characters_and_end_position_is_known() {
        let mut lexer = Lexer::new("ãé x\n");
        assert_eq!(lexer.next().map(|t| t.text), Some("ãé"));
        assert_eq!(
            lexer.next().map(|t| t.pos),
            Some(Pos { line: 1, column: 4 })
        );
        assert_eq!(lexer.next(), None);
        assert_eq!(lexer.pos(), Pos { line: 2, column: 1 });
    }
}
