//! The `v` command: labelled camera fields in any order, then a check that
//! the camera can form an image.

use super::cursor::looks_numeric;
use super::{COMMANDS, Parser};
use crate::scene::lexer::Pos;
use crate::scene::rules::{self, FROM_IS_AT, TOO_FAR};
use crate::scene::{ParseError, ParseErrorKind, Viewpoint};

impl Parser<'_, '_> {
    /// `v` then `from at up angle hither resolution aperture focal` in any
    /// order, until a token that is not one of these labels. A missing field
    /// keeps its [`Viewpoint::default`] value (aperture 0, focal 1); a repeated
    /// one keeps the last value.
    pub(super) fn view(&mut self, v_pos: Pos) -> Result<(), ParseError> {
        let mut view = Viewpoint::default();
        let mut at_pos = None;
        let mut up_pos = None;
        while let Some(label) = self.cursor.peek() {
            match label.text {
                "from" => {
                    self.cursor.next_token();
                    view.from = self.cursor.vec3("the camera position (from)")?;
                }
                "at" => {
                    self.cursor.next_token();
                    at_pos = Some(label.pos);
                    view.at = self.cursor.vec3("the camera target (at)")?;
                }
                "up" => {
                    self.cursor.next_token();
                    up_pos = Some(label.pos);
                    view.up = self.cursor.vec3("the camera up vector")?;
                }
                "angle" => {
                    self.cursor.next_token();
                    view.angle = self.angle()?;
                }
                "hither" => {
                    self.cursor.next_token();
                    view.hither = self.non_negative("hither distance", "the hither distance")?;
                }
                "resolution" => {
                    self.cursor.next_token();
                    (view.width, view.height) = self.resolution()?;
                }
                "aperture" => {
                    self.cursor.next_token();
                    view.aperture = self.non_negative("aperture", "the lens aperture")?;
                }
                "focal" => {
                    self.cursor.next_token();
                    let pos = self.cursor.here();
                    view.focal = self.cursor.number("the focal distance ratio")?;
                    self.rule(pos, rules::focal(view.focal))?;
                }
                word if !looks_numeric(word) && !COMMANDS.contains(&word) => {
                    let kind = ParseErrorKind::UnknownViewField(word.to_string());
                    return Err(self.cursor.error_at(label.pos, kind));
                }
                _ => break,
            }
        }
        rules::camera(&view).map_err(|why| {
            let pos = if why == FROM_IS_AT || why == TOO_FAR {
                at_pos
            } else {
                up_pos
            };
            let kind = ParseErrorKind::DegenerateCamera(why);
            self.cursor.error_at(pos.unwrap_or(v_pos), kind)
        })?;
        self.scene.view = view;
        Ok(())
    }

    fn angle(&mut self) -> Result<f32, ParseError> {
        let pos = self.cursor.here();
        let angle = self.cursor.number("the field of view angle")?;
        self.rule(pos, rules::view_angle(angle))?;
        Ok(angle)
    }

    fn non_negative(
        &mut self,
        what: &'static str,
        expected: &'static str,
    ) -> Result<f32, ParseError> {
        let pos = self.cursor.here();
        let value = self.cursor.number(expected)?;
        self.rule(pos, rules::non_negative(what, value))?;
        Ok(value)
    }

    /// `resolution w h`: both in `1..=max_resolution`, `w * h` at most
    /// `max_pixels`.
    fn resolution(&mut self) -> Result<(u32, u32), ParseError> {
        let limit = self.limits.max_resolution;
        let width_pos = self.cursor.here();
        let mut side = |expected| -> Result<u32, ParseError> {
            let (value, token) = self.cursor.integer(expected)?;
            if value < 1 {
                let why = format!("must be at least 1, found {value}");
                return Err(self.invalid(token.pos, "resolution", why));
            }
            u32::try_from(value)
                .ok()
                .filter(|&v| v <= limit)
                .ok_or_else(|| {
                    let kind = ParseErrorKind::AboveLimit {
                        what: "resolution",
                        found: token.text.to_string(),
                        limit: limit.into(),
                    };
                    self.cursor.error_at(token.pos, kind)
                })
        };
        let width = side("the image width")?;
        let height = side("the image height")?;
        let pixels = u64::from(width) * u64::from(height);
        if pixels > self.limits.max_pixels {
            let kind = ParseErrorKind::AboveLimit {
                what: "pixel count",
                found: format!("{width}x{height} = {pixels}"),
                limit: self.limits.max_pixels,
            };
            return Err(self.cursor.error_at(width_pos, kind));
        }
        Ok((width, height))
    }
}
