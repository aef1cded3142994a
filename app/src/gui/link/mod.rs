//! A link a teacher can send: the web page's query string says what the
//! window opens (`?lesson=shadows`, `?scene=balls_low`). Read here, on
//! every target, so the desktop's tests check what the page will open.

/// What a page's query asks the window to open.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Link {
    /// A bundled lesson's name: opened in the Lessons window, its first
    /// step set up.
    pub lesson: Option<String>,
    /// A bundled scene's name: opened as the scene picker would.
    pub scene: Option<String>,
}

impl Link {
    /// Reads `query` (`?a=b&c=d`, with or without its `?`, values
    /// percent-encoded as browsers write them). A key it does not know,
    /// or one given twice, is an error naming it: a link that silently
    /// opened something else would mislead a whole class.
    pub fn parse(query: &str) -> Result<Self, String> {
        let mut link = Link::default();
        let query = query.strip_prefix('?').unwrap_or(query);
        for pair in query.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
            let value =
                decode(value).ok_or_else(|| format!("the link's {key} is not valid: {value}"))?;
            let slot = match key {
                "lesson" => &mut link.lesson,
                "scene" => &mut link.scene,
                _ => {
                    return Err(format!(
                        "the link asks for {key:?}, which the page does not know: it reads lesson and scene"
                    ));
                }
            };
            if value.is_empty() {
                return Err(format!(
                    "the link's {key} is empty: give a name, as {key}=NAME"
                ));
            }
            if slot.replace(value).is_some() {
                return Err(format!("the link gives {key} twice"));
            }
        }
        Ok(link)
    }
}

/// `text` with `+` as a space and `%XX` as that byte, or `None` when an
/// escape is cut short or the bytes are not UTF-8.
fn decode(text: &str) -> Option<String> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lesson_and_a_scene_are_read_with_or_without_the_question_mark() {
        let both = Link {
            lesson: Some("shadows".into()),
            scene: Some("balls_low".into()),
        };
        assert_eq!(
            Link::parse("?lesson=shadows&scene=balls_low"),
            Ok(both.clone())
        );
        assert_eq!(Link::parse("scene=balls_low&lesson=shadows"), Ok(both));
        assert_eq!(Link::parse(""), Ok(Link::default()));
        assert_eq!(Link::parse("?"), Ok(Link::default()));
    }

    #[test]
    fn values_are_percent_decoded() {
        let link = Link::parse("?scene=my%20scene+two%2Ep3f").unwrap();
        assert_eq!(link.scene.as_deref(), Some("my scene two.p3f"));
        let link = Link::parse("?lesson=%C3%A9t%C3%A9").unwrap();
        assert_eq!(link.lesson.as_deref(), Some("été"));
    }

    #[test]
    fn unknown_repeated_empty_and_broken_values_are_refused_by_name() {
        let error = |query: &str| Link::parse(query).unwrap_err();
        assert!(
            error("?lessons=shadows").contains("\"lessons\""),
            "{}",
            error("?lessons=shadows")
        );
        assert!(error("?lesson=a&lesson=b").contains("lesson twice"));
        assert!(error("?scene=").contains("scene is empty"));
        assert!(error("?scene").contains("scene is empty"));
        assert!(error("?lesson=%4").contains("not valid"));
        assert!(error("?lesson=%zz").contains("not valid"));
        assert!(error("?lesson=%FF").contains("not valid"));
    }
}
