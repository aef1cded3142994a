//! The settings' own words: one list of names ([`WORDS`]) that a lesson's
//! `settings = "--no-aa --spp 4"`, the command line's flags and a page's
//! link all mean the same thing by. [`Overrides`] is what a line of them
//! says, read here without any command-line parser, so a flag renamed in
//! the `workbench` binary breaks no lesson a teacher wrote. The ranges a
//! value must fall in stay with [`RenderSettings::validate`].

use crate::accel::AccelKind;

use super::{RenderSettings, Sampling};

/// What a word takes after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Takes {
    /// Nothing: the word alone turns something on (or off, for `no-...`).
    Nothing,
    /// A whole number (`--spp 4`).
    Whole,
    /// A number (`--ambient 0.3`).
    Number,
    /// One of these names (`--accel grid`).
    OneOf(&'static [&'static str]),
}

/// One setting's name, what it takes and what it sets: a line of
/// `docs/guide/settings.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Word {
    /// Written `--NAME` in a lesson, on the command line and in a link's key.
    pub name: &'static str,
    /// Its value, if any.
    pub takes: Takes,
    /// What it sets, for the docs and messages.
    pub sets: &'static str,
}

const fn word(name: &'static str, takes: Takes, sets: &'static str) -> Word {
    Word { name, takes, sets }
}

/// Every setting a lesson, a link or the command line can give, in the
/// order [`Overrides::apply`] applies them.
pub const WORDS: &[Word] = &[
    word("width", Takes::Whole, "the image's width in pixels"),
    word("height", Takes::Whole, "the image's height in pixels"),
    word(
        "depth",
        Takes::Whole,
        "the most bounces a ray makes (reflection and refraction)",
    ),
    word(
        "aa",
        Takes::Nothing,
        "anti-aliasing on: N x N jittered samples per pixel",
    ),
    word("spp", Takes::Whole, "N, for N x N samples per pixel"),
    word(
        "sampling",
        Takes::OneOf(&["uniform", "adaptive"]),
        "how anti-aliasing spends its samples (adaptive turns anti-aliasing on)",
    ),
    word(
        "noise-threshold",
        Takes::Number,
        "adaptive: the estimated error a pixel stops below (turns adaptive on)",
    ),
    word(
        "min-spp",
        Takes::Whole,
        "adaptive: the samples every pixel takes first",
    ),
    word(
        "max-spp",
        Takes::Whole,
        "adaptive: the samples no pixel exceeds",
    ),
    word(
        "no-aa",
        Takes::Nothing,
        "anti-aliasing off: one ray through each pixel's centre",
    ),
    word(
        "soft-shadows",
        Takes::Nothing,
        "point lights become squares, sampled",
    ),
    word(
        "no-shadows",
        Takes::Nothing,
        "no shadow rays: every light reaches every point",
    ),
    word(
        "light-size",
        Takes::Number,
        "the side of a soft shadow's square light",
    ),
    word(
        "aperture",
        Takes::Number,
        "the lens's diameter in pixels (above 0 turns depth of field on)",
    ),
    word(
        "dof",
        Takes::Nothing,
        "depth of field on (the scene's lens)",
    ),
    word(
        "focal",
        Takes::Number,
        "the sharp plane's distance, times the view distance",
    ),
    word("ambient", Takes::Number, "the ambient light's intensity"),
    word(
        "accel",
        Takes::OneOf(&["none", "grid", "bvh"]),
        "the acceleration structure",
    ),
    word("grid-m", Takes::Number, "the uniform grid's multiplier m"),
    word("seed", Takes::Whole, "the seed of the jittered samples"),
];

/// A word that is not one of [`WORDS`], or a value it cannot take.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum VocabularyError {
    /// A word that is no setting's `--NAME`.
    #[error("`{0}` is not a setting; the settings are {list}", list = names())]
    Unknown(String),
    /// A word that takes a value ended the line.
    #[error("`--{0}` needs a value")]
    Missing(&'static str),
    /// A value the word cannot take.
    #[error("`--{name}` takes {wanted}, not `{value}`")]
    Value {
        /// The word.
        name: &'static str,
        /// What was written after it.
        value: String,
        /// What it takes, in words.
        wanted: String,
    },
    /// `--aa=yes`: a switch given a value.
    #[error("`--{0}` takes no value")]
    Unwanted(&'static str),
    /// A quote opened and never closed.
    #[error("a {quote} quote is not closed in \"{text}\"")]
    Unclosed {
        /// The quote opened.
        quote: char,
        /// The whole line.
        text: String,
    },
}

/// `text` split into words as a shell splits them, at whitespace outside
/// single or double quotes, the quotes removed: a line of settings as a
/// lesson writes it (`--set 'object 5 ior 1.33'` keeps its edit whole).
pub fn split_words(text: &str) -> Result<Vec<String>, VocabularyError> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote = None;
    for c in text.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_default().push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_default();
            }
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, c) => word.get_or_insert_default().push(c),
        }
    }
    if let Some(q) = quote {
        return Err(VocabularyError::Unclosed {
            quote: q,
            text: text.to_string(),
        });
    }
    words.extend(word);
    Ok(words)
}

/// `--width, --height, ...`, for messages.
fn names() -> String {
    let names: Vec<String> = WORDS.iter().map(|w| format!("--{}", w.name)).collect();
    names.join(", ")
}

/// How anti-aliasing spends its samples, as `--sampling` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SamplingChoice {
    /// N x N samples in every pixel.
    Uniform,
    /// Samples where each pixel's estimated error asks for them.
    Adaptive,
}

/// What a line of settings changes; anything left out keeps the scene's
/// value (or the tracer's default).
#[derive(Debug, Clone, Default, PartialEq)]
#[allow(missing_docs)] // each field is its word in [`WORDS`]
pub struct Overrides {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub depth: Option<u32>,
    pub aa: bool,
    pub spp: Option<u32>,
    pub sampling: Option<SamplingChoice>,
    pub noise_threshold: Option<f32>,
    pub min_spp: Option<u32>,
    pub max_spp: Option<u32>,
    pub no_aa: bool,
    pub soft_shadows: bool,
    pub no_shadows: bool,
    pub light_size: Option<f32>,
    pub aperture: Option<f32>,
    pub dof: bool,
    pub focal: Option<f32>,
    pub ambient: Option<f32>,
    pub accel: Option<AccelKind>,
    pub grid_m: Option<f32>,
    pub seed: Option<u64>,
}

impl Overrides {
    /// Reads words such as `--no-aa`, `--spp 4` or `--accel=grid`. A word
    /// given twice keeps its last value; `--aa` and `--no-aa` (or
    /// `--soft-shadows` and `--no-shadows`) are separate words, applied in
    /// [`WORDS`]' order whatever the order written.
    pub fn parse<S: AsRef<str>>(words: &[S]) -> Result<Overrides, VocabularyError> {
        let mut overrides = Overrides::default();
        let mut words = words.iter().map(AsRef::as_ref);
        while let Some(written) = words.next() {
            let unknown = || VocabularyError::Unknown(written.to_string());
            let bare = written.strip_prefix("--").ok_or_else(unknown)?;
            let (name, inline) = match bare.split_once('=') {
                Some((name, value)) => (name, Some(value)),
                None => (bare, None),
            };
            let word = WORDS.iter().find(|w| w.name == name).ok_or_else(unknown)?;
            let value = match (word.takes, inline) {
                (Takes::Nothing, Some(_)) => return Err(VocabularyError::Unwanted(word.name)),
                (Takes::Nothing, None) => "",
                (_, Some(value)) => value,
                (_, None) => words.next().ok_or(VocabularyError::Missing(word.name))?,
            };
            overrides.set(word, value)?;
        }
        Ok(overrides)
    }

    /// Sets `word` to `value` (empty for a word that takes nothing).
    fn set(&mut self, word: &Word, value: &str) -> Result<(), VocabularyError> {
        let bad = |wanted: &str| VocabularyError::Value {
            name: word.name,
            value: value.to_string(),
            wanted: wanted.to_string(),
        };
        let whole = || value.parse::<u32>().map_err(|_| bad("a whole number"));
        let number = || {
            value
                .parse::<f32>()
                .ok()
                .filter(|n| n.is_finite())
                .ok_or_else(|| bad("a number"))
        };
        match word.name {
            "width" => self.width = Some(whole()?),
            "height" => self.height = Some(whole()?),
            "depth" => self.depth = Some(whole()?),
            "aa" => self.aa = true,
            "spp" => self.spp = Some(whole()?),
            "sampling" => {
                self.sampling = Some(match value {
                    "uniform" => SamplingChoice::Uniform,
                    "adaptive" => SamplingChoice::Adaptive,
                    _ => return Err(bad("uniform or adaptive")),
                })
            }
            "noise-threshold" => self.noise_threshold = Some(number()?),
            "min-spp" => self.min_spp = Some(whole()?),
            "max-spp" => self.max_spp = Some(whole()?),
            "no-aa" => self.no_aa = true,
            "soft-shadows" => self.soft_shadows = true,
            "no-shadows" => self.no_shadows = true,
            "light-size" => self.light_size = Some(number()?),
            "aperture" => self.aperture = Some(number()?),
            "dof" => self.dof = true,
            "focal" => self.focal = Some(number()?),
            "ambient" => self.ambient = Some(number()?),
            "accel" => self.accel = Some(value.parse().map_err(|_| bad("none, grid or bvh"))?),
            "grid-m" => self.grid_m = Some(number()?),
            "seed" => self.seed = Some(value.parse().map_err(|_| bad("a whole number"))?),
            // A word of WORDS this match forgot: a test sets every word.
            other => return Err(VocabularyError::Unknown(format!("--{other}"))),
        }
        Ok(())
    }

    /// Applies the overrides to settings taken from the scene, in
    /// [`WORDS`]' order: `--no-aa` after `--spp` and `--sampling`, the
    /// aperture before `--dof`.
    pub fn apply(&self, s: &mut RenderSettings) {
        if let Some(w) = self.width {
            s.width = w;
        }
        if let Some(h) = self.height {
            s.height = h;
        }
        if let Some(d) = self.depth {
            s.max_depth = d;
        }
        if self.aa {
            s.antialiasing = true;
        }
        if let Some(n) = self.spp {
            s.set_samples(n.max(1));
        }
        self.apply_sampling(s);
        if self.no_aa {
            s.antialiasing = false;
        }
        if self.soft_shadows {
            s.soft_shadows = true;
        }
        if self.no_shadows {
            s.shadows = false;
        }
        if let Some(size) = self.light_size {
            s.light_size = size;
        }
        if let Some(a) = self.aperture {
            s.lens_override.aperture = Some(a);
            s.depth_of_field = a > 0.0;
        }
        if self.dof {
            s.depth_of_field = true;
        }
        if let Some(f) = self.focal {
            s.lens_override.focal = Some(f);
        }
        if let Some(a) = self.ambient {
            s.ambient = a;
        }
        if let Some(a) = self.accel {
            s.accel = a;
        }
        if let Some(m) = self.grid_m {
            s.grid_multiplier = m;
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
    }

    /// `--sampling` and the adaptive knobs: adaptive sampling (with
    /// anti-aliasing on) from N's defaults, or the settings' own adaptive
    /// sampling (the scene's, its bounds following `--spp`), with the
    /// knobs given; `--sampling uniform` wins over them.
    fn apply_sampling(&self, s: &mut RenderSettings) {
        let knobs =
            self.noise_threshold.is_some() || self.min_spp.is_some() || self.max_spp.is_some();
        match self.sampling {
            Some(SamplingChoice::Uniform) => {
                s.sampling = Sampling::Uniform;
                return;
            }
            None if !knobs => return,
            _ => {}
        }
        s.sample_adaptively(|adaptive| {
            if let Some(t) = self.noise_threshold {
                adaptive.noise_threshold = t;
            }
            if let Some(max) = self.max_spp {
                adaptive.max_spp = max;
                adaptive.min_spp = adaptive.min_spp.min(max);
            }
            if let Some(min) = self.min_spp {
                adaptive.min_spp = min;
            }
        });
        s.antialiasing = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value each word takes, as a teacher would write it.
    fn sample(word: &Word) -> &'static str {
        match word.takes {
            Takes::Nothing => "",
            Takes::Whole => "3",
            Takes::Number => "0.25",
            Takes::OneOf(names) => names[0],
        }
    }

    #[test]
    fn every_word_sets_something_of_its_own() {
        let mut seen = Vec::new();
        for word in WORDS {
            let mut line = vec![format!("--{}", word.name)];
            if word.takes != Takes::Nothing {
                line.push(sample(word).to_string());
            }
            let overrides = Overrides::parse(&line).unwrap_or_else(|e| panic!("{line:?}: {e}"));
            assert_ne!(overrides, Overrides::default(), "{line:?} set nothing");
            assert!(
                !seen.contains(&overrides),
                "{line:?} sets what another word sets"
            );
            seen.push(overrides);
        }
    }

    /// The user guide's page lists every word, in this order.
    #[test]
    fn the_settings_page_lists_every_word() {
        let page = include_str!("../../../docs/guide/settings.md");
        let listed: Vec<&str> = page
            .lines()
            .filter_map(|l| l.strip_prefix("| `--")?.split('`').next())
            .collect();
        let words: Vec<&str> = WORDS.iter().map(|w| w.name).collect();
        assert_eq!(listed, words);
    }

    #[test]
    fn a_line_splits_at_spaces_outside_quotes() {
        assert_eq!(split_words(" a  ''  'b c'd ").unwrap(), ["a", "", "b cd"]);
        let open = split_words("--set 'object 5").unwrap_err().to_string();
        assert!(open.contains("' quote is not closed"), "{open}");
    }

    #[test]
    fn a_line_reads_values_inline_or_after_and_the_last_wins() {
        let overrides = Overrides::parse(&["--no-aa", "--spp", "4", "--accel=grid", "--spp=2"]);
        let expected = Overrides {
            no_aa: true,
            spp: Some(2),
            accel: Some(AccelKind::Grid),
            ..Overrides::default()
        };
        assert_eq!(overrides, Ok(expected));
    }

    #[test]
    fn a_wrong_word_or_value_is_named() {
        let cases: [(&[&str], &str); 6] = [
            (
                &["--fast"],
                "`--fast` is not a setting; the settings are --width, --height",
            ),
            (&["spp", "4"], "`spp` is not a setting"),
            (&["--spp"], "`--spp` needs a value"),
            (
                &["--spp", "four"],
                "`--spp` takes a whole number, not `four`",
            ),
            (
                &["--accel", "kd"],
                "`--accel` takes none, grid or bvh, not `kd`",
            ),
            (&["--aa=yes"], "`--aa` takes no value"),
        ];
        for (line, said) in cases {
            let error = Overrides::parse(line).unwrap_err().to_string();
            assert!(error.starts_with(said), "{line:?}: {error}");
        }
        let nan = Overrides::parse(&["--ambient", "NaN"]).unwrap_err();
        assert!(nan.to_string().contains("takes a number"), "{nan}");
    }

    #[test]
    fn no_aa_wins_over_adaptive_and_aperture_turns_the_lens_on() {
        let mut settings = RenderSettings::default();
        let overrides = Overrides::parse(&["--no-aa", "--sampling", "adaptive", "--aperture", "2"]);
        overrides.unwrap().apply(&mut settings);
        assert!(!settings.antialiasing);
        assert!(matches!(settings.sampling, Sampling::Adaptive(_)));
        assert!(settings.depth_of_field);
        assert_eq!(settings.lens_override.aperture, Some(2.0));
    }

    #[test]
    fn an_adaptive_knob_turns_adaptive_and_anti_aliasing_on_unless_uniform_is_said() {
        let mut settings = RenderSettings {
            antialiasing: false,
            ..RenderSettings::default()
        };
        let knob = Overrides::parse(&["--noise-threshold", "0.02"]).unwrap();
        knob.apply(&mut settings);
        assert!(settings.antialiasing);
        let Sampling::Adaptive(adaptive) = &settings.sampling else {
            panic!("{:?}", settings.sampling);
        };
        assert_eq!(adaptive.noise_threshold, 0.02);
        let uniform = Overrides::parse(&["--noise-threshold", "0.02", "--sampling", "uniform"]);
        let mut settings = RenderSettings::default();
        uniform.unwrap().apply(&mut settings);
        assert_eq!(settings.sampling, Sampling::Uniform);
    }
}
