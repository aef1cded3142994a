//! Lessons fetched from the page's site: one lesson by a link
//! (`?lesson=lessons/mine.toml`), or a class's folder by its index file
//! (`?folder=class/lessons.index`), since a static host lists no folder.
//! Each lesson's `file =` scene is fetched beside it (a `bundled` scene
//! the page does not embed, from `scenes/`) before the lesson is read, so
//! a teacher's folder works on the page as it does on disk.

use crate::bundled;
use crate::gui::link::beside;
use crate::lessons::Lesson;
use crate::lessons::folder::from_index_lines;
use crate::lessons::format::{NamedScene, SceneFiles, parse_lesson, scene_named};

use super::WorkbenchApp;

/// What a file fetched from the page's site is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FetchFor {
    /// A scene to open.
    Scene,
    /// A folder's index: the lessons it names are fetched next.
    Index,
    /// Lesson `i` of the lessons being fetched.
    Lesson(usize),
    /// The scene file lesson `i` names.
    LessonScene(usize),
}

/// Lessons being fetched, read once all their files are in.
#[derive(Debug, Default)]
pub(super) struct LessonFetch {
    /// A folder's (by its index): listed as a folder is; else one lesson
    /// opened at `step`.
    folder: bool,
    /// The step a link asked for, from 1.
    step: Option<usize>,
    lessons: Vec<FetchedLesson>,
    /// The fetches started for these lessons: a reply to another (lessons
    /// a later link replaced) is dropped.
    fetches: Vec<u64>,
}

/// One lesson's files: its text and its scene file's, each once fetched.
#[derive(Debug)]
struct FetchedLesson {
    url: String,
    text: Option<Result<String, String>>,
    /// The scene file's URL and, once fetched, its text.
    scene: Option<(String, Option<Result<String, String>>)>,
}

impl FetchedLesson {
    fn new(url: String) -> Self {
        FetchedLesson {
            url,
            text: None,
            scene: None,
        }
    }

    /// Whether every file it needs has come (or failed).
    fn is_in(&self) -> bool {
        self.text.is_some() && self.scene.as_ref().is_none_or(|(_, text)| text.is_some())
    }

    /// The lesson read, or why it cannot be: a file that did not come, or
    /// the lesson's own mistakes.
    fn read(&self) -> Result<Lesson, String> {
        let text = match &self.text {
            Some(Ok(text)) => text,
            Some(Err(e)) => return Err(format!("cannot read the lesson {}: {e}", self.url)),
            None => return Err(format!("the lesson {} did not arrive", self.url)),
        };
        let scenes = match &self.scene {
            Some((url, Some(Ok(text)))) => SceneFiles::Fetched { url, text },
            Some((url, Some(Err(e)))) => {
                return Err(format!("{}: cannot read its scene {url}: {e}", self.url));
            }
            Some((url, None)) => {
                return Err(format!("{}: its scene {url} did not arrive", self.url));
            }
            None => SceneFiles::Nowhere,
        };
        let name = self.url.rsplit('/').next().unwrap_or(&self.url);
        let stem = name.strip_suffix(".toml").unwrap_or(name);
        parse_lesson(text, stem, &self.url, scenes).map_err(|e| e.to_string())
    }
}

/// The URL of the scene file the lesson at `url` (its `text`) names, to
/// fetch with it: a `file` beside it, or a bundled scene the page does
/// not embed, in `scenes/`.
fn scene_url(url: &str, text: &str) -> Option<String> {
    match scene_named(text)? {
        NamedScene::File(file) => Some(beside(url, &file)),
        NamedScene::Bundled(name) if bundled::find(&name).is_none() => {
            bundled::site_scene(&name).map(|s| s.url())
        }
        NamedScene::Bundled(_) => None,
    }
}

impl WorkbenchApp {
    /// Fetches the lesson at `url` and its scene file, then opens it at
    /// `step` (from 1) as a dropped lesson opens.
    pub(super) fn fetch_lesson(&mut self, url: &str, step: Option<usize>) {
        self.lesson_fetch = Some(LessonFetch {
            step,
            lessons: vec![FetchedLesson::new(url.to_string())],
            ..LessonFetch::default()
        });
        self.fetch_lesson_file(url, FetchFor::Lesson(0));
    }

    /// Fetches a folder's index at `url`, then the lessons it names and
    /// their scenes, then lists them as a folder is listed.
    pub(super) fn fetch_folder(&mut self, url: &str) {
        self.lesson_fetch = Some(LessonFetch {
            folder: true,
            ..LessonFetch::default()
        });
        self.fetch_lesson_file(url, FetchFor::Index);
    }

    /// Fetches one of the lesson fetch's files, noting the fetch as its.
    fn fetch_lesson_file(&mut self, url: &str, for_what: FetchFor) {
        let id = self.fetch_for(url, for_what);
        if let Some(fetch) = &mut self.lesson_fetch {
            fetch.fetches.push(id);
        }
    }

    /// A lesson's file fetched (`for_what` is not [`FetchFor::Scene`]):
    /// kept, what it names fetched next, and the lessons read once all
    /// are in. A reply for lessons no longer wanted (another link came
    /// since) is dropped.
    pub(super) fn lesson_file_fetched(
        &mut self,
        url: &str,
        id: u64,
        for_what: FetchFor,
        bytes: Result<Vec<u8>, String>,
    ) {
        let text = bytes.and_then(|b| {
            String::from_utf8(b)
                .map_err(|_| "not text: a lesson and its scene are text files".into())
        });
        let Some(fetch) = self
            .lesson_fetch
            .as_mut()
            .filter(|f| f.fetches.contains(&id))
        else {
            return;
        };
        let mut next = Vec::new();
        match for_what {
            FetchFor::Scene => return,
            FetchFor::Index => match text {
                Ok(index) => {
                    for file in from_index_lines(&index) {
                        let lesson = beside(url, file);
                        next.push((lesson.clone(), FetchFor::Lesson(fetch.lessons.len())));
                        fetch.lessons.push(FetchedLesson::new(lesson));
                    }
                    if fetch.lessons.is_empty() {
                        self.lesson_fetch = None;
                        return self
                            .messages
                            .lasting_error(format!("the lesson index {url} names no lesson"));
                    }
                }
                Err(e) => {
                    self.lesson_fetch = None;
                    return self
                        .messages
                        .lasting_error(format!("cannot read the lesson index {url}: {e}"));
                }
            },
            FetchFor::Lesson(i) => {
                let Some(lesson) = fetch.lessons.get_mut(i) else {
                    return;
                };
                if let Some(scene) = text.as_deref().ok().and_then(|t| scene_url(&lesson.url, t)) {
                    next.push((scene.clone(), FetchFor::LessonScene(i)));
                    lesson.scene = Some((scene, None));
                }
                lesson.text = Some(text);
            }
            FetchFor::LessonScene(i) => {
                if let Some((_, scene)) = fetch.lessons.get_mut(i).and_then(|l| l.scene.as_mut()) {
                    *scene = Some(text);
                }
            }
        }
        for (url, for_what) in next {
            self.fetch_lesson_file(&url, for_what);
        }
        self.open_fetched_lessons();
    }

    /// Once every file of the lessons being fetched is in: a folder's
    /// lessons listed (those that do not read said), or the one lesson
    /// opened at its step.
    fn open_fetched_lessons(&mut self) {
        let all_in = self
            .lesson_fetch
            .as_ref()
            .is_some_and(|f| !f.lessons.is_empty() && f.lessons.iter().all(FetchedLesson::is_in));
        if !all_in {
            return;
        }
        let Some(fetch) = self.lesson_fetch.take() else {
            return;
        };
        let read: Vec<Result<Lesson, String>> =
            fetch.lessons.iter().map(FetchedLesson::read).collect();
        if fetch.folder {
            if self.add_lessons(read) {
                self.set_up_lesson_step();
            }
            return;
        }
        match read.into_iter().next() {
            Some(Ok(lesson)) => self.set_up_lesson_at(Ok(lesson), fetch.step),
            Some(Err(e)) => self.messages.lasting_error(e),
            None => {}
        }
    }
}
