//! What the window remembers across restarts (eframe's storage): side A's
//! controls and the session (last scene, recent files, panels). Every
//! field has a default, so an old or partial saved state still loads.

use std::path::PathBuf;

use serde::de::IgnoredAny;
use serde::{Deserialize, Serialize};
use tracer::render::{LensOverride, RenderSettings};

use crate::bundled::{self, SiteScene};
use crate::gui::sides::Controls;
use crate::lessons::progress::{Record, StepNotes, StepsDone};
use crate::load::SceneSource;

/// How many recent files to remember.
const MAX_RECENT: usize = 8;

/// What the window keeps of a session beside the controls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub(crate) struct Session {
    pub(crate) last_scene: Option<SceneSource>,
    /// Files opened recently, newest first.
    pub(crate) recent: Vec<PathBuf>,
    pub(crate) show_stats: bool,
}

impl Default for Session {
    fn default() -> Self {
        Self {
            last_scene: None,
            recent: Vec::new(),
            show_stats: true,
        }
    }
}

impl Session {
    /// Puts `path` first in the recent files.
    pub(crate) fn remember(&mut self, path: PathBuf) {
        self.recent.retain(|p| p != &path);
        self.recent.insert(0, path);
        self.recent.truncate(MAX_RECENT);
    }
}

/// The saved form: side A's controls beside the session's fields, as
/// earlier versions wrote them.
#[derive(Debug, Serialize, Deserialize)]
#[serde(default)]
struct Saved {
    controls: Controls,
    last_scene: Option<SceneSource>,
    recent: Vec<PathBuf>,
    show_stats: bool,
    /// The lesson steps done, per lesson.
    lessons: StepsDone,
    /// When each step was done and its answer; `lesson progress` reads
    /// these three under these names (`lessons::progress`).
    lesson_notes: StepNotes,
    /// The name the student typed in the Lessons panel.
    student: String,
}

impl Default for Saved {
    fn default() -> Self {
        let session = Session::default();
        Self {
            controls: Controls::default(),
            last_scene: session.last_scene,
            recent: session.recent,
            show_stats: session.show_stats,
            lessons: StepsDone::new(),
            lesson_notes: StepNotes::new(),
            student: String::new(),
        }
    }
}

/// The controls, session and lesson progress `storage` holds, or the
/// defaults.
pub(crate) fn restore(storage: Option<&dyn eframe::Storage>) -> (Controls, Session, Record) {
    let saved = storage
        .and_then(|s| s.get_string(eframe::APP_KEY))
        .and_then(|text| read(&text));
    match saved {
        Some(saved) => (
            saved.controls,
            Session {
                last_scene: saved.last_scene,
                recent: saved.recent,
                show_stats: saved.show_stats,
            },
            Record {
                student: saved.student,
                done: saved.lessons,
                notes: saved.lesson_notes,
            },
        ),
        None => (Controls::default(), Session::default(), Record::default()),
    }
}

/// Writes `controls`, `session` and the lessons' `progress` into `storage`.
pub(crate) fn save(
    storage: &mut dyn eframe::Storage,
    controls: &Controls,
    session: &Session,
    progress: &Record,
) {
    let saved = Saved {
        controls: controls.clone(),
        last_scene: session
            .last_scene
            .as_ref()
            .map(|s| remembered(s, bundled::site_scene_at)),
        recent: session.recent.clone(),
        show_stats: session.show_stats,
        lessons: progress.done.clone(),
        lesson_notes: progress.notes.clone(),
        student: progress.student.clone(),
    };
    eframe::set_value(storage, eframe::APP_KEY, &saved);
}

/// How the saved state names scene `source`: one fetched from beside the
/// page (`site`: the site scene at a URL) by its name, fetched again when
/// the page opens, for its text could outgrow the browser's storage for
/// the site, and the lesson progress saved with it would be lost; any
/// other as it is.
fn remembered(
    source: &SceneSource,
    site: impl Fn(&str) -> Option<&'static SiteScene>,
) -> SceneSource {
    match source {
        SceneSource::Written { name, .. } => {
            site(name).map_or_else(|| source.clone(), |s| SceneSource::Bundled(s.name.into()))
        }
        _ => source.clone(),
    }
}

/// Reads a saved state. Before the controls held the render settings as
/// one value (`render`) they were saved flat, the settings' fields beside
/// the window's own; such a state gives its settings too. Before the
/// scene's view owned the lens, the settings saved the lens they rendered
/// with (`aperture`, `focal`): it comes back as the user's, as it rendered.
fn read(text: &str) -> Option<Saved> {
    let mut saved: Saved = ron::from_str(text).ok()?;
    #[derive(Deserialize, Default)]
    #[serde(default)]
    struct Probe {
        controls: ProbeControls,
    }
    #[derive(Deserialize, Default)]
    #[serde(default)]
    struct ProbeControls {
        #[serde(deserialize_with = "present")]
        render: bool,
    }
    fn present<'de, D: serde::Deserializer<'de>>(field: D) -> Result<bool, D::Error> {
        IgnoredAny::deserialize(field).map(|_| true)
    }
    /// `controls` alone, or `render` within them.
    #[derive(Deserialize, Default)]
    #[serde(default)]
    struct InControls<T> {
        controls: T,
    }
    #[derive(Deserialize, Default)]
    #[serde(default)]
    struct Render<T> {
        render: T,
    }
    #[derive(Deserialize, Default)]
    #[serde(default)]
    struct OldLens {
        #[serde(deserialize_with = "some")]
        aperture: Option<f32>,
        #[serde(deserialize_with = "some")]
        focal: Option<f32>,
    }
    fn some<'de, D: serde::Deserializer<'de>>(field: D) -> Result<Option<f32>, D::Error> {
        f32::deserialize(field).map(Some)
    }
    let probe: Probe = ron::from_str(text).ok()?;
    let old = if probe.controls.render {
        ron::from_str::<InControls<Render<OldLens>>>(text)
            .ok()?
            .controls
            .render
    } else {
        saved.controls.render = ron::from_str::<InControls<RenderSettings>>(text)
            .ok()?
            .controls;
        ron::from_str::<InControls<OldLens>>(text).ok()?.controls
    };
    if old.aperture.is_some() || old.focal.is_some() {
        saved.controls.render.lens_override = LensOverride {
            aperture: old.aperture,
            focal: old.focal,
        };
    }
    Some(saved)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saved_state_reads_back_as_it_was() {
        let mut controls = Controls::default();
        controls.render.samples = 7;
        controls.resolution_scale = 0.5;
        let mut session = Session::default();
        session.remember("/a.p3f".into());
        let saved = Saved {
            controls: controls.clone(),
            last_scene: Some(SceneSource::Bundled("glass".into())),
            recent: session.recent.clone(),
            show_stats: false,
            lessons: StepsDone::from([("camera".to_string(), [0, 2].into())]),
            lesson_notes: StepNotes::new(),
            student: "Ada".into(),
        };
        let back = read(&ron::to_string(&saved).unwrap()).unwrap();
        assert_eq!(back.lessons, saved.lessons);
        assert_eq!(back.student, "Ada");
        assert_eq!(back.controls, controls);
        assert_eq!(back.last_scene, saved.last_scene);
        assert_eq!((back.recent, back.show_stats), (session.recent, false));
    }

    #[test]
    fn a_scene_fetched_from_beside_the_page_is_remembered_by_name() {
        static TETRA: SiteScene = SiteScene {
            name: "tetra",
            file: "tetra.p3f",
            description: "",
            size: 423_667,
        };
        let site = |url: &str| (url == TETRA.url()).then_some(&TETRA);
        let fetched = SceneSource::Written {
            name: "scenes/tetra.p3f".into(),
            text: "v from 0 0 5 ...".into(),
        };
        assert_eq!(
            remembered(&fetched, site),
            SceneSource::Bundled("tetra".into())
        );
        // A file a link fetched, or a lesson's step: kept as it is.
        let linked = SceneSource::Written {
            name: "mine/scene.p3f".into(),
            text: "v".into(),
        };
        assert_eq!(remembered(&linked, site), linked);
        let bundled = SceneSource::Bundled("glass".into());
        assert_eq!(remembered(&bundled, site), bundled);
    }

    /// `lesson progress` reads the window's saved lessons under the names
    /// `Saved` writes them with.
    #[test]
    fn the_saved_lessons_are_what_lesson_progress_reads() {
        let mut record = Record {
            student: "Ada".into(),
            ..Record::default()
        };
        record.mark_done("camera", 1, "then".into(), Some("16".into()));
        let saved = Saved {
            lessons: record.done.clone(),
            lesson_notes: record.notes.clone(),
            student: record.student.clone(),
            ..Saved::default()
        };
        let stored = format!("{{\"app\":{:?}}}", ron::to_string(&saved).unwrap());
        let path = std::path::Path::new("app.ron");
        let read = crate::lessons::progress::of_window_state(&stored, path).unwrap();
        assert_eq!(read, record.export());
    }

    /// `lesson progress` finds the file eframe keeps the window's state in.
    #[test]
    fn lesson_progress_looks_where_eframe_saves() {
        let eframes = eframe::storage_dir(crate::gui::TITLE).map(|d| d.join("app.ron"));
        assert_eq!(crate::lessons::progress::window_state_file(), eframes);
    }

    #[test]
    fn a_flat_state_of_an_earlier_version_gives_its_settings() {
        let text = "(controls:(samples:3,accel:Grid,resolution_scale:0.25,srgb:true))";
        let saved = read(text).unwrap();
        assert_eq!(saved.controls.render.samples, 3);
        assert_eq!(saved.controls.render.accel, tracer::accel::AccelKind::Grid);
        assert_eq!(saved.controls.resolution_scale, 0.25);
        assert!(saved.controls.srgb);
        assert!(read("not ron").is_none());
    }

    /// A state saved when the settings held the lens they rendered with
    /// renders with it again: it comes back as the user's override.
    #[test]
    fn an_earlier_states_lens_comes_back_as_the_users() {
        let nested = "(controls:(render:(depth_of_field:true,aperture:12.0,focal:1.5,samples:5)))";
        let saved = read(nested).unwrap();
        assert!(saved.controls.render.depth_of_field);
        assert_eq!(saved.controls.render.samples, 5);
        let lens = LensOverride {
            aperture: Some(12.0),
            focal: Some(1.5),
        };
        assert_eq!(saved.controls.render.lens_override, lens);
        let flat = read("(controls:(aperture:12.0,focal:1.5,srgb:true))").unwrap();
        assert_eq!(flat.controls.render.lens_override, lens);
        assert!(flat.controls.srgb);
        let none = read("(controls:(render:(samples:5)))").unwrap();
        assert_eq!(none.controls.render.lens_override, LensOverride::default());
    }

    #[test]
    fn recent_files_are_unique_newest_first_and_bounded() {
        let mut session = Session::default();
        for i in 0..10 {
            session.remember(format!("/{i}.p3f").into());
        }
        session.remember("/5.p3f".into());
        assert_eq!(session.recent.len(), MAX_RECENT);
        assert_eq!(session.recent[0], PathBuf::from("/5.p3f"));
        assert_eq!(session.recent[1], PathBuf::from("/9.p3f"));
    }
}
