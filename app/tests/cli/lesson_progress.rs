//! `workbench lesson progress`: a student's record read from the window's
//! saved state or an exported file and written as JSON, CSV or an HTML
//! page; a class's files merged into one table; a broken file named with
//! its line and column.

use std::path::Path;
use std::process::Command;

use crate::support::{RUN_TIMEOUT, Scratch, output_within, workbench_fails, workbench_ok, write};

/// eframe's storage file as the window leaves it: the `app` key holds the
/// window's state, its lessons among the rest.
const WINDOW_STATE: &str = r#"{
    "app": "(controls:(samples:3),lessons:{\"camera\":[0,2],\"shadows\":[1]},lesson_notes:{\"camera\":{2:(done_at:Some(\"2026-12-05 17:04 UTC\"),answer:Some(\"16, or so\"))}},student:\"Ada <Lovelace>\")",
    "window": "()",
}"#;

/// An exported file naming its student.
const ADA: &str = r#"{
  "format-version": 1,
  "student": "Ada",
  "lessons": [
    { "lesson": "camera", "steps": [ { "step": 1 }, { "step": 3, "answer": "16" } ] }
  ]
}"#;

/// An exported file naming no one: its file stem names it.
const UNNAMED: &str = r#"{
  "format-version": 1,
  "lessons": [ { "lesson": "shadows", "steps": [ { "step": 2 } ] } ]
}"#;

/// `workbench args` with the data folder in `home`: stdout, which must
/// succeed.
fn with_data_folder(home: &Path, args: &[&str]) -> String {
    let mut command = Command::new(crate::support::workbench_exe());
    command
        .args(args)
        .env("XDG_DATA_HOME", home)
        .env("HOME", home);
    let run = output_within(command, RUN_TIMEOUT).unwrap();
    assert!(
        run.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8_lossy(&run.stdout).into_owned()
}

#[test]
fn the_windows_saved_progress_is_written_as_json_csv_and_html() {
    let dir = Scratch::new("progress-window-state");
    let home = dir.join("data");
    std::fs::create_dir_all(home.join("whittedworkbench")).unwrap();
    std::fs::write(home.join("whittedworkbench/app.ron"), WINDOW_STATE).unwrap();

    let json: serde_json::Value =
        serde_json::from_str(&with_data_folder(&home, &["lesson", "progress"])).unwrap();
    assert_eq!(json["format-version"], 1);
    assert_eq!(json["student"], "Ada <Lovelace>");
    assert_eq!(json["lessons"][0]["lesson"], "camera");
    let steps = &json["lessons"][0]["steps"];
    assert_eq!(steps[0], serde_json::json!({ "step": 1 }), "no note kept");
    assert_eq!(
        steps[1],
        serde_json::json!({ "step": 3, "done-at": "2026-12-05 17:04 UTC", "answer": "16, or so" })
    );
    assert_eq!(json["lessons"][1]["steps"][0]["step"], 2);

    let csv = with_data_folder(&home, &["lesson", "progress", "--format", "csv"]);
    assert_eq!(
        csv,
        "student,lesson,step,done-at,answer\n\
         Ada <Lovelace>,camera,1,,\n\
         Ada <Lovelace>,camera,3,2026-12-05 17:04 UTC,\"16, or so\"\n\
         Ada <Lovelace>,shadows,2,,\n"
    );

    let page = dir.join("ada.html");
    let page_arg = page.to_str().unwrap();
    with_data_folder(&home, &["lesson", "progress", "-o", page_arg]);
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("<title>Lesson progress: Ada &lt;Lovelace&gt;</title>"));
    assert!(
        html.contains("<td>camera</td><td>3</td><td>2026-12-05 17:04 UTC</td><td>16, or so</td>"),
        "{html}"
    );
    assert!(
        html.contains("it is not a proof"),
        "the page says what it is worth"
    );
    assert!(!html.contains("://"), "a page that fetches nothing: {html}");

    // An exported file given reads the same way, and the window's state
    // file may be named too.
    let exported = write(&dir, "ada.json", ADA);
    let csv = workbench_ok(&[
        "lesson",
        "progress",
        exported.to_str().unwrap(),
        "--format",
        "csv",
    ]);
    assert_eq!(
        csv,
        "student,lesson,step,done-at,answer\nAda,camera,1,,\nAda,camera,3,,16\n"
    );
    let state = home.join("whittedworkbench/app.ron");
    let named = workbench_ok(&["lesson", "progress", state.to_str().unwrap()]);
    assert!(named.contains("\"student\": \"Ada <Lovelace>\""), "{named}");
}

/// `lesson progress --merge a b -o out`: what it wrote, in the format
/// `out`'s extension names.
fn merged_into(a: &str, b: &str, out: &Path) -> String {
    let args = [
        "lesson",
        "progress",
        "--merge",
        a,
        b,
        "-o",
        out.to_str().unwrap(),
    ];
    workbench_ok(&args);
    std::fs::read_to_string(out).unwrap()
}

#[test]
fn merged_files_make_one_row_per_student_and_a_column_per_lesson() {
    let dir = Scratch::new("progress-merge");
    let ada = write(&dir, "ada.json", ADA);
    let bob = write(&dir, "bob.json", UNNAMED);
    let (ada, bob) = (ada.to_str().unwrap(), bob.to_str().unwrap());

    let csv = workbench_ok(&["lesson", "progress", "--merge", ada, bob, "--format", "csv"]);
    assert_eq!(csv, "student,camera,shadows\nAda,1 3,\nbob,,2\n");

    let class = dir.join("class.html");
    let html = merged_into(ada, bob, &class);
    assert!(
        html.contains("<th>student</th><th>camera</th><th>shadows</th>"),
        "{html}"
    );
    assert!(
        html.contains("<tr data-row=\"Ada\"><td>Ada</td><td>1 3</td><td></td></tr>"),
        "{html}"
    );
    assert!(
        html.contains("<tr data-row=\"bob\"><td>bob</td><td></td><td>2</td></tr>"),
        "{html}"
    );

    let json = dir.join("class.json");
    let json: serde_json::Value = serde_json::from_str(&merged_into(ada, bob, &json)).unwrap();
    assert_eq!(json["format-version"], 1);
    assert_eq!(json["students"][1]["student"], "bob");
    assert_eq!(json["students"][1]["file"], bob);
    assert_eq!(
        json["students"][0]["lessons"][0]["steps"][1]["answer"],
        "16"
    );
}

#[test]
fn a_malformed_progress_file_is_named_with_its_line_and_column() {
    let dir = Scratch::new("progress-malformed");
    let good = write(&dir, "good.json", ADA);
    let broken = write(
        &dir,
        "broken.json",
        &ADA.replace("\"step\": 3", "\"step\": \"three\""),
    );
    let (good, broken) = (good.to_str().unwrap(), broken.to_str().unwrap());
    let error = workbench_fails(&["lesson", "progress", "--merge", good, broken]);
    assert!(
        error.contains(&format!("{broken}:5:63: invalid type: string \"three\"")),
        "{error}"
    );
    assert!(!error.contains("panicked"), "{error}");
    let truncated = write(&dir, "truncated.json", &ADA[..40]);
    let error = workbench_fails(&["lesson", "progress", truncated.to_str().unwrap()]);
    assert!(error.contains("truncated.json:3:"), "{error}");
    let missing = workbench_fails(&["lesson", "progress", "nowhere.json"]);
    assert!(
        missing.contains("cannot read the progress file nowhere.json"),
        "{missing}"
    );
}
