//! Links a teacher can send ([`Link`]): what a page's query opens (a
//! bundled scene or lesson by name, a file on the page's site by URL,
//! fetched as a dropped file is read), the settings and edits it gives
//! the scene once loaded, and Copy link, the query of what is on screen.

use tracer::render::RenderSettings;
use tracer::scene::edit::Edit;

use crate::bundled;
use crate::gui::link::{self, Link, Source};
use crate::gui::platform::target;
use crate::load::SceneSource;

use super::WorkbenchApp;

/// A link's settings and edits, waiting for its scene (`label`) to load.
pub(super) struct PendingLink {
    label: String,
    link: Link,
}

/// The files a link fetched, by URL, so Copy link links to them again.
#[derive(Default)]
pub(super) struct Fetched(Vec<String>);

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
        match &link.scene {
            Some(Source::Bundled(name)) => match bundled::find(name) {
                Some(scene) => self.open(SceneSource::Bundled(scene.name.to_string())),
                None => {
                    let names: Vec<&str> = bundled::SCENES.iter().map(|s| s.name).collect();
                    return self.messages.lasting_error(format!(
                        "no bundled scene is called {name:?}: the scenes are {}",
                        names.join(", ")
                    ));
                }
            },
            Some(Source::Url(url)) => self.fetch(url, false),
            None => {}
        }
        if let Some(scene) = &link.scene {
            let label = match scene {
                Source::Bundled(name) => name.clone(),
                Source::Url(url) => url.clone(),
            };
            self.pending_link = Some(PendingLink {
                label,
                link: link.clone(),
            });
        }
        match &link.lesson {
            Some(Source::Bundled(name)) => self.open_bundled_lesson(name, link.step),
            Some(Source::Url(url)) => {
                self.link_step = link.step;
                self.fetch(url, true);
            }
            None => {}
        }
    }

    /// Fetches `url` from the page's site (`target::fetch`), then opens it
    /// as a dropped file is opened: a lesson (`lesson`) or a scene.
    fn fetch(&mut self, url: &str, lesson: bool) {
        self.fetched.0.push(url.to_string());
        self.dialogs.fetch(url, lesson);
    }

    /// Once a linked scene (`loaded`) is in: the link's settings on A's
    /// controls (over the scene's own), then its edits, each undoable as
    /// the editor's. A bad edit is said with the link's words.
    pub(super) fn finish_link(&mut self, loaded: &SceneSource) {
        let Some(pending) = self.pending_link.take_if(|p| p.label == loaded.label()) else {
            return;
        };
        let flags = match pending.link.render_flags() {
            Ok(flags) => flags,
            Err(e) => return self.messages.lasting_error(e),
        };
        let controls = &mut self.sides.a.controls;
        flags.apply(&mut controls.render);
        let accel = controls.render.accel;
        controls.set_accel(accel);
        for text in &flags.set {
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
                    .0
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
            SceneSource::Written { name, .. } if self.fetched.0.contains(name) => {
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
