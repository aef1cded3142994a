//! Any bytes, read as the workbench reads a file (lossy UTF-8), must give a
//! scene or a parse error, never a panic, hang or runaway allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tracer::scene::{Limits, parse_scene};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = parse_scene(&text, None, &Limits::default());
});
