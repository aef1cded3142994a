//! A link a teacher can send: the web page's query string says what the
//! window opens (`?lesson=shadows`, `?scene=my/scene.p3f&spp=4`), and
//! Copy link writes the query of what is on screen. Read and written
//! here, on every target, so the desktop's tests check what the page
//! will open.

use tracer::render::{RenderSettings, Sampling};

use tracer::render::vocabulary::{VocabularyError, WORDS};

use crate::lessons::actions::SettingsLine;

/// Where a link's scene or lesson comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Source {
    /// A bundled scene's or lesson's name (`balls_low`, `shadows`).
    Bundled(String),
    /// A file on the page's own site, by a URL relative to the page
    /// (`lessons/mine.toml`, `my/scene.p3f`), fetched when opened.
    Url(String),
}

impl Source {
    /// Tells a name from a URL: a bundled name is one word (letters,
    /// digits, `_`, `-`), so a value with a `/` or a `.` (a folder or a
    /// file's extension) is a URL. A URL to another site (`https://…`,
    /// `//host/…`) is refused: the page fetches only from its own.
    fn read(key: &str, value: String) -> Result<Self, String> {
        if value.contains(':') || value.starts_with("//") {
            return Err(format!(
                "the link's {key} {value:?} is not on the page's own site: \
                 give a bundled name or a URL relative to the page, as {key}=folder/file"
            ));
        }
        Ok(if value.contains(['/', '.']) {
            Source::Url(value)
        } else {
            Source::Bundled(value)
        })
    }

    fn text(&self) -> &str {
        match self {
            Source::Bundled(text) | Source::Url(text) => text,
        }
    }
}

/// What a page's query asks the window to open.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Link {
    /// A lesson: opened in the Lessons panel, its step set up.
    pub(crate) lesson: Option<Source>,
    /// A class's folder, by the URL of its index file (`lessons.index`,
    /// one lesson file a line): its lessons listed, the first set up.
    pub(crate) folder: Option<String>,
    /// The lesson's step to set up, counted from 1 as the Lessons panel
    /// counts them (the first when not given).
    pub(crate) step: Option<usize>,
    /// A scene: opened as the scene picker or a dropped file would.
    pub(crate) scene: Option<Source>,
    /// Render settings in the command line's words, in the link's order:
    /// a flag's name without its `--` (`spp`, `accel`, `set`) and its
    /// value (empty for a switch such as `aa`).
    pub(crate) settings: Vec<(String, String)>,
}

impl Link {
    /// Reads `query` (`?a=b&c=d`, with or without its `?`, values
    /// percent-encoded as browsers write them). `lesson`, `step` and
    /// `scene` say what opens; every other key is a word of the settings'
    /// vocabulary (`spp=4`, `accel=bvh`, `aa`) or an edit (`set=object 5
    /// ior 1.33`, repeatable as on the command line). A key it does not
    /// know, a value the flag refuses, a lesson, step or scene given twice
    /// or empty is an error naming it: a link that silently opened
    /// something else would mislead a whole class.
    pub(crate) fn parse(query: &str) -> Result<Self, String> {
        let mut link = Link::default();
        let query = query.strip_prefix('?').unwrap_or(query);
        for pair in query.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
            let value =
                decode(value).ok_or_else(|| format!("the link's {key} is not valid: {value}"))?;
            let empty = || format!("the link's {key} is empty: give one, as {key}=NAME");
            let twice = || format!("the link gives {key} twice");
            match key {
                "lesson" | "scene" => {
                    if value.is_empty() {
                        return Err(empty());
                    }
                    let source = Source::read(key, value)?;
                    let slot = if key == "lesson" {
                        &mut link.lesson
                    } else {
                        &mut link.scene
                    };
                    if slot.replace(source).is_some() {
                        return Err(twice());
                    }
                }
                "folder" => {
                    if value.is_empty() {
                        return Err(empty());
                    }
                    let Source::Url(url) = Source::read(key, value)? else {
                        return Err(
                            "the link's folder is a lessons.index file beside the page, \
                             as folder=class/lessons.index"
                                .into(),
                        );
                    };
                    if link.folder.replace(url).is_some() {
                        return Err(twice());
                    }
                }
                "step" => {
                    let step = value.parse().ok().filter(|&s| s >= 1).ok_or_else(|| {
                        format!("the link's step is {value:?}, not a step number from 1")
                    })?;
                    if link.step.replace(step).is_some() {
                        return Err(twice());
                    }
                }
                _ => link.settings.push((key.to_string(), value)),
            }
        }
        if link.step.is_some() && link.lesson.is_none() {
            return Err("the link gives a step but no lesson: add lesson=NAME".into());
        }
        if link.folder.is_some() && link.lesson.is_some() {
            return Err("the link gives a folder and a lesson: give one".into());
        }
        link.settings_line()?;
        Ok(link)
    }

    /// The settings in the settings' own words (`docs/guide/settings.md`,
    /// as a lesson writes them), or the word or value refused ("the
    /// link's `fast` is not a setting ..."). No command-line parser reads
    /// them, so a renamed flag breaks no link a teacher sent.
    pub(crate) fn settings_line(&self) -> Result<SettingsLine, String> {
        if self.settings.iter().any(|(key, _)| key == "srgb") {
            return Err("the link's settings: the window shows sRGB always; drop srgb".into());
        }
        let words = self
            .settings
            .iter()
            .map(|(key, value)| match value.is_empty() {
                true => format!("--{key}"),
                false => format!("--{key}={value}"),
            });
        SettingsLine::from_words(words).map_err(|e| match e {
            VocabularyError::Unknown(word) => format!(
                "the link's `{}` is not a setting: a link reads lesson, folder, step, \
                 scene, set and the settings {}",
                word.trim_start_matches("--")
                    .split('=')
                    .next()
                    .unwrap_or_default(),
                WORDS.iter().map(|w| w.name).collect::<Vec<_>>().join(", ")
            ),
            e => format!("the link's settings: {e}"),
        })
    }

    /// The query that opens this link (`?scene=balls_low&spp=4`), its
    /// values percent-encoded; empty when it opens nothing.
    pub(crate) fn query(&self) -> String {
        let mut pairs = Vec::new();
        if let Some(lesson) = &self.lesson {
            pairs.push(format!("lesson={}", encode(lesson.text())));
        }
        if let Some(folder) = &self.folder {
            pairs.push(format!("folder={}", encode(folder)));
        }
        if let Some(step) = self.step {
            pairs.push(format!("step={step}"));
        }
        if let Some(scene) = &self.scene {
            pairs.push(format!("scene={}", encode(scene.text())));
        }
        for (key, value) in &self.settings {
            pairs.push(match value.is_empty() {
                true => key.clone(),
                false => format!("{key}={}", encode(value)),
            });
        }
        match pairs.is_empty() {
            true => String::new(),
            false => format!("?{}", pairs.join("&")),
        }
    }
}

/// The settings flags that turn `base` (the scene's own settings) into
/// `now` (what the window renders with), in the command line's words for
/// [`Link::settings`]: only what differs, so a link stays short. What no
/// flag sets (the camera moved, soft shadows turned off when the scene
/// has them, Keep refining) is left out.
pub(crate) fn settings_flags(now: &RenderSettings, base: &RenderSettings) -> Vec<(String, String)> {
    let mut flags = Vec::new();
    let mut flag = |key: &str, value: String| flags.push((key.to_string(), value));
    if now.width != base.width || now.height != base.height {
        flag("width", now.width.to_string());
        flag("height", now.height.to_string());
    }
    if now.max_depth != base.max_depth {
        flag("depth", now.max_depth.to_string());
    }
    if now.samples != base.samples {
        flag("spp", now.samples.to_string());
    }
    match now.sampling {
        Sampling::Uniform if base.sampling != Sampling::Uniform => {
            flag("sampling", "uniform".into());
        }
        Sampling::Adaptive(knobs) if now.sampling != base.sampling => {
            flag("noise-threshold", knobs.noise_threshold.to_string());
            flag("max-spp", knobs.max_spp.to_string());
            flag("min-spp", knobs.min_spp.to_string());
        }
        _ => {}
    }
    if now.antialiasing != base.antialiasing {
        flag(if now.antialiasing { "aa" } else { "no-aa" }, String::new());
    }
    if now.soft_shadows && !base.soft_shadows {
        flag("soft-shadows", String::new());
    }
    if !now.shadows && base.shadows {
        flag("no-shadows", String::new());
    }
    if now.light_size != base.light_size {
        flag("light-size", now.light_size.to_string());
    }
    if let Some(aperture) = now.lens_override.aperture
        && now.lens_override.aperture != base.lens_override.aperture
    {
        flag("aperture", aperture.to_string());
    }
    if let Some(focal) = now.lens_override.focal
        && now.lens_override.focal != base.lens_override.focal
    {
        flag("focal", focal.to_string());
    }
    if now.depth_of_field && !base.depth_of_field && now.lens_override.aperture.is_none() {
        flag("dof", String::new());
    }
    if now.ambient != base.ambient {
        flag("ambient", now.ambient.to_string());
    }
    if now.accel != base.accel {
        flag("accel", now.accel.name().into());
    }
    if now.grid_multiplier != base.grid_multiplier {
        flag("grid-m", now.grid_multiplier.to_string());
    }
    if now.seed != base.seed {
        flag("seed", now.seed.to_string());
    }
    flags
}

/// `relative` read beside `url`, as a page reads a relative link:
/// `beside("class/lessons.index", "prism.toml")` is `class/prism.toml`.
pub(crate) fn beside(url: &str, relative: &str) -> String {
    match url.rfind('/') {
        Some(slash) => format!("{}/{relative}", &url[..slash]),
        None => relative.to_string(),
    }
}

/// `text` with `+` as a space and `%XX` as that byte, or `None` when an
/// escape is cut short or the bytes are not UTF-8.
pub(crate) fn decode(text: &str) -> Option<String> {
    let mut bytes = Vec::with_capacity(text.len());
    let mut rest = text.bytes();
    while let Some(b) = rest.next() {
        bytes.push(match b {
            b'+' => b' ',
            b'%' => {
                let hex = [rest.next()?, rest.next()?];
                u8::from_str_radix(std::str::from_utf8(&hex).ok()?, 16).ok()?
            }
            b => b,
        });
    }
    String::from_utf8(bytes).ok()
}

/// `text` percent-encoded for a query's value: letters, digits and
/// `-_.~/` as they are, a space as `+`, every other byte as `%XX`.
fn encode(text: &str) -> String {
    text.bytes()
        .map(|b| match b {
            b'a'..=b'z' | b'A'..=b'Z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' | b'/' => {
                char::from(b).to_string()
            }
            b' ' => "+".into(),
            b => format!("%{b:02X}"),
        })
        .collect()
}

#[cfg(test)]
mod tests;
