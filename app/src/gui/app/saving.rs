//! Files in and out: the open and save dialogs on threads of their own
//! (the UI keeps drawing), behind [`FileDialog`] so a test can answer them, the PNG, EXR, edited-scene and lesson-progress writes, and
//! `--screenshot`.
//! Their results come back to the UI thread as [`Reply`]s.

use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};
use web_time::Instant;

use anyhow::Context as _;
use tracer::render::{JobState, Snapshot};
use tracer::scene::{Scene, write_p3f_in};

use crate::figures::study_plot;
use crate::gui::platform::screenshot::{self, ScreenshotOutcome, ScreenshotPlan};
use crate::gui::platform::target;
use crate::gui::platform::target::SaveTo;
use crate::gui::platform::transfer::Transfer;
use crate::gui::sides::{Activity, Side, SideId};
use crate::lessons::progress::Progress;
use crate::load::SceneSource;
use crate::measure::study::{Param, Point};

use super::lesson_fetch::FetchFor;

/// Results of background dialogs and saves, delivered to the UI thread.
pub(crate) enum Reply {
    Open(PathBuf),
    /// A folder of lessons to add to the Lessons panel's list.
    LessonFolder(PathBuf),
    /// A dropped file that is no file on disk, by name, and its bytes
    /// or why they could not be read.
    Dropped {
        path: PathBuf,
        bytes: Result<Vec<u8>, String>,
    },
    /// A file fetched from the page's site (`url`, fetch number `id`),
    /// what it is for, and its bytes or why they could not be fetched.
    Fetched {
        url: String,
        id: u64,
        for_what: FetchFor,
        bytes: Result<Vec<u8>, String>,
    },
    Notice(String),
    Error(String),
    /// The line to print once the screenshot is saved, or why it was not.
    Screenshot(Result<String, String>),
    /// A side's scene, as it stood in history state `state`, is in `path`.
    SceneSaved {
        side: SideId,
        path: PathBuf,
        state: u64,
    },
}

/// An edited scene to write: which side's, and its history state then.
pub(crate) struct SceneSave {
    pub(crate) scene: Scene,
    pub(crate) side: SideId,
    pub(crate) state: u64,
}

impl SceneSave {
    /// The scene as P3F in `path`, its skybox still found from there.
    pub(crate) fn write(&self, path: &Path) -> anyhow::Result<()> {
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        std::fs::write(path, write_p3f_in(&self.scene, folder))
            .with_context(|| format!("cannot write the scene to {}", path.display()))
    }

    /// The name a save dialog offers: `<stem>-edited.p3f` beside the
    /// scene's file (the current folder for a bundled scene).
    pub(crate) fn suggested(&self, source: &SceneSource) -> (PathBuf, String) {
        let stem = Path::new(&source.label())
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        let stem = stem.strip_suffix("-edited").unwrap_or(&stem).to_string();
        let folder = match source {
            SceneSource::File(path) => path.parent().map(Path::to_path_buf),
            _ => None,
        };
        (
            folder.unwrap_or_else(|| PathBuf::from(".")),
            format!("{stem}-edited.p3f"),
        )
    }
}

/// What a save writes: the shown render (PNG) or the linear film (EXR).
pub(crate) enum SaveImage {
    /// Boxed: a snapshot's statistics are far larger than the film's
    /// handle.
    Shown(Box<Snapshot>),
    Linear(image::Rgb32FImage),
}

impl SaveImage {
    /// Side `side`'s render on screen, as PNG or (`exr`) its linear film.
    pub(crate) fn of(side: &Side, exr: bool) -> anyhow::Result<Self> {
        let image = if exr {
            side.engine.linear_image().map(SaveImage::Linear)
        } else {
            side.image
                .shown()
                .cloned()
                .map(|s| SaveImage::Shown(Box::new(s)))
        };
        image.ok_or_else(|| anyhow::anyhow!("there is no image to save yet"))
    }

    /// The image at its full resolution, encoded as its file.
    pub(crate) fn encode(&self) -> anyhow::Result<Vec<u8>> {
        let mut bytes = Cursor::new(Vec::new());
        match self {
            SaveImage::Linear(film) => film.write_to(&mut bytes, image::ImageFormat::OpenExr)?,
            SaveImage::Shown(snapshot) => snapshot
                .to_image()
                .ok_or_else(|| anyhow::anyhow!("the image buffer has the wrong size"))?
                .write_to(&mut bytes, image::ImageFormat::Png)?,
        }
        Ok(bytes.into_inner())
    }
}

/// What a file dialog asks: a file to open, or a name to write under.
#[derive(Debug, Clone)]
pub struct FileQuestion {
    /// A name to write under; otherwise an existing file to open.
    pub save: bool,
    /// A folder to open rather than a file (its filter is not used).
    pub pick_folder: bool,
    /// The filter's name ("PNG image") and its extensions.
    pub filter: (&'static str, &'static [&'static str]),
    /// Where the dialog opens.
    pub(crate) folder: Option<PathBuf>,
    /// The name it offers.
    pub name: Option<String>,
}

/// Answers the window's file dialogs: the desktop's native dialog in the
/// window, a double that answers as a test says in the tests. `None`: the
/// user cancelled (or no dialog could be shown).
pub trait FileDialog: Send + Sync {
    fn ask(&self, question: &FileQuestion) -> Option<PathBuf>;
}

/// The desktop's own dialog (rfd).
pub(crate) struct NativeDialog;

impl FileDialog for NativeDialog {
    fn ask(&self, question: &FileQuestion) -> Option<PathBuf> {
        let (filter, extensions) = question.filter;
        let mut dialog = target::FileDialog::new();
        if let Some(folder) = &question.folder {
            dialog = dialog.set_directory(folder);
        }
        if question.pick_folder {
            return dialog.pick_folder();
        }
        let mut dialog = dialog.add_filter(filter, extensions);
        if let Some(name) = &question.name {
            dialog = dialog.set_file_name(name);
        }
        if question.save {
            dialog.save_file()
        } else {
            dialog.pick_file()
        }
    }
}

/// A dialog answered with the one path it was made with: what a test
/// chooses without a desktop to show a dialog on.
pub(crate) struct Answer(pub PathBuf);

impl FileDialog for Answer {
    fn ask(&self, _question: &FileQuestion) -> Option<PathBuf> {
        Some(self.0.clone())
    }
}

/// The file dialogs, each asked on a thread of its own, and the channel
/// their threads answer on.
pub(crate) struct Dialogs {
    sender: Sender<Reply>,
    replies: Receiver<Reply>,
    pub(crate) dialog: Arc<dyn FileDialog>,
}

impl Default for Dialogs {
    fn default() -> Self {
        let (sender, replies) = channel();
        Self {
            sender,
            replies,
            dialog: Arc::new(NativeDialog),
        }
    }
}

impl Dialogs {
    /// Reads the bytes of `file`, dropped but no file on disk (the web
    /// page's), as the platform gives them (`target::read_dropped`: at
    /// once on the desktop, later on the page), and replies with them.
    pub(crate) fn read_dropped(&self, file: Arc<dyn egui::DroppedFile>, ctx: &egui::Context) {
        let (reply, ctx) = (self.sender.clone(), ctx.clone());
        let path = file.path().to_path_buf();
        target::read_dropped(file, move |bytes| {
            let _ = reply.send(Reply::Dropped { path, bytes });
            ctx.request_repaint();
        });
    }

    /// Fetches `url` from the page's site (`target::fetch`, followed by
    /// `progress`) and replies with its bytes, as fetch number `id`, for
    /// what `for_what` says.
    pub(crate) fn fetch(&self, url: &str, id: u64, for_what: FetchFor, progress: Transfer) {
        let (reply, url) = (self.sender.clone(), url.to_string());
        target::fetch(&url.clone(), progress, move |bytes| {
            let _ = reply.send(Reply::Fetched {
                url,
                id,
                for_what,
                bytes,
            });
        });
    }

    /// The replies that came in since the last frame.
    pub(crate) fn take(&self) -> Vec<Reply> {
        self.replies.try_iter().collect()
    }

    /// Asks `question` on a thread called `name` and replies with what
    /// `answer` makes of the path chosen, or with the notice `unanswered`;
    /// false when no thread could be started.
    fn ask_on_thread(
        &self,
        name: &str,
        question: FileQuestion,
        unanswered: &'static str,
        answer: impl FnOnce(PathBuf) -> Reply + Send + 'static,
    ) -> bool {
        let (reply, dialog) = (self.sender.clone(), self.dialog.clone());
        target::spawn(name, move || {
            let _ = reply.send(match dialog.ask(&question) {
                Some(path) => answer(path),
                None => Reply::Notice(unanswered.into()),
            });
        })
        .is_ok()
    }

    /// Asks where to save (`question`, its name offered) on a thread
    /// called `name`, then saves what `bytes` makes there
    /// (`target::SaveTo`: the file chosen on the desktop, a download on
    /// the page) and replies with `saved` of where it went, or with the
    /// notice `unanswered`; false when no thread could be started.
    fn save_on_thread(
        &self,
        name: &str,
        question: FileQuestion,
        unanswered: &'static str,
        bytes: impl FnOnce() -> anyhow::Result<Vec<u8>> + Send + 'static,
        saved: impl FnOnce(String) -> String + Send + 'static,
    ) -> bool {
        let (reply, dialog) = (self.sender.clone(), self.dialog.clone());
        target::spawn(name, move || {
            let _ = reply.send(match SaveTo::ask(&*dialog, &question) {
                Some(to) => match bytes().and_then(|bytes| to.write(&bytes)) {
                    Ok(()) => Reply::Notice(saved(to.describe())),
                    Err(e) => Reply::Error(format!("{e:#}")),
                },
                None => Reply::Notice(unanswered.into()),
            });
        })
        .is_ok()
    }

    /// The native open dialog; false when no thread could be started.
    pub(crate) fn open(&self) -> bool {
        let question = FileQuestion {
            save: false,
            pick_folder: false,
            filter: (
                "Scenes, meshes and lessons",
                &["p3f", "nff", "obj", "ply", "toml"],
            ),
            folder: Some("scenes".into()),
            name: None,
        };
        self.ask_on_thread(
            "open-dialog",
            question,
            "nothing opened (cancelled, or no file dialog on this desktop: \
             drop a file on the window instead)",
            Reply::Open,
        )
    }

    /// The native folder dialog for a folder of lessons (the Lessons
    /// window's Lesson folder...); false when no thread could be started.
    pub(crate) fn open_lesson_folder(&self) -> bool {
        let question = FileQuestion {
            save: false,
            pick_folder: true,
            filter: ("Lesson folders", &[]),
            folder: None,
            name: None,
        };
        self.ask_on_thread(
            "lesson-folder-dialog",
            question,
            "no lesson folder added (cancelled, or no file dialog on this desktop: \
             start the workbench with --lesson-folder DIR instead)",
            Reply::LessonFolder,
        )
    }

    /// The native save dialog for the lessons' `progress` (the Lessons
    /// window's Export progress...), offered as the student's name, and
    /// the write; false when no thread could be started.
    pub(crate) fn save_progress(&self, progress: Progress) -> bool {
        let question = FileQuestion {
            save: true,
            pick_folder: false,
            filter: ("Lesson progress", &["json"]),
            folder: None,
            name: Some(format!("{}-progress.json", progress.student_or("lessons"))),
        };
        self.save_on_thread(
            "save-progress-dialog",
            question,
            "progress not exported (cancelled, or no file dialog on this desktop: \
             `workbench lesson progress` reads it from the saved state)",
            move || Ok(progress.to_json().into_bytes()),
            |to| format!("progress exported to {to}"),
        )
    }

    /// The native save dialog for a study's chart (its `points` of
    /// `param` on `subject`), and the chart drawn and written, off the
    /// window's thread; false when no thread could be started.
    pub(crate) fn save_study_chart(&self, param: Param, points: Vec<Point>, subject: &str) -> bool {
        let question = FileQuestion {
            save: true,
            pick_folder: false,
            filter: ("PNG image", &["png"]),
            folder: None,
            name: Some(study_plot::chart_file_name(param, subject)),
        };
        let subject = subject.to_string();
        self.save_on_thread(
            "save-chart-dialog",
            question,
            "chart not saved (cancelled, or no file dialog on this desktop)",
            move || study_plot::chart_png(param, &points, &subject),
            |to| format!("chart saved to {to}"),
        )
    }

    /// The native save dialog for `image`, named after `scene`, and the
    /// write; false when no thread could be started.
    pub(crate) fn save(&self, image: SaveImage, scene: &str) -> bool {
        let stem = Path::new(scene)
            .file_stem()
            .map_or_else(|| "render".into(), |s| s.to_string_lossy().into_owned());
        let filter: (&str, &[&str]) = match image {
            SaveImage::Linear(_) => ("OpenEXR image", &["exr"]),
            SaveImage::Shown(_) => ("PNG image", &["png"]),
        };
        let question = FileQuestion {
            save: true,
            pick_folder: false,
            filter,
            folder: None,
            name: Some(format!("{stem}.{}", filter.1[0])),
        };
        self.save_on_thread(
            "save-dialog",
            question,
            "not saved (cancelled, or no file dialog on this desktop)",
            move || image.encode(),
            |to| format!("saved {to}"),
        )
    }
}

impl Dialogs {
    /// The native save dialog for an edited scene from `source`, and the
    /// write; false when no thread could be started.
    pub(crate) fn save_scene(&self, save: SceneSave, source: &SceneSource) -> bool {
        let (folder, name) = save.suggested(source);
        let question = FileQuestion {
            save: true,
            pick_folder: false,
            filter: ("P3F scene", &["p3f"]),
            folder: Some(folder),
            name: Some(name),
        };
        self.ask_on_thread(
            "save-scene-dialog",
            question,
            "scene not saved (cancelled, or no file dialog on this desktop)",
            move |path| match save.write(&path) {
                Ok(()) => Reply::SceneSaved {
                    side: save.side,
                    path,
                    state: save.state,
                },
                Err(e) => Reply::Error(format!("{e:#}")),
            },
        )
    }
}

/// `--screenshot`: where and when, and whether it was asked for already.
pub(crate) struct ScreenshotRequest {
    plan: ScreenshotPlan,
    pub(crate) outcome: ScreenshotOutcome,
    opened_at: Instant,
    requested: bool,
    /// Where side A's image was drawn in the last frame, in points.
    image_rect: Option<egui::Rect>,
    /// Whether the last two frames drew it at the same place: the
    /// screenshot is of a later frame, so a layout still settling (panels
    /// sized on their first frames, the observer's split) would put the
    /// image elsewhere than the line says.
    layout_settled: bool,
}

impl ScreenshotRequest {
    pub(crate) fn new(plan: ScreenshotPlan, outcome: ScreenshotOutcome) -> Self {
        Self {
            plan,
            outcome,
            opened_at: Instant::now(),
            requested: false,
            image_rect: None,
            layout_settled: false,
        }
    }

    /// Keeps where the viewport drew side A's image this frame, for the
    /// line that reports the screenshot.
    pub(crate) fn saw_image_at(&mut self, rect: Option<egui::Rect>) {
        self.layout_settled = rect == self.image_rect;
        self.image_rect = rect;
    }

    /// Asks egui for the screenshot once it is due: after the plan's delay,
    /// or once `a`'s render is done and on screen (or `error` shows). The
    /// result comes back through `dialogs`.
    pub(crate) fn take_when_due(
        &mut self,
        ctx: &egui::Context,
        a: &Side,
        error: bool,
        dialogs: &Dialogs,
    ) {
        if self.requested {
            return;
        }
        let due = match self.plan.after {
            Some(delay) => {
                let elapsed = self.opened_at.elapsed();
                if elapsed < delay {
                    ctx.request_repaint_after(delay - elapsed);
                }
                elapsed >= delay
            }
            None => {
                let finished = !a.engine.is_loading()
                    && (error
                        || (a.engine.activity() == Activity::Job(JobState::Done)
                            && a.image.is_current(&a.engine)));
                if finished && !self.layout_settled {
                    ctx.request_repaint();
                }
                finished && self.layout_settled
            }
        };
        if !due {
            return;
        }
        self.requested = true;
        let path = self.plan.path.clone();
        let shown = a.image.shown().map(|shown| {
            let drawn = self
                .image_rect
                .map(|rect| screenshot::describe_rect(rect, ctx.pixels_per_point()));
            match drawn {
                Some(drawn) => format!("{}, {drawn}", screenshot::describe(shown)),
                None => screenshot::describe(shown),
            }
        });
        let reply = dialogs.sender.clone();
        let wake = ctx.clone();
        ctx.request_screenshot(move |image| {
            let result = screenshot::save(&image, &path)
                .map(|()| match shown {
                    Some(shown) => format!("saved screenshot {} of {shown}", path.display()),
                    None => format!("saved screenshot {}", path.display()),
                })
                .map_err(|e| format!("{e:#}"));
            let _ = reply.send(Reply::Screenshot(result));
            wake.request_repaint();
        });
    }
}
