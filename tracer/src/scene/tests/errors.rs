//! Every kind of bad input gives the right error at the right token.

use std::path::Path;

use super::{parse_err, parse_err_with};
use crate::scene::{Limits, ParseError, ParseErrorKind, parse_scene, parse_scene_file};

fn invalid(what: &'static str, why: &str) -> ParseErrorKind {
    ParseErrorKind::InvalidValue {
        what,
        why: why.to_string(),
    }
}

#[test]
fn display_names_file_line_column_and_command() {
    let error = parse_scene(
        "s 1 2 x 4",
        Some(Path::new("dir/a.nff")),
        &Limits::default(),
    )
    .unwrap_err();
    assert_eq!(
        error.to_string(),
        "dir/a.nff:1:7: in `s`: expected the sphere centre, found `x`"
    );
    let error = parse_scene("\n  frob 1", None, &Limits::default()).unwrap_err();
    assert_eq!(error.to_string(), "<input>:2:3: unknown command `frob`");
}

#[test]
fn unknown_command_and_stray_number() {
    assert_eq!(
        parse_err("s 0 0 0 1\nsphere 1", 2, 1, None),
        ParseErrorKind::UnknownCommand("sphere".into())
    );
    assert_eq!(
        parse_err("s 0 0 0 1 5", 1, 11, None),
        ParseErrorKind::UnexpectedNumber("5".into())
    );
}

#[test]
fn every_command_word_is_dispatched() {
    for word in crate::scene::parse::COMMANDS {
        let kind = parse_scene(word, None, &Limits::default()).map_err(|e| e.kind);
        assert!(
            !matches!(kind, Err(ParseErrorKind::UnknownCommand(_))),
            "{word}"
        );
    }
}

#[test]
fn every_view_field_is_dispatched() {
    for field in crate::scene::VIEW_FIELDS {
        let kind = parse_scene(&format!("v {field}"), None, &Limits::default()).map_err(|e| e.kind);
        assert!(
            !matches!(kind, Err(ParseErrorKind::UnknownViewField(_))),
            "{field}: {kind:?}"
        );
    }
}

#[test]
fn unknown_view_field() {
    assert_eq!(
        parse_err("v\nfrom 0 0 5\n  fov 45", 3, 3, Some("v")),
        ParseErrorKind::UnknownViewField("fov".into())
    );
}

#[test]
fn missing_value_points_just_after_the_last_token() {
    assert_eq!(
        parse_err("s 1 2 3\n", 1, 8, Some("s")),
        ParseErrorKind::MissingValue {
            expected: "the sphere radius"
        }
    );
    assert_eq!(
        parse_err("env  # no name\n", 1, 4, Some("env")),
        ParseErrorKind::MissingValue {
            expected: "the skybox folder name"
        }
    );
}

#[test]
fn not_a_number_and_not_an_integer() {
    assert_eq!(
        parse_err("s 1 2 3\ns 4 5 6 7", 2, 1, Some("s")),
        ParseErrorKind::NotANumber {
            found: "s".into(),
            expected: "the sphere radius"
        }
    );
    assert_eq!(
        parse_err("p 3.5", 1, 3, Some("p")),
        ParseErrorKind::NotAnInteger {
            found: "3.5".into(),
            expected: "the polygon vertex count"
        }
    );
    assert_eq!(
        parse_err("v resolution 512 x", 1, 18, Some("v")),
        ParseErrorKind::NotAnInteger {
            found: "x".into(),
            expected: "the image height"
        }
    );
}

#[test]
fn nan_and_infinity_are_rejected() {
    for word in ["nan", "NaN", "inf", "-inf", "+Infinity", "1e39", "-1e39"] {
        assert_eq!(
            parse_err(&format!("s 0 {word} 0 1"), 1, 5, Some("s")),
            ParseErrorKind::NonFinite {
                found: word.into(),
                expected: "the sphere centre"
            }
        );
    }
    // Counted as numbers by `f`, so the error names the bad value.
    assert!(matches!(
        parse_err("f 1 1 1 1 0 nan 0 1", 1, 13, Some("f")),
        ParseErrorKind::NonFinite { .. }
    ));
}

#[test]
fn wrong_number_counts_for_material_and_lights() {
    let wrong = |expected, found| ParseErrorKind::WrongNumberCount { expected, found };
    assert_eq!(
        parse_err(
            "s 0 0 0 1\n f 1 1 1 1 1 1 1 1 1\ns 0 0 0 1",
            2,
            2,
            Some("f")
        ),
        wrong("8 (NFF) or 11 (P3F)", 9)
    );
    assert_eq!(parse_err("l 1 2 3 4", 1, 1, Some("l")), wrong("3 or 6", 4));
    assert_eq!(
        parse_err("al 1 2 3 4 5 6 7", 1, 1, Some("al")),
        wrong("8 or 11", 7)
    );
}

#[test]
fn invalid_geometry() {
    assert_eq!(
        parse_err("s 0 0 0 0", 1, 9, Some("s")),
        invalid("sphere radius", "must not be zero")
    );
    assert_eq!(
        parse_err("p 2 0 0 0 1 1 1", 1, 3, Some("p")),
        invalid(
            "polygon vertex count",
            "a polygon needs at least 3 vertices, found 2"
        )
    );
    assert_eq!(
        parse_err("pp -3", 1, 4, Some("pp")),
        invalid("patch vertex count", "must not be negative, found -3")
    );
    assert_eq!(
        parse_err("pl 0 0 0 1 1 1 2 2 2", 1, 1, Some("pl")),
        invalid("plane", "its three points are collinear")
    );
    assert_eq!(
        parse_err("c 1 1 1 1 1 1 1 2", 1, 1, Some("c")),
        invalid("cone", "base and apex are the same point")
    );
    assert_eq!(
        parse_err("c 0 0 0 1 0 0 1 -1", 1, 17, Some("c")),
        invalid(
            "cone radius",
            "only both radii together may be negative (an inside-only cone)"
        )
    );
    assert_eq!(
        parse_err("box 0 0 0 1 0 1", 1, 1, Some("box")),
        invalid("box", "it has zero thickness along an axis")
    );
    assert_eq!(
        parse_err("al 0 0 0 0 0 0 1 1", 1, 1, Some("al")),
        invalid("area light", "it faces its own centre")
    );
    assert_eq!(
        parse_err("al 0 1 0 0 0 0 1 -1", 1, 18, Some("al")),
        invalid("area light size", "must be greater than 0, found -1")
    );
}

#[test]
fn invalid_mesh_indices() {
    let mesh = "mesh 3 1 0 0 0 1 0 0 0 1 0\n";
    assert_eq!(
        parse_err(&format!("{mesh}1 0 2"), 2, 3, Some("mesh")),
        invalid(
            "mesh index",
            "indices start at 1 (or -1 for the last vertex), found 0"
        )
    );
    assert_eq!(
        parse_err(&format!("{mesh}1 2 4"), 2, 5, Some("mesh")),
        invalid("mesh index", "4 is out of range for 3 vertices")
    );
    assert_eq!(
        parse_err(&format!("{mesh}-4 1 2"), 2, 1, Some("mesh")),
        invalid("mesh index", "-4 is out of range for 3 vertices")
    );
}

#[test]
fn invalid_settings() {
    assert_eq!(
        parse_err("accel 3", 1, 7, Some("accel")),
        invalid(
            "acceleration structure",
            "must be 0 (none), 1 (grid) or 2 (BVH), found 3"
        )
    );
    assert_eq!(
        parse_err("spp -1", 1, 5, Some("spp")),
        invalid("samples per pixel", "must not be negative, found -1")
    );
    assert_eq!(
        parse_err("spp 65", 1, 5, Some("spp")),
        ParseErrorKind::AboveLimit {
            what: "samples per pixel side",
            found: "65".into(),
            limit: 64
        }
    );
    assert_eq!(
        parse_err("spp 4\nadaptive 1.5", 2, 10, Some("adaptive")),
        invalid("noise threshold", "must lie in 0..1, found 1.5")
    );
    assert_eq!(
        parse_err("adaptive -0.01", 1, 10, Some("adaptive")),
        invalid("noise threshold", "must lie in 0..1, found -0.01")
    );
}

#[test]
fn invalid_camera_fields() {
    let cases = [
        ("v angle 0", 9, "field of view angle"),
        ("v angle 180", 9, "field of view angle"),
        ("v resolution 0 5", 14, "resolution"),
        ("v aperture -1", 12, "aperture"),
        ("v focal 0", 9, "focal distance"),
        ("v hither -0.5", 10, "hither distance"),
    ];
    for (text, column, field) in cases {
        let kind = parse_err(text, 1, column, Some("v"));
        assert!(
            matches!(kind, ParseErrorKind::InvalidValue { what, .. } if what == field),
            "{text}: {kind:?}"
        );
    }
    assert_eq!(
        parse_err("v resolution 512 16385", 1, 18, Some("v")),
        ParseErrorKind::AboveLimit {
            what: "resolution",
            found: "16385".into(),
            limit: 16384
        }
    );
    assert!(matches!(
        parse_err("v resolution 16384 16384", 1, 14, Some("v")),
        ParseErrorKind::AboveLimit {
            what: "pixel count",
            ..
        }
    ));
}

#[test]
fn degenerate_cameras() {
    assert_eq!(
        parse_err("v from 1 2 3\n at 1 2 3 up 0 1 0", 2, 2, Some("v")),
        ParseErrorKind::DegenerateCamera("`from` and `at` are the same point")
    );
    assert_eq!(
        parse_err("v from 0 0 0 at 0 0 -1 up 0 0 3", 1, 24, Some("v")),
        ParseErrorKind::DegenerateCamera("`up` is parallel to the view direction")
    );
    assert_eq!(
        parse_err("s 0 0 0 1\nv from 0 5 0 at 0 0 0", 2, 1, Some("v")),
        ParseErrorKind::DegenerateCamera("`up` is parallel to the view direction")
    );
}

#[test]
fn huge_counts_fail_fast_without_allocating() {
    assert_eq!(
        parse_err("mesh 4000000000 1", 1, 6, Some("mesh")),
        ParseErrorKind::AboveLimit {
            what: "mesh vertex count",
            found: "4000000000".into(),
            limit: 10_000_000
        }
    );
    let unlimited = Limits {
        max_mesh_vertices: usize::MAX,
        max_mesh_triangles: usize::MAX,
        max_polygon_vertices: usize::MAX,
        ..Limits::default()
    };
    assert_eq!(
        parse_err_with("mesh 4000000000 1", &unlimited, 1, 6, Some("mesh")),
        ParseErrorKind::NotEnoughInput {
            what: "mesh vertex count",
            count: 4_000_000_000,
            needed: 12_000_000_000,
            remaining: 0
        }
    );
    assert!(matches!(
        parse_err_with(
            "mesh 3 99999999999999999999 0 0 0 1 0 0 0 1 0",
            &unlimited,
            1,
            8,
            Some("mesh")
        ),
        ParseErrorKind::AboveLimit { .. }
    ));
    assert!(matches!(
        parse_err_with("pp 100000000000 1 2 3", &unlimited, 1, 4, Some("pp")),
        ParseErrorKind::NotEnoughInput { .. }
    ));
}

#[test]
fn object_light_material_and_size_limits() {
    let small = Limits {
        max_objects: 2,
        max_lights: 1,
        max_materials: 1,
        max_file_bytes: 100,
        ..Limits::default()
    };
    assert!(matches!(
        parse_err_with("s 0 0 0 1 s 0 0 0 1\ns 0 0 0 1", &small, 2, 1, Some("s")),
        ParseErrorKind::AboveLimit {
            what: "object count",
            ..
        }
    ));
    assert!(matches!(
        parse_err_with("l 0 0 0 l 0 0 0", &small, 1, 9, Some("l")),
        ParseErrorKind::AboveLimit {
            what: "light count",
            ..
        }
    ));
    // The default material counts too.
    assert!(matches!(
        parse_err_with("s 0 0 0 1 f 1 1 1 1 0 1 0 1", &small, 1, 11, Some("f")),
        ParseErrorKind::AboveLimit {
            what: "material count",
            ..
        }
    ));
    let long = format!("{}\ns 0 0 0 1", "#".repeat(100));
    assert!(matches!(
        parse_err_with(&long, &small, 0, 0, None),
        ParseErrorKind::AboveLimit {
            what: "size in bytes",
            ..
        }
    ));
}

#[test]
fn io_errors_name_the_file() {
    let path = Path::new("/nonexistent/whitted/scene.p3f");
    let error: ParseError = parse_scene_file(path, &Limits::default()).unwrap_err();
    assert_eq!((error.line, error.column), (0, 0));
    assert!(matches!(error.kind, ParseErrorKind::Io(_)));
    assert!(
        error
            .to_string()
            .starts_with("/nonexistent/whitted/scene.p3f:0:0: cannot read the scene:")
    );
}
