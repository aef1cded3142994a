//! Splits scene text into whitespace-separated tokens with line and column.
