//! Random token streams never make the parser panic, and whatever it
//! accepts the writer reproduces exactly.

use proptest::prelude::*;

use super::assert_round_trip;
use crate::scene::{Limits, parse_scene};

const WORDS: &[&str] = &[
    "v",
    "b",
    "bclr",
    "env",
    "l",
    "al",
    "f",
    "s",
    "pl",
    "p",
    "pp",
    "c",
    "box",
    "mesh",
    "accel",
    "spp",
    "from",
    "at",
    "up",
    "angle",
    "hither",
    "resolution",
    "aperture",
    "focal",
    "#",
    "#x",
    "nan",
    "inf",
    "-infinity",
    "1e39",
    "x",
    "é",
    "-",
    "+",
    ".",
    "1e",
    "0x10",
];

fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(WORDS).prop_map(str::to_string),
        4 => (-4i64..8).prop_map(|n| n.to_string()),
        2 => any::<f32>().prop_map(|x| x.to_string()),
        1 => any::<i64>().prop_map(|n| n.to_string()),
        1 => "[a-z0-9.#+-]{1,5}",
    ]
}

fn separator() -> impl Strategy<Value = &'static str> {
    prop::sample::select(&[" ", "\n", "\t", "\r\n", "  "][..])
}

fn small_limits() -> Limits {
    Limits {
        max_polygon_vertices: 64,
        max_mesh_vertices: 64,
        max_mesh_triangles: 64,
        ..Limits::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn token_streams_never_panic_and_accepted_ones_round_trip(
        tokens in prop::collection::vec((token(), separator()), 0..60)
    ) {
        let text: String = tokens.iter().flat_map(|(t, s)| [t.as_str(), s]).collect();
        if let Ok(scene) = parse_scene(&text, None, &small_limits()) {
            assert_round_trip(&scene);
        }
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        let _ = parse_scene(&text, None, &small_limits());
    }
}
