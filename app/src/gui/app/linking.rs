//! Links a teacher can send ([`Link`]): what a page's query opens (a
//! bundled scene or lesson by name, a file on the page's site by URL,
//! fetched as a dropped file is read), the settings and edits it gives
//! the scene once loaded, and Copy link, the query of what is on screen.

use tracer::render::RenderSettings;
use tracer::scene::edit::Edit;

use crate::bundled::{self, SiteScene};
use crate::gui::link::{self, Link, Source};
use crate::gui::platform::target;
use crate::gui::platform::transfer::Transfer;
use crate::load::SceneSource;

use super::lesson_fetch::FetchFor;

use super::WorkbenchApp;

/// A link's settings and edits, waiting for its scene (`label`) to load.
pub(super) struct PendingLink {
    label: String,
    link: Link,
}

/// The files fetched from the page's site (by a link or the scene list),
/// by URL, so Copy link links to them again; and the scene being fetched.
#[derive(Default)]
pub(super) struct Fetched {
    urls: Vec<String>,
    /// Fetches started, which number them.
    started: u64,
    /// The scene fetch under way: the last one asked for, the only one
    /// that opens when it arrives.
    scene: Option<SceneFetch>,
}

impl Fetched {
    /// The scene fetch under way, for the scene panel.
    pub(super) fn scene(&self) -> Option<&SceneFetch> {
        self.scene.as_ref()
    }
}

/// A scene being fetched from the page's site, for the scene panel's
/// progress bar.
pub(crate) struct SceneFetch {
    pub(crate) url: String,
    pub(crate) transfer: Transfer,
    id: u64,
}

impl WorkbenchApp {
    /// Opens what a page's link asks for (its query, `?lesson=shadows`,
    /// `?scene=my/scene.p3f&spp=4`): its scene (its settings and edits
    /// applied once loaded), then its lesson at its step (which sets up
    /// a scene of its own). A query that does not read, a name not
    /// bundled or a file the site does not have is said on the page.
    pub fn open_link(&mut self, query: &str) {
        let link = match Link::parse(query) {
            Ok(link) => link,
            Err(e) => return self.messages.lasting_error(e),
        };
        let label = match &link.scene {
            Some(Source::Bundled(name)) => match bundled::find(name) {
                Some(scene) => {
                    self.open(SceneSource::Bundled(scene.name.to_string()));
                    Some(name.clone())
                }
                // A scene of `scenes/` the page does not embed.
                None => match bundled::site_scene(name) {
                    Some(scene) => {
                        self.fetch_site_scene(scene);
                        Some(scene.url())
                    }
                    None => {
                        let offered = bundled::offered();
                        let names: Vec<&str> = offered.iter().map(|s| s.name()).collect();
                        return self.messages.lasting_error(format!(
                            "no bundled scene is called {name:?}: the scenes are {}",
                            names.join(", ")
                        ));
                    }
                },
            },
            Some(Source::Url(url)) => {
                self.fetch_for(url, FetchFor::Scene);
                Some(url.clone())
            }
            None => None,
        };
        if let Some(label) = label {
            self.pending_link = Some(PendingLink {
                label,
                link: link.clone(),
            });
        }
        match &link.lesson {
            Some(Source::Bundled(name)) => self.open_bundled_lesson(name, link.step),
            Some(Source::Url(url)) => self.fetch_lesson(url, link.step),
            None => {}
        }
        if let Some(folder) = &link.folder {
            self.fetch_folder(folder);
        }
    }

    /// Fetches `url` from the page's site (`target::fetch`), then opens it
    /// as `for_what` says: a scene as a dropped file opens, or a lesson's
    /// file ([`Self::lesson_file_fetched`]). A scene fetch replaces the one
    /// under way: the last asked for opens.
    pub(super) fn fetch_for(&mut self, url: &str, for_what: FetchFor) -> u64 {
        self.fetched.urls.push(url.to_string());
        self.fetched.started += 1;
        let (id, transfer) = (self.fetched.started, Transfer::default());
        if for_what == FetchFor::Scene {
            self.cancel_scene_fetch();
            self.fetched.scene = Some(SceneFetch {
                url: url.to_string(),
                transfer: transfer.clone(),
                id,
            });
        }
        self.dialogs.fetch(url, id, for_what, transfer);
        id
    }

    /// Fetches a scene of `scenes/` the page does not embed (picked in the
    /// scene list, or named by a link), to open once it arrives.
    pub(super) fn fetch_site_scene(&mut self, scene: &SiteScene) {
        self.fetch_for(&scene.url(), FetchFor::Scene);
    }

    /// Stops the scene fetch under way, if any: another scene was opened.
    pub(super) fn cancel_scene_fetch(&mut self) {
        if let Some(fetch) = self.fetched.scene.take() {
            fetch.transfer.cancel();
        }
    }

    /// Opens what fetch `id` of `url` gave, or says why it gave nothing;
    /// a scene only if it is still the one wanted (no later pick).
    pub(super) fn open_fetched(
        &mut self,
        url: &str,
        id: u64,
        for_what: FetchFor,
        bytes: Result<Vec<u8>, String>,
    ) {
        if for_what != FetchFor::Scene {
            return self.lesson_file_fetched(url, id, for_what, bytes);
        }
        if self.fetched.scene.as_ref().is_none_or(|f| f.id != id) {
            return;
        }
        self.fetched.scene = None;
        self.open_dropped_text(std::path::Path::new(url), bytes, false);
    }

    /// Once a linked scene (`loaded`) is in: the link's settings on A's
    /// controls (over the scene's own), then its edits, each undoable as
    /// the editor's. A bad edit is said with the link's words.
    pub(super) fn finish_link(&mut self, loaded: &SceneSource) {
        let Some(pending) = self.pending_link.take_if(|p| p.label == loaded.label()) else {
            return;
        };
        let line = match pending.link.settings_line() {
            Ok(line) => line,
            Err(e) => return self.messages.lasting_error(e),
        };
        // Through the controls' own change, so a link's `width=` becomes
        // the resolution scale the window sizes its image by.
        let scene_width = self
            .sides
            .a
            .engine
            .scene()
            .map_or(1, |s| s.scene.view.width);
        let controls = &mut self.sides.a.controls;
        controls.change_settings(scene_width, |settings| line.overrides.apply(settings));
        for text in &line.set {
            let Some(scene) = self.sides.a.engine.scene() else {
                return;
            };
            let applied = Edit::parse_in(text, &scene.scene)
                .map_err(|e| e.to_string())
                .and_then(|edit| self.sides.a.edit(edit).map(drop));
            if let Err(e) = applied {
                return self
                    .messages
                    .lasting_error(format!("the link's set={text:?}: {e}"));
            }
        }
    }

    /// The link to what is on screen: the lesson and its step when one
    /// is open (it sets up its own scene and settings), otherwise side
    /// A's scene with the settings that differ from the scene's own and
    /// its edits; `None`, said why, when the scene came from no link (a
    /// file from disk, or dropped).
    pub(super) fn current_link(&self) -> Result<Link, String> {
        if self.lessons.open
            && let Some(lesson) = self.lessons.lesson()
        {
            let source = match crate::lessons::bundled::find(&lesson.name) {
                Some(_) => Source::Bundled(lesson.name.clone()),
                None => match self
                    .fetched
                    .urls
                    .iter()
                    .find(|url| url_names(url, &lesson.name))
                {
                    Some(url) => Source::Url(url.clone()),
                    None => {
                        return Err(format!(
                            "lesson {} is no bundled one nor from a link: put its file beside \
                             the page and link to it as lesson=folder/{}.toml",
                            lesson.name, lesson.name
                        ));
                    }
                },
            };
            return Ok(Link {
                lesson: Some(source),
                step: Some(self.lessons.step() + 1),
                ..Link::default()
            });
        }
        let a = &self.sides.a;
        let loaded = a.engine.scene().ok_or("no scene is open yet")?;
        let source = match &loaded.source {
            SceneSource::Bundled(name) => Source::Bundled(name.clone()),
            SceneSource::Written { name, .. } if self.fetched.urls.contains(name) => {
                Source::Url(name.clone())
            }
            other => {
                return Err(format!(
                    "{} is a file of this computer, which a link cannot open: \
                     put it beside the page and link to it as scene=folder/{}",
                    other.label(),
                    other.label()
                ));
            }
        };
        // The scene's own settings, as opening it adopts them (its edits
        // made: a lens edited is followed as it was then).
        let mut base = RenderSettings::default();
        base.adopt_scene(&loaded.scene);
        let mut settings = link::settings_flags(&a.controls.render, &base);
        settings.extend(a.history.texts().into_iter().map(|t| ("set".into(), t)));
        Ok(Link {
            scene: Some(source),
            settings,
            ..Link::default()
        })
    }

    /// Copy link: the page's address with the query of what is on screen
    /// on the clipboard, or why there is none.
    pub(super) fn copy_link(&mut self, ctx: &egui::Context) {
        match self.current_link() {
            Ok(link) => {
                let address = format!("{}{}", target::page_address(), link.query());
                ctx.copy_text(address.clone());
                self.messages.notify(format!("copied {address}"));
            }
            Err(e) => self.messages.notify(format!("no link to copy: {e}")),
        }
    }
}

/// Whether `url` is the file of lesson `name` (`lessons/name.toml`).
fn url_names(url: &str, name: &str) -> bool {
    let file = url.rsplit('/').next().unwrap_or(url);
    file.strip_suffix(".toml") == Some(name)
}
