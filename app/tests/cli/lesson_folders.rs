//! A folder of lessons on the command line: `lesson list DIR` in chapter
//! order, `lesson check DIR` on every file, scenes found beside the
//! lessons, and an index file choosing which files and in which order.

use crate::support::{Scratch, workbench, workbench_ok};

/// A lesson of chapter `chapter` whose scene is the file `scene`, beside it.
fn lesson(title: &str, chapter: u32, scene: &str) -> String {
    format!(
        r#"title = "{title}"
chapter = {chapter}

[scene]
file = "{scene}"

[start]
settings = "--no-aa"

[[step]]
title = "Smooth"
text = "Turn anti-aliasing on."
check = {{ kind = "value", of = "aa", is = "on" }}
solution = {{ settings = "--aa" }}
"#
    )
}

const SCENE: &str = "v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 16 16\n\
                     l 0 5 5 1 1 1\nf 1 0 0 1 0 0 0 0 1 0 1\ns 0 0 0 1\n";

/// A class folder: two lessons (chapters 9 and 2) and their scene.
fn class_folder(name: &str) -> Scratch {
    let dir = Scratch::new(name);
    std::fs::create_dir(dir.join("scenes")).unwrap();
    std::fs::write(dir.join("scenes/ball.p3f"), SCENE).unwrap();
    std::fs::write(
        dir.join("a_late.toml"),
        lesson("Late", 9, "scenes/ball.p3f"),
    )
    .unwrap();
    std::fs::write(
        dir.join("b_early.toml"),
        lesson("Early", 2, "scenes/ball.p3f"),
    )
    .unwrap();
    dir
}

#[test]
fn a_folder_is_listed_in_chapter_order_and_checked_whole() {
    let dir = class_folder("lesson-folder");
    let folder = dir.display().to_string();
    let list = workbench_ok(&["lesson", "list", &folder]);
    let early = list.find("b_early").unwrap_or_else(|| panic!("{list}"));
    let late = list.find("a_late").unwrap_or_else(|| panic!("{list}"));
    assert!(early < late, "chapter 2 before chapter 9:\n{list}");
    let check = workbench_ok(&["lesson", "check", &folder]);
    assert!(check.contains("b_early (chapter 2): Early"), "{check}");
    assert!(check.contains("a_late (chapter 9): Late"), "{check}");
    assert!(check.contains("all 2 steps pass"), "{check}");
}

#[test]
fn a_broken_file_in_a_folder_fails_and_the_others_are_still_read() {
    let dir = class_folder("lesson-folder-broken");
    std::fs::write(
        dir.join("c_broken.toml"),
        lesson("Broken", 0, "scenes/ball.p3f"),
    )
    .unwrap();
    let folder = dir.display().to_string();
    let run = workbench(&["lesson", "list", &folder]);
    assert!(!run.status.success());
    let (out, err) = (
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr),
    );
    assert!(out.contains("b_early") && out.contains("a_late"), "{out}");
    assert!(
        err.contains("c_broken.toml:2:11: expected a chapter from 1 to 99"),
        "{err}"
    );
    let run = workbench(&["lesson", "check", &folder]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(out.contains("c_broken.toml:2:11"), "{out}");
    assert!(out.contains("step 1/1 Smooth: pass"), "{out}");
}

/// An index names which files a folder offers, in its order: what a
/// static web host, which lists nothing, will read.
#[test]
fn an_index_chooses_the_folders_lessons() {
    let dir = class_folder("lesson-folder-index");
    std::fs::write(dir.join("lessons.index"), "# this week\na_late.toml\n").unwrap();
    let folder = dir.display().to_string();
    let list = workbench_ok(&["lesson", "list", &folder, "--format", "json"]);
    let json: serde_json::Value = serde_json::from_str(&list).unwrap();
    let names: Vec<&str> = (json.as_array().unwrap().iter())
        .map(|l| l["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["a_late"], "{json}");
}
