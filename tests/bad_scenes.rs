//! The bad-scene corpus: every file in `tests/bad_scenes/` must make
//! `workbench render` fail with the exact `file:line:column` and message
//! listed in `tests/bad_scenes/expected.txt`, and write no image. A few
//! limits that need huge files or odd settings are checked through the
//! library or the command line's overrides instead.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use tracer::scene::{Limits, ParseErrorKind, parse_scene, parse_scene_file};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/bad_scenes")
}

/// A fresh folder for one test's outputs.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("workbench-bad-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `workbench render` from the corpus folder, so errors name the file
/// exactly as listed in the manifest.
fn render(scene: &str, out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_workbench"))
        .current_dir(corpus())
        .args(["render", scene, "-o"])
        .arg(out)
        .args(extra)
        .output()
        .expect("the workbench binary runs")
}

struct Expected {
    file: String,
    location: String,
    fragment: String,
}

fn manifest() -> Vec<Expected> {
    let text = std::fs::read_to_string(corpus().join("expected.txt")).unwrap();
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|line| {
            let (file, rest) = line.split_once(char::is_whitespace).unwrap();
            let (location, fragment) = rest.trim_start().split_once(char::is_whitespace).unwrap();
            Expected {
                file: file.to_string(),
                location: location.to_string(),
                fragment: fragment.trim().to_string(),
            }
        })
        .collect()
}

#[test]
fn every_bad_scene_fails_with_its_exact_position_and_message() {
    let entries = manifest();
    assert!(entries.len() >= 20, "only {} entries", entries.len());
    let out_dir = scratch("corpus");
    let mut failures = Vec::new();
    for e in &entries {
        let out = out_dir.join(format!("{}.png", e.file));
        let run = render(&e.file, &out, &["--width", "8", "--height", "8"]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        let at = format!("{}:{}: ", e.file, e.location);
        let problems = [
            (run.status.success(), "exited with success"),
            (!stderr.contains(&at), "does not name the position"),
            (!stderr.contains(&e.fragment), "lacks the message"),
            (stderr.contains("panicked"), "panicked"),
            (out.exists(), "wrote an image"),
        ];
        for (bad, why) in problems {
            if bad {
                failures.push(format!(
                    "{} ({at}{}): {why}\n  stderr: {stderr}",
                    e.file, e.fragment
                ));
            }
        }
    }
    // Nothing half-written either: no temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&out_dir).unwrap().collect();
    assert!(leftovers.is_empty(), "files left in {}", out_dir.display());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_manifest_lists_every_file_of_the_corpus() {
    let listed: Vec<String> = manifest().into_iter().map(|e| e.file).collect();
    for entry in std::fs::read_dir(corpus()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name != "expected.txt" {
            assert!(listed.contains(&name), "{name} has no line in expected.txt");
        }
    }
}

#[test]
fn a_file_above_the_size_limit_is_refused_before_parsing() {
    let dir = scratch("size");
    let path = dir.join("big.p3f");
    std::fs::write(&path, "s 0 0 0 1\n".repeat(100)).unwrap();
    let limits = Limits {
        max_file_bytes: 500,
        ..Limits::default()
    };
    let err = parse_scene_file(&path, &limits).unwrap_err();
    assert_eq!((err.line, err.column), (0, 0));
    assert!(
        matches!(err.kind, ParseErrorKind::AboveLimit { .. }),
        "{err}"
    );
    assert!(
        err.to_string().contains("exceeds the limit of 500"),
        "{err}"
    );
}

#[test]
fn object_light_and_material_counts_are_bounded() {
    let limits = Limits {
        max_objects: 2,
        max_lights: 1,
        max_materials: 1,
        ..Limits::default()
    };
    let err = parse_scene("s 0 0 0 1\ns 0 0 0 1\ns 0 0 0 1\n", None, &limits).unwrap_err();
    assert_eq!((err.line, err.column), (3, 1), "{err}");
    assert!(
        err.to_string()
            .contains("object count 3 exceeds the limit of 2")
    );
    let err = parse_scene("l 0 0 0\nl 1 1 1\n", None, &limits).unwrap_err();
    assert_eq!((err.line, err.column), (2, 1), "{err}");
    let err = parse_scene("f 1 1 1 1 0 1 0 0\nf 1 1 1 1 0 1 0 0\n", None, &limits).unwrap_err();
    assert_eq!((err.line, err.column), (2, 1), "{err}");
}

#[test]
fn a_folder_or_missing_file_is_an_error_not_a_panic() {
    let dir = scratch("folder");
    let out = dir.join("out.png");
    for scene in [dir.to_str().unwrap(), "/nonexistent/scene.p3f"] {
        let run = render(scene, &out, &[]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{scene}");
        assert!(
            stderr.contains(&format!("{scene}:0:0: cannot read the scene")),
            "{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!out.exists());
    }
}

#[test]
fn out_of_range_overrides_are_refused_by_name() {
    let dir = scratch("settings");
    let out = dir.join("out.png");
    let cases: [(&[&str], &str); 6] = [
        (&["--width", "0"], "width = 0 is out of range"),
        (&["--width", "100000"], "width = 100000 is out of range"),
        (
            &["--width", "16384", "--height", "16384"],
            "width x height = 268435456",
        ),
        (&["--spp", "65"], "samples = 65 is out of range"),
        (&["--depth", "1000"], "depth = 1000 is out of range"),
        (&["--ambient", "NaN"], "ambient = NaN is out of range"),
    ];
    // A good scene, so that only the override is wrong.
    let scene = dir.join("good.p3f");
    std::fs::write(&scene, "v resolution 8 8\ns 0 0 0 1\n").unwrap();
    for (args, message) in cases {
        let run = render(scene.to_str().unwrap(), &out, args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{args:?}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!out.exists(), "{args:?}");
    }
}
