//! `workbench report` end to end: quick reports of two scenes checked for
//! structure (every section, every image decodes, the timing table's rows)
//! and for numbers (the page's equal the report's JSON, whose shape and
//! counts are `bench --matrix --format json`'s), the course's section on
//! `balls_medium`, and Ctrl-C writing nothing.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support::scenes::{RED_SPHERE_ON_A_BOX, spheres_on_a_floor};
use crate::support::{scratch, workbench_fails, workbench_ok, write};

/// The page's sections, in order.
const SECTIONS: [&str; 7] = [
    "run",
    "whitted",
    "sampling",
    "acceleration",
    "statistics",
    "pixel",
    "course",
];

/// Writes a quick report of `scene` (two runs, one thread) with its JSON;
/// returns the page and the JSON rows.
fn quick_report(dir: &Path, scene: &Path) -> (String, Vec<Value>) {
    let page = dir.join("report.html");
    let json = dir.join("times.json");
    let said = workbench_ok(&[
        "report",
        scene.to_str().unwrap(),
        "-o",
        page.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
        "--quick",
        "--runs",
        "2",
        "--threads",
        "1",
    ]);
    assert!(said.contains("wrote"), "{said}");
    let rows: Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
    assert!(
        rows.as_array().unwrap().iter().all(|r| r["runs"] == 2),
        "--runs 2"
    );
    (
        std::fs::read_to_string(page).unwrap(),
        rows.as_array().unwrap().clone(),
    )
}

/// Standard base64 decoded (the page's `data:` URIs).
fn base64_decode(text: &str) -> Vec<u8> {
    let value = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: {}", c as char),
        }
    };
    let mut out = Vec::new();
    for chunk in text.as_bytes().chunks(4) {
        let data: Vec<u8> = chunk.iter().copied().filter(|&c| c != b'=').collect();
        let n = data
            .iter()
            .enumerate()
            .fold(0, |n, (i, &c)| n | value(c) << (18 - 6 * i));
        out.extend((0..data.len().saturating_sub(1)).map(|i| (n >> (16 - 8 * i)) as u8));
    }
    out
}

/// Every inline PNG of the page, decoded.
fn images(page: &str) -> Vec<image::DynamicImage> {
    page.split("src=\"data:image/png;base64,")
        .skip(1)
        .map(|rest| {
            let data = &rest[..rest.find('"').unwrap()];
            image::load_from_memory(&base64_decode(data)).expect("an inline image decodes")
        })
        .collect()
}

/// The table of class `class`: its headers and its rows (`data-row`, cells).
fn table(page: &str, class: &str) -> (Vec<String>, Vec<(String, Vec<String>)>) {
    let start = page
        .find(&format!("<table class=\"{class}\">"))
        .unwrap_or_else(|| panic!("no {class} table"));
    let html = &page[start..start + page[start..].find("</table>").unwrap()];
    let between = |text: &str, open: &str, close: &str| -> Vec<String> {
        text.split(open)
            .skip(1)
            .map(|s| s[..s.find(close).unwrap()].to_string())
            .collect()
    };
    let headers = between(html, "<th>", "</th>");
    let rows = html
        .split("<tr data-row=\"")
        .skip(1)
        .map(|row| {
            let id = row[..row.find('"').unwrap()].to_string();
            (id, between(row, "<td>", "</td>"))
        })
        .collect();
    (headers, rows)
}

/// The `bench --matrix` row's name (its images' file stem).
fn stem(row: &Value) -> String {
    let mut stem = row["accel"].as_str().unwrap().to_string();
    if row["soft_shadows"].as_bool().unwrap() {
        stem += "_soft";
    }
    if row["antialiasing"].as_bool().unwrap() {
        stem += &format!("_aa{}", row["n"]);
    }
    if row["depth_of_field"].as_bool().unwrap() {
        stem += "_dof";
    }
    stem
}

fn ms(seconds: &Value) -> String {
    format!("{:.1}", seconds.as_f64().unwrap() * 1e3)
}

/// Every section, every image, the 12 + 6 rows, and each row's numbers
/// equal to the JSON's.
fn check_page(page: &str, rows: &[Value]) {
    let mut at = 0;
    for id in SECTIONS {
        let found = page[at..]
            .find(&format!("<section id=\"{id}\">"))
            .unwrap_or_else(|| panic!("section {id} missing or out of order"));
        at += found;
    }
    assert!(only_svg_namespace(page), "no address outside the file");
    let decoded = images(page);
    // Whitted (3), sampling (7 + 2 crops), tests per pixel (3), the figure.
    assert!(decoded.len() >= 15, "{} images", decoded.len());
    assert!(decoded.iter().all(|i| i.width() > 0 && i.height() > 0));

    // Adaptive sampling beside uniform: a point per threshold of the
    // quick report, each between the minimum (4) and the reference's 36
    // samples a pixel, strictly fewer as the threshold grows.
    assert!(page.contains("PSNR against frame time"));
    let (headers, adaptive) = table(page, "adaptive");
    let cell = |cells: &[String], name: &str| -> f64 {
        cells[headers.iter().position(|h| h == name).unwrap()]
            .parse()
            .unwrap()
    };
    let ids: Vec<&str> = adaptive.iter().map(|(id, _)| id.as_str()).collect();
    assert_eq!(ids, ["t0.01", "t0.02", "t0.04"]);
    let means: Vec<f64> = adaptive
        .iter()
        .map(|(_, cells)| cell(cells, "samples/px"))
        .collect();
    // Strictly fewer, every point above the floor: a report that ignored
    // the threshold (or stopped every pixel at 4) gives equal means.
    assert!(means.windows(2).all(|w| w[0] > w[1]), "{means:?}");
    assert!(means.iter().all(|&m| m > 4.0), "{means:?}");
    for (id, cells) in &adaptive {
        assert!(cell(cells, "samples/px") >= 4.0, "{id}");
        assert!(cell(cells, "most/px") <= 36.0, "{id}");
        assert!(cell(cells, "PSNR dB").is_finite(), "{id}");
    }

    let (headers, table_rows) = table(page, "timing");
    let column = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let ids: Vec<&str> = table_rows.iter().map(|(id, _)| id.as_str()).collect();
    let course: Vec<&str> = ids
        .iter()
        .copied()
        .filter(|id| id.starts_with("none") || id.starts_with("grid"))
        .collect();
    assert_eq!(course.len(), 12, "the course's twelve rows: {ids:?}");
    assert_eq!(ids.len(), 18, "and a BVH row for each: {ids:?}");
    for (none, bvh) in ids[..6].iter().zip(&ids[12..]) {
        assert_eq!(none.replacen("none", "bvh", 1), **bvh);
    }
    assert_eq!(rows.len(), table_rows.len());
    for (row, (id, cells)) in rows.iter().zip(&table_rows) {
        assert_eq!(&stem(row), id);
        assert_eq!(
            cells[column("frame ms")],
            ms(&row["median_seconds"]),
            "{id}"
        );
        assert_eq!(
            cells[column("min..max ms")],
            format!("{}..{}", ms(&row["min_seconds"]), ms(&row["max_seconds"])),
            "{id}"
        );
        assert_eq!(cells[column("MAD ms")], ms(&row["mad_seconds"]), "{id}");
        assert_eq!(cells[column("runs")], row["runs"].to_string(), "{id}");
        assert_eq!(cells[column("rays")], row["rays"].to_string(), "{id}");
        assert_eq!(
            cells[column("samples/px")],
            row["samples_per_pixel"].to_string(),
            "{id}"
        );
    }
}

/// The only address a page may hold is SVG's namespace name, which is
/// never fetched.
fn only_svg_namespace(page: &str) -> bool {
    !page
        .replace("xmlns=\"http://www.w3.org/2000/svg\"", "")
        .contains("://")
}

/// `bench --matrix --format json` of `scene`, one run on one thread.
fn bench_matrix(scene: &Path) -> Vec<Value> {
    let out = workbench_ok(&[
        "bench",
        scene.to_str().unwrap(),
        "--matrix",
        "--runs",
        "1",
        "--threads",
        "1",
        "--format",
        "json",
    ]);
    serde_json::from_str::<Value>(&out)
        .unwrap()
        .as_array()
        .unwrap()
        .clone()
}

/// The report's JSON has bench's shape, and its counts (which do not
/// depend on timing) are bench's: the report measured what bench measures.
fn check_against_bench(scene: &Path, rows: &[Value]) {
    let bench = bench_matrix(scene);
    assert_eq!(bench.len(), rows.len());
    let timing = |key: &str| key.contains("seconds") || key == "rays_per_second" || key == "runs";
    for (ours, theirs) in rows.iter().zip(&bench) {
        let (ours, theirs) = (ours.as_object().unwrap(), theirs.as_object().unwrap());
        let keys = |o: &serde_json::Map<String, Value>| o.keys().cloned().collect::<Vec<_>>();
        assert_eq!(keys(ours), keys(theirs), "the same fields");
        for (key, value) in ours {
            if !timing(key) {
                assert_eq!(value, &theirs[key], "{key} of {}", ours["label"]);
            }
        }
    }
}

fn scenes(dir: &Path) -> [PathBuf; 2] {
    [
        write(dir, "spheres.p3f", &spheres_on_a_floor(48, 32, "", "")),
        write(dir, "box.p3f", RED_SPHERE_ON_A_BOX),
    ]
}

#[test]
fn quick_reports_of_two_scenes_have_every_section_and_the_json_numbers() {
    let dir = scratch("report-two-scenes");
    // The spheres' scene has a glass sphere, the box's nothing that refracts.
    for (scene, refracts) in scenes(&dir).into_iter().zip([true, false]) {
        let (page, rows) = quick_report(&dir, &scene);
        check_page(&page, &rows);
        let (_, whitted) = table(&page, "whitted");
        let ids: Vec<&str> = whitted.iter().map(|(id, _)| id.as_str()).collect();
        let expected = if refracts {
            vec!["local", "depth0", "depth1", "depth4-opaque", "depth4"]
        } else {
            vec!["local", "depth0", "depth1", "depth4"]
        };
        assert_eq!(ids, expected, "{}", scene.display());
        // Local shading casts no shadow ray, hard shadows one per light
        // faced; neither bounces.
        let (shadow, reflection, refraction) = (3, 4, 5);
        let count = |row: usize, column: usize| whitted[row].1[column].parse::<u64>().unwrap();
        assert_eq!(count(0, shadow), 0, "local shading: no shadow ray");
        assert!(count(1, shadow) > 0, "hard shadows: shadow rays");
        for row in [0, 1] {
            assert_eq!(count(row, reflection) + count(row, refraction), 0);
        }
        assert!(page.contains("local shading only"));
        if refracts {
            assert_eq!(count(3, refraction), 0, "made opaque, nothing refracts");
            assert_ne!(count(4, refraction), 0);
        } else {
            assert!(page.contains("nothing in it refracts"));
        }
        check_against_bench(&scene, &rows);
        assert!(page.contains("Quick report"), "a quick report says so");
        // Not the course's scene: its section says so, without a table.
        assert!(!page.contains("<table class=\"course\">"));
    }
}

#[test]
fn the_course_scene_gets_its_times_beside_ours() {
    let dir = scratch("report-course");
    let scene = write(
        &dir,
        "balls_medium.p3f",
        &spheres_on_a_floor(40, 30, "", ""),
    );
    let (page, rows) = quick_report(&dir, &scene);
    let (headers, course) = table(&page, "course");
    let column = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let reported = [
        1.03, 14.45, 14.82, 2.23, 16.51, 16.84, 0.77, 12.01, 12.20, 1.75, 14.50, 13.99,
    ];
    assert_eq!(course.len(), 12);
    for ((id, cells), seconds) in course.iter().zip(reported) {
        let ours = rows.iter().find(|r| &stem(r) == id).unwrap();
        assert_eq!(cells[column("course s")], format!("{seconds:.2}"), "{id}");
        assert_eq!(
            cells[column("ours ms")],
            ms(&ours["median_seconds"]),
            "{id}"
        );
        let speedup = seconds / ours["median_seconds"].as_f64().unwrap();
        assert_eq!(cells[column("speed-up")], format!("{speedup:.1}x"), "{id}");
    }
}

#[test]
fn a_pixel_outside_the_image_is_refused() {
    let dir = scratch("report-bad-pixel");
    let [scene, _] = scenes(&dir);
    let out = dir.join("never.html");
    let said = workbench_fails(&[
        "report",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quick",
        "--runs",
        "1",
        "--pixel",
        "48",
        "3",
    ]);
    assert!(said.contains("--pixel 48 3 is outside"), "{said}");
    assert!(!out.exists());
}

/// Ctrl-C while measuring writes nothing, not even a temporary file. The
/// signal lands after the handler is set and before the measuring starts
/// ([`crate::support::interrupted`]), however fast the machine.
#[cfg(target_os = "linux")]
#[test]
fn ctrl_c_writes_nothing() {
    let dir = scratch("report-interrupt");
    let [scene, _] = scenes(&dir);
    let out = dir.join("report.html");
    let run = crate::support::interrupted(
        &[
            "report",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--quick",
            "--runs",
            "1",
            "--threads",
            "1",
        ],
        "stopping",
    );
    assert!(!run.status.success(), "an interrupted report must fail");
    assert!(run.stderr.contains("interrupted"), "{}", run.stderr);
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.contains("report"))
        .collect();
    assert!(left.is_empty(), "nothing written: {left:?}");
}

/// `--quick` lowers a large image to 128 pixels on its longer side and the
/// runs to 3; `--pixel` picks the pixel explained; `--set` edits the scene
/// (the glass sphere made opaque: nothing refracts, the edit is listed);
/// `--srgb` encodes the images with the sRGB curve.
#[test]
fn report_flags_apply() {
    let dir = scratch("report-flags");
    let scene = write(&dir, "wide.p3f", &spheres_on_a_floor(256, 128, "", ""));
    let run = |name: &str, extra: &[&str]| -> (String, Vec<Value>) {
        let (page, json) = (
            dir.join(format!("{name}.html")),
            dir.join(format!("{name}.json")),
        );
        let mut args = vec![
            "report",
            scene.to_str().unwrap(),
            "-o",
            page.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
            "--quick",
            "--runs",
            "5",
            "--threads",
            "1",
            "--pixel",
            "10",
            "5",
            "--set",
            "object 2 t 0",
        ];
        args.extend(extra);
        workbench_ok(&args);
        let rows: Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
        (
            std::fs::read_to_string(page).unwrap(),
            rows.as_array().unwrap().clone(),
        )
    };
    let (linear, rows) = run("linear", &[]);
    for row in &rows {
        assert_eq!(
            (row["width"].as_u64(), row["height"].as_u64()),
            (Some(128), Some(64))
        );
        assert_eq!(row["runs"], 3, "--quick keeps at most 3 of --runs 5");
    }
    assert!(linear.contains("128 x 64 (the scene asks for 256 x 128)"));
    assert!(linear.contains("Pixel (10, 5), given with --pixel"));
    assert!(linear.contains("object 2 t 0"), "the edit is listed");
    let (_, whitted) = table(&linear, "whitted");
    assert!(
        whitted
            .iter()
            .all(|(id, cells)| !id.ends_with("opaque") && cells[5] == "0"),
        "the glass sphere was made opaque: nothing refracts"
    );
    let (srgb, _) = run("srgb", &["--srgb"]);
    let (a, b) = (images(&linear), images(&srgb));
    // Compared whole, not printed: a failure would print every pixel.
    assert!(
        a[0].to_rgb8() != b[0].to_rgb8(),
        "sRGB encodes the images otherwise"
    );
}
