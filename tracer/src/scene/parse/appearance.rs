//! Commands that set how the scene looks rather than what is in it:
//! materials, lights, background, skybox and the rendering hints.

use glam::Vec3;

use super::Parser;
use crate::scene::lexer::Pos;
use crate::scene::{LightSpec, Material, ParseError, ParseErrorKind, rules};

impl Parser<'_, '_> {
    /// `f` with 8 numbers (NFF: `r g b Kd Ks shine T ior`, white specular)
    /// or 11 (P3F: `dr dg db Kd sr sg sb Ks shine T ior`).
    pub(super) fn material(&mut self, pos: Pos) -> Result<(), ParseError> {
        let found = self.cursor.numbers_ahead();
        let material = match found {
            8 | 11 => {
                let diffuse = self.cursor.vec3("the diffuse color")?;
                let kd = self.cursor.number("Kd")?;
                let (specular, ks) = if found == 11 {
                    (
                        self.cursor.vec3("the specular color")?,
                        self.cursor.number("Ks")?,
                    )
                } else {
                    (Vec3::ONE, self.cursor.number("Ks")?)
                };
                Material {
                    diffuse,
                    kd,
                    specular,
                    ks,
                    shine: self.cursor.number("the shininess")?,
                    transmittance: self.cursor.number("the transmittance")?,
                    ior: self.cursor.number("the index of refraction")?,
                }
            }
            _ => return Err(self.wrong_count(pos, "8 (NFF) or 11 (P3F)", found)),
        };
        self.rule(pos, rules::material(&material))?;
        self.push_material(material, pos)?;
        Ok(())
    }

    /// `l x y z [r g b]`: a point light, white when the color is missing.
    pub(super) fn point_light(&mut self, pos: Pos) -> Result<(), ParseError> {
        let found = self.cursor.numbers_ahead();
        if found != 3 && found != 6 {
            return Err(self.wrong_count(pos, "3 or 6", found));
        }
        let position = self.cursor.vec3("the light position")?;
        let color = self.optional_color(found == 6)?;
        self.push_light(LightSpec::Point { position, color }, pos)
    }

    /// `al x y z ax ay az w h [r g b]`: a rectangle centred at x y z facing
    /// ax ay az, with positive width and height.
    pub(super) fn area_light(&mut self, pos: Pos) -> Result<(), ParseError> {
        let found = self.cursor.numbers_ahead();
        if found != 8 && found != 11 {
            return Err(self.wrong_count(pos, "8 or 11", found));
        }
        let centre = self.cursor.vec3("the area light centre")?;
        let aim = self.cursor.vec3("the point the area light faces")?;
        self.rule(pos, rules::area_light_aim(centre, aim))?;
        let mut side = |expected| {
            let pos = self.cursor.here();
            let value = self.cursor.number(expected)?;
            self.rule(pos, rules::area_light_side(value))?;
            Ok(value)
        };
        let width = side("the area light width")?;
        let height = side("the area light height")?;
        let color = self.optional_color(found == 11)?;
        let light = LightSpec::Area {
            centre,
            aim,
            width,
            height,
            color,
        };
        self.push_light(light, pos)
    }

    fn optional_color(&mut self, present: bool) -> Result<Option<Vec3>, ParseError> {
        if present {
            Ok(Some(self.cursor.vec3("the light color")?))
        } else {
            Ok(None)
        }
    }

    fn push_light(&mut self, light: LightSpec, pos: Pos) -> Result<(), ParseError> {
        let count = self.scene.lights.len();
        if count >= self.limits.max_lights {
            return Err(self.above_limit("light count", count, self.limits.max_lights, pos));
        }
        self.scene.lights.push(light);
        Ok(())
    }

    /// `b r g b` (NFF) or `bclr r g b` (P3F).
    pub(super) fn background(&mut self) -> Result<(), ParseError> {
        self.scene.background = self.cursor.vec3("the background color")?;
        Ok(())
    }

    /// `env NAME`: the skybox folder; whether it exists is not the parser's
    /// business (a missing one is a warning when the world is built).
    pub(super) fn env(&mut self) -> Result<(), ParseError> {
        let name = self.cursor.expect("the skybox folder name")?;
        self.scene.env = Some(name.text.to_string());
        Ok(())
    }

    /// `accel k` with k in 0..=2.
    pub(super) fn accel(&mut self) -> Result<(), ParseError> {
        let (value, token) = self
            .cursor
            .integer("the acceleration structure (0, 1 or 2)")?;
        match u32::try_from(value) {
            Ok(k @ 0..=2) => {
                self.scene.accel = Some(k);
                Ok(())
            }
            _ => {
                let why = format!(
                    "must be 0 (none), 1 (grid) or 2 (BVH), found {}",
                    token.text
                );
                Err(self.invalid(token.pos, "acceleration structure", why))
            }
        }
    }

    /// `spp n` with n in `0..=max_spp`.
    pub(super) fn spp(&mut self) -> Result<(), ParseError> {
        let (value, token) = self.cursor.integer("the samples per pixel side")?;
        if value < 0 {
            let why = format!("must not be negative, found {value}");
            return Err(self.invalid(token.pos, "samples per pixel", why));
        }
        let limit = self.limits.max_spp;
        match u32::try_from(value) {
            Ok(n) if n <= limit => {
                self.scene.spp = Some(n);
                Ok(())
            }
            _ => Err(self.cursor.error_at(
                token.pos,
                ParseErrorKind::AboveLimit {
                    what: "samples per pixel side",
                    found: token.text.to_string(),
                    limit: limit.into(),
                },
            )),
        }
    }

    /// `adaptive T` with T a noise threshold in `0..=1`.
    pub(super) fn adaptive(&mut self) -> Result<(), ParseError> {
        let pos = self.cursor.here();
        let threshold = self.cursor.number("the noise threshold")?;
        self.rule(pos, rules::noise_threshold(threshold))?;
        self.scene.adaptive = Some(threshold);
        Ok(())
    }

    /// The count of numbers does not match any form of the command.
    fn wrong_count(&self, pos: Pos, expected: &'static str, found: usize) -> ParseError {
        self.cursor
            .error_at(pos, ParseErrorKind::WrongNumberCount { expected, found })
    }
}
