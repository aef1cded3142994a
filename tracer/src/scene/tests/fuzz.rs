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

/// The numbers each command or `v` label takes (`p`, `pp` and `mesh`
/// get their counts too), so a phrase is often valid.
fn arity(word: &str) -> &'static [usize] {
    match word {
        "b" | "bclr" | "from" | "at" | "up" => &[3],
        "l" => &[3, 6],
        "al" | "f" => &[8, 11],
        "s" => &[4],
        "pl" => &[9],
        "p" => &[10],
        "pp" => &[19],
        "c" => &[8],
        "box" => &[6],
        "mesh" => &[13],
        "resolution" => &[2],
        "accel" | "spp" | "env" | "angle" | "hither" | "aperture" | "focal" => &[1],
        _ => &[0],
    }
}

/// A command or `v` label and mostly the right count of small numbers
/// (the counts of `p`, `pp` and `mesh` included), so accepted scenes and
/// the round trip get exercised too.
fn phrase() -> impl Strategy<Value = String> {
    let number = prop_oneof![
        3 => (1i32..4).prop_map(|n| n.to_string()),
        1 => (-3i32..5).prop_map(|n| n.to_string()),
        1 => (-10.0f32..10.0).prop_map(|x| x.to_string()),
    ];
    let word = prop::sample::select(&WORDS[..24]);
    (word, any::<prop::sample::Index>(), 0..13usize)
        .prop_flat_map(move |(word, pick, random)| {
            let counts = arity(word);
            let exact = counts[pick.index(counts.len())];
            let count = prop_oneof![3 => Just(exact), 1 => Just(random)];
            (
                Just(word),
                count.prop_flat_map({
                    let number = number.clone();
                    move |n| prop::collection::vec(number.clone(), n)
                }),
            )
        })
        .prop_map(|(word, mut numbers)| {
            // Counts that announce what follows.
            let head = match word {
                "p" => Some("3"),
                "pp" => Some("3"),
                "mesh" => Some("3 1"),
                _ => None,
            };
            if let (Some(head), false) = (head, numbers.is_empty()) {
                numbers[0] = head.to_string();
            }
            // A `v` label needs its `v` first.
            let v = if WORDS[..16].contains(&word) {
                ""
            } else {
                "v "
            };
            format!("{v}{word} {}", numbers.join(" "))
        })
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
    fn command_phrases_never_panic_and_accepted_ones_round_trip(
        phrases in prop::collection::vec((phrase(), separator()), 0..12)
    ) {
        let text: String = phrases.iter().flat_map(|(p, s)| [p.as_str(), s]).collect();
        if let Ok(scene) = parse_scene(&text, None, &small_limits()) {
            assert_round_trip(&scene);
        }
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        let _ = parse_scene(&text, None, &small_limits());
    }
}
