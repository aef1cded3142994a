//! The page's HTML pieces: escaping, images inlined as base64 PNG, tables,
//! and the page around the sections (its style sheet, for screen and print).
//! Everything is inline so the file opens anywhere without a network.

use std::fmt::Write as _;

use anyhow::{Context, Result};
use image::RgbImage;

/// `text` safe inside HTML text and attribute values.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Standard base64 (RFC 4648, with padding): what a `data:` URI carries.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `image` as an `<img>` with its PNG inline, shown `width` CSS pixels
/// wide (pixelated when magnified, so pixels stay pixels).
pub(crate) fn image(image: &RgbImage, alt: &str, width: u32) -> Result<String> {
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .context("cannot encode an image of the report")?;
    let (w, h) = image.dimensions();
    let shown = width.max(1);
    let height = (u64::from(h) * u64::from(shown) / u64::from(w.max(1))).max(1);
    Ok(format!(
        "<img src=\"data:image/png;base64,{}\" alt=\"{}\" width=\"{shown}\" height=\"{height}\">",
        base64(&png),
        escape(alt)
    ))
}

/// A figure: `body` (an image or a chart) with a caption.
pub(crate) fn figure(body: &str, caption: &str) -> String {
    format!(
        "<figure>{body}<figcaption>{}</figcaption></figure>\n",
        escape(caption)
    )
}

/// Name and value pairs as a table without a header (escaped here).
pub(crate) fn facts(rows: &[(&str, String)]) -> String {
    let mut out = String::from("<table class=\"facts\">\n");
    for (name, value) in rows {
        let _ = writeln!(
            out,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(name),
            escape(value)
        );
    }
    out.push_str("</table>\n");
    out
}

/// A table with a header row; cells are HTML already (escape text first).
/// `row_ids` names each row (`data-row`) so scripts and tests find them.
pub(crate) fn table(class: &str, headers: &[&str], rows: &[(String, Vec<String>)]) -> String {
    let mut out = format!("<table class=\"{class}\">\n<thead><tr>");
    for h in headers {
        let _ = write!(out, "<th>{}</th>", escape(h));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for (id, cells) in rows {
        let _ = write!(out, "<tr data-row=\"{}\">", escape(id));
        for c in cells {
            let _ = write!(out, "<td>{c}</td>");
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody>\n</table>\n");
    out
}

/// A section: `<section id=...>` with its heading.
pub(crate) fn titled_section(id: &str, title: &str, body: &str) -> String {
    format!(
        "<section id=\"{id}\">\n<h2>{}</h2>\n{body}</section>\n",
        escape(title)
    )
}

/// The whole page: `title`, then `sections` in order.
pub(crate) fn page(title: &str, sections: &[String]) -> String {
    let mut out =
        String::from("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    let _ = writeln!(out, "<title>{}</title>", escape(title));
    out.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    // The page may fetch nothing: its images are data: URIs, its style inline.
    out.push_str(
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; \
         img-src data:; style-src 'unsafe-inline'\">\n",
    );
    let _ = writeln!(out, "<style>{STYLE}</style>\n</head>\n<body>");
    let _ = writeln!(out, "<h1>{}</h1>", escape(title));
    for s in sections {
        out.push_str(s);
    }
    out.push_str("</body>\n</html>\n");
    out
}

/// Readable on screen and on paper: images never split across pages.
const STYLE: &str = "
body { font-family: system-ui, sans-serif; max-width: 1100px; margin: 1.5em auto; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.7em; margin-bottom: 0.2em; }
h2 { border-bottom: 2px solid #ccc; padding-bottom: 0.2em; margin-top: 1.6em; }
h3 { margin-bottom: 0.3em; }
p.how { color: #555; font-size: 0.9em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: right; }
th { background: #f2f2f2; }
td:first-child, th:first-child { text-align: left; }
table.facts td, table.facts th { text-align: left; }
.facts-row { display: flex; flex-wrap: wrap; gap: 0 2em; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
figure { margin: 0.4em 0; break-inside: avoid; }
figcaption { font-size: 0.85em; color: #444; max-width: 380px; }
img { image-rendering: pixelated; border: 1px solid #ddd; }
pre { background: #f7f7f7; padding: 0.8em; white-space: pre-wrap; font-size: 0.8em; }
svg text { font-family: system-ui, sans-serif; }
@media print {
  body { max-width: none; margin: 0; }
  section { break-before: page; }
  section:first-of-type { break-before: auto; }
  table, figure, svg { break-inside: avoid; }
}
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_rfc_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded, "{plain}");
        }
        assert_eq!(base64(&[0xfb, 0xff, 0xfe]), "+//+");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(
            escape("a<b & \"c\" 'd'>"),
            "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;"
        );
    }
}
