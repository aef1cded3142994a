//! What a lesson's start, a step's setup or a solution does to the state,
//! each value with its place in the lesson file: read by `format`, applied
//! by `state`, so neither needs the other.

use tracer::render::View;
use tracer::render::vocabulary::{Overrides, VocabularyError, split_words};

/// A value with the place in the lesson file it was read from, so a
/// problem found later (an edit the scene refuses) still names its line.
#[derive(Debug, Clone, PartialEq)]
pub struct Located<T> {
    pub value: T,
    pub(crate) line: usize,
    pub(crate) column: usize,
}

/// What a lesson's start, a step's setup or a solution does to the state.
#[derive(Debug, Clone, Default)]
pub(crate) struct Actions {
    /// Side A's settings; their `--set` lines edit A's scene.
    pub(crate) settings: Option<Located<SettingsLine>>,
    /// Scene edits of side A in the `--set` language, in order.
    pub(crate) edits: Vec<Located<String>>,
    /// Compare mode on, side B being A with these flags over it (their
    /// `--set` lines edit B's scene).
    pub(crate) compare: Option<Located<SettingsLine>>,
    /// Scene edits of side B alone, in the `--set` language, after
    /// `compare`: B's scene differs from A's, the point of the layout.
    pub(crate) compare_edits: Vec<Located<String>>,
    /// The pixel pinned for the ray tree and the observer.
    pub(crate) pixel: Option<(u32, u32)>,
    /// The answer typed or picked (solutions only).
    pub(crate) answer: Option<String>,
    /// The image view to show (window layout).
    pub(crate) view: Option<View>,
    /// The observer view on or off (window layout).
    pub(crate) observer: Option<bool>,
}

/// A lesson's line of settings (`"--no-aa --spp 4"`): the settings' own
/// words (`tracer::render::vocabulary`, which no command-line flag's
/// rename changes) and `--set` edits of the scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct SettingsLine {
    pub(crate) overrides: Overrides,
    /// Scene edits in the `--set` language, in order.
    pub(crate) set: Vec<String>,
}

impl SettingsLine {
    /// Reads `text`: words split as a shell splits them, `--set EDIT`
    /// taken out, the rest read by the vocabulary.
    pub(crate) fn parse(text: &str) -> Result<SettingsLine, VocabularyError> {
        Self::from_words(split_words(text)?)
    }

    /// [`SettingsLine::parse`] of words already split (a link's
    /// settings, whose values may hold spaces).
    pub(crate) fn from_words(
        words: impl IntoIterator<Item = String>,
    ) -> Result<SettingsLine, VocabularyError> {
        let mut set = Vec::new();
        let mut settings = Vec::new();
        let mut words = words.into_iter();
        while let Some(word) = words.next() {
            if word == "--set" {
                set.push(words.next().ok_or(VocabularyError::Missing("set"))?);
            } else if let Some(edit) = word.strip_prefix("--set=") {
                set.push(edit.to_string());
            } else {
                settings.push(word);
            }
        }
        Ok(SettingsLine {
            overrides: Overrides::parse(&settings)?,
            set,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_keeps_its_edits_whole_and_reads_the_rest_as_settings() {
        let line =
            SettingsLine::parse("--aa --set 'object 5 ior 1.33' --spp 2 --set=\"camera focal 2\"");
        let line = line.unwrap();
        assert_eq!(line.set, ["object 5 ior 1.33", "camera focal 2"]);
        assert!(line.overrides.aa);
        assert_eq!(line.overrides.spp, Some(2));
        let missing = SettingsLine::parse("--aa --set").unwrap_err();
        assert_eq!(missing.to_string(), "`--set` needs a value");
        let flag = SettingsLine::parse("--srgb").unwrap_err();
        assert!(
            flag.to_string().starts_with("`--srgb` is not a setting"),
            "{flag}"
        );
    }
}
