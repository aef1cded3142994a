//! The `env` skybox: six images on the faces of a cube around the scene,
//! looked up by ray direction with the usual (OpenGL) cube-map convention:
//! right = +x, left = -x, top = +y, bottom = -y, front = +z, back = -z.
//! A sky painted for that convention stands upright in a y-up scene;
//! [`Skybox::upright`] turns it for a scene whose up is another axis.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use glam::{Mat3A, Quat, Vec3, Vec3A};
use rayon::prelude::*;

/// Face names in the order +x, -x, +y, -y, +z, -z.
pub const FACE_NAMES: [&str; 6] = ["right", "left", "top", "bottom", "front", "back"];

/// Why a skybox could not be loaded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SkyboxError {
    /// The `env` folder does not exist.
    #[error("skybox folder {0} not found")]
    MissingFolder(PathBuf),
    /// A face image is missing from the folder.
    #[error("skybox face `{face}` not found in {dir} (looked for .png, .jpg, .jpeg)")]
    MissingFace {
        /// The skybox folder.
        dir: PathBuf,
        /// The face's file stem, e.g. "px".
        face: &'static str,
    },
    /// A face image that cannot be decoded.
    #[error("skybox face {file}: {message}")]
    Unreadable {
        /// The image file.
        file: PathBuf,
        /// The decoder's message.
        message: String,
    },
}

/// One face of a sky decoded ahead of time: `width * height` texels of
/// three bytes (red, green, blue), row by row from the top left.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb8Face {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 3` bytes, RGB, row by row.
    pub bytes: &'static [u8],
}

/// One face: RGB values in [0, 1], as stored (no decoding: the renderer
/// writes values directly by default, so the sky looks as painted).
#[derive(Debug, Clone, PartialEq)]
struct Face {
    width: u32,
    height: u32,
    texels: Texels,
}

/// A face's texels in the form its image came in.
#[derive(Debug, Clone, PartialEq)]
enum Texels {
    /// An 8-bit image's own bytes, turned into `[0, 1]` on lookup as the
    /// `image` crate turns them (`v / 255`): a sixteenth of the memory of
    /// floats, which made the bundled sky's six faces megabytes of fresh
    /// pages at every start. Borrowed when they were decoded before the
    /// program ran (a sky embedded in a binary, see [`Skybox::from_rgb8`]).
    Bytes(Cow<'static, [[u8; 3]]>),
    /// Deeper images and painted skies, as floats.
    Floats(Vec<Vec3A>),
}

impl Texels {
    #[inline]
    fn get(&self, i: usize) -> Vec3A {
        match self {
            Texels::Bytes(bytes) => {
                let [r, g, b] = bytes[i];
                Vec3A::new(unit(r), unit(g), unit(b))
            }
            Texels::Floats(floats) => floats[i],
        }
    }
}

/// An 8-bit value in `[0, 1]`, exactly as `image`'s `to_rgb32f` gives it.
#[inline]
fn unit(v: u8) -> f32 {
    v as f32 / u8::MAX as f32
}

/// Six faces of a sky cube.
#[derive(Debug, Clone, PartialEq)]
pub struct Skybox {
    faces: Vec<Face>,
    /// Turns a scene direction into the cube's, whose up is +y: the
    /// identity unless [`Skybox::upright`] stood the sky on another axis.
    to_cube: Mat3A,
}

/// Largest face accepted, so a hostile folder cannot exhaust memory.
const MAX_FACE_PIXELS: u64 = 4096 * 4096;

/// Whether a face of `width` x `height` texels is one we accept: at least
/// one texel, at most [`MAX_FACE_PIXELS`].
fn face_size_allowed(width: u32, height: u32) -> bool {
    width > 0 && height > 0 && width as u64 * height as u64 <= MAX_FACE_PIXELS
}

impl Skybox {
    /// Loads the six faces from `dir`.
    pub fn load(dir: &Path) -> Result<Skybox, SkyboxError> {
        if !dir.is_dir() {
            return Err(SkyboxError::MissingFolder(dir.to_path_buf()));
        }
        let faces = FACE_NAMES
            .par_iter()
            .map(|&face| {
                let file = ["png", "jpg", "jpeg"]
                    .iter()
                    .map(|ext| dir.join(format!("{face}.{ext}")))
                    .find(|p| p.is_file())
                    .ok_or_else(|| SkyboxError::MissingFace {
                        dir: dir.to_path_buf(),
                        face,
                    })?;
                load_face(&file)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Skybox::of(faces))
    }

    fn of(faces: Vec<Face>) -> Skybox {
        Skybox {
            faces,
            to_cube: Mat3A::IDENTITY,
        }
    }

    /// A skybox from six faces already decoded to 8-bit RGB, in
    /// [`FACE_NAMES`] order: a sky embedded in a binary, decoded when it
    /// was built, costs no decoding and no copy at each start (decoding
    /// the bundled sky's six PNGs was a visible part of every `workbench
    /// render`).
    pub fn from_rgb8(faces: [Rgb8Face; 6]) -> Result<Skybox, SkyboxError> {
        let faces = faces
            .into_iter()
            .zip(FACE_NAMES)
            .map(|(face, name)| {
                let texels = face.width as u64 * face.height as u64;
                if !face_size_allowed(face.width, face.height)
                    || face.bytes.len() as u64 != texels * 3
                {
                    return Err(SkyboxError::Unreadable {
                        file: PathBuf::from(name),
                        message: format!(
                            "{} bytes are not the RGB texels of a {}x{} face within 1x1..4096x4096",
                            face.bytes.len(),
                            face.width,
                            face.height
                        ),
                    });
                }
                Ok(Face {
                    width: face.width,
                    height: face.height,
                    texels: Texels::Bytes(Cow::Borrowed(bytemuck::cast_slice(face.bytes))),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Skybox::of(faces))
    }

    /// Builds a skybox from six faces given as functions of the face's
    /// `(s, t)` coordinates, for generators and tests.
    pub fn from_fn(size: u32, paint: impl Fn(usize, f32, f32) -> Vec3A) -> Skybox {
        let size = size.max(1);
        let faces = (0..6)
            .map(|f| Face {
                width: size,
                height: size,
                texels: Texels::Floats(
                    (0..size * size)
                        .map(|i| {
                            let s = ((i % size) as f32 + 0.5) / size as f32;
                            let t = ((i / size) as f32 + 0.5) / size as f32;
                            paint(f, s, t)
                        })
                        .collect(),
                ),
            })
            .collect();
        Skybox::of(faces)
    }

    /// This sky stood upright for a scene whose up is `up`: the cube's +y
    /// (its top face, the zenith of a sky painted for OpenGL's convention)
    /// turns onto `up` by the shortest rotation. A sky that is not the
    /// scene's own (a fallback) needs it: a z-up scene would otherwise see
    /// the ground half of a y-up sky above its horizon. A zero or
    /// non-finite `up` leaves the sky as it is.
    pub fn upright(mut self, up: Vec3) -> Skybox {
        let Some(up) = up.try_normalize() else {
            return self;
        };
        self.to_cube = Mat3A::from_quat(Quat::from_rotation_arc(up, Vec3::Y));
        self
    }

    /// The sky's colour in direction `dir` (nearest texel).
    pub fn sample(&self, dir: Vec3A) -> Vec3A {
        let (face, s, t) = cube_face(self.to_cube * dir);
        let f = &self.faces[face];
        let x = ((s * f.width as f32) as u32).min(f.width - 1);
        let y = ((t * f.height as f32) as u32).min(f.height - 1);
        f.texels.get((y * f.width + x) as usize)
    }
}

/// The face index (in [`FACE_NAMES`] order) and the `(s, t)` coordinates in
/// `[0, 1]` (s to the right, t downwards in the image) that OpenGL's cube-map
/// rules give for `dir`.
pub(crate) fn cube_face(dir: Vec3A) -> (usize, f32, f32) {
    let a = dir.abs();
    let (face, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
        if dir.x > 0.0 {
            (0, -dir.z, -dir.y, a.x)
        } else {
            (1, dir.z, -dir.y, a.x)
        }
    } else if a.y >= a.z {
        if dir.y > 0.0 {
            (2, dir.x, dir.z, a.y)
        } else {
            (3, dir.x, -dir.z, a.y)
        }
    } else if dir.z > 0.0 {
        (4, dir.x, -dir.y, a.z)
    } else {
        (5, -dir.x, -dir.y, a.z)
    };
    if ma == 0.0 || !ma.is_finite() {
        return (4, 0.5, 0.5);
    }
    (face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0))
}

fn load_face(file: &Path) -> Result<Face, SkyboxError> {
    let unreadable = |message: String| SkyboxError::Unreadable {
        file: file.to_path_buf(),
        message,
    };
    let reader = image::ImageReader::open(file)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| unreadable(e.to_string()))?;
    let (w, h) = reader
        .into_dimensions()
        .map_err(|e| unreadable(e.to_string()))?;
    if !face_size_allowed(w, h) {
        return Err(unreadable(format!("{w}x{h} is outside 1x1..4096x4096")));
    }
    let img = image::open(file).map_err(|e| unreadable(e.to_string()))?;
    Ok(face_from_image(img))
}

/// A face from a decoded image: its bytes if it has 8 bits per channel,
/// floats otherwise.
fn face_from_image(img: image::DynamicImage) -> Face {
    let (width, height) = (img.width(), img.height());
    let texels = if img.color().bytes_per_pixel() / img.color().channel_count() == 1 {
        Texels::Bytes(img.to_rgb8().pixels().map(|p| p.0).collect())
    } else {
        Texels::Floats(img.to_rgb32f().pixels().map(|p| Vec3A::from(p.0)).collect())
    };
    Face {
        width,
        height,
        texels,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn each_axis_samples_its_face_centre() {
        let axes = [
            Vec3A::X,
            Vec3A::NEG_X,
            Vec3A::Y,
            Vec3A::NEG_Y,
            Vec3A::Z,
            Vec3A::NEG_Z,
        ];
        for (i, axis) in axes.iter().enumerate() {
            let (face, s, t) = cube_face(*axis);
            assert_eq!(face, i, "{axis}");
            assert!((s - 0.5).abs() < 1e-6 && (t - 0.5).abs() < 1e-6);
        }
    }

    /// The OpenGL cube-map table (the specification's "Selection of cube
    /// map images"), written out here rather than borrowed from
    /// [`cube_face`]: for each face, the direction at `(s, t)`, where the
    /// spec gives `s = (sc / |ma| + 1) / 2` and `t = (tc / |ma| + 1) / 2`
    /// with, per major axis, +x: sc = -rz, tc = -ry; -x: sc = +rz,
    /// tc = -ry; +y: sc = +rx, tc = +rz; -y: sc = +rx, tc = -rz; +z:
    /// sc = +rx, tc = -ry; -z: sc = -rx, tc = -ry.
    pub(crate) fn opengl_direction(face: usize, s: f32, t: f32) -> Vec3A {
        let (sc, tc) = (2.0 * s - 1.0, 2.0 * t - 1.0);
        let d = match face {
            0 => Vec3A::new(1.0, -tc, -sc),
            1 => Vec3A::new(-1.0, -tc, sc),
            2 => Vec3A::new(sc, 1.0, tc),
            3 => Vec3A::new(sc, -1.0, -tc),
            4 => Vec3A::new(sc, -tc, 1.0),
            5 => Vec3A::new(-sc, -tc, -1.0),
            _ => unreachable!("six faces"),
        };
        d.normalize()
    }

    /// Texels that say where they are: red the face (in eighths), green s,
    /// blue t of the texel centre.
    pub(crate) fn labelled_sky(size: u32) -> Skybox {
        Skybox::from_fn(size, |face, s, t| Vec3A::new(face as f32 / 8.0, s, t))
    }

    /// The face and texel centre a colour of [`labelled_sky`] names.
    pub(crate) fn label(colour: Vec3A) -> (usize, f32, f32) {
        ((colour.x * 8.0).round() as usize, colour.y, colour.z)
    }

    #[test]
    fn every_texel_is_seen_where_the_opengl_table_puts_it() {
        let size = 8;
        let sky = labelled_sky(size);
        for face in 0..6 {
            for j in 0..size {
                for i in 0..size {
                    let s = (i as f32 + 0.5) / size as f32;
                    let t = (j as f32 + 0.5) / size as f32;
                    // Any length: only the direction counts.
                    let dir = opengl_direction(face, s, t) * (1.0 + (i * 7 + j) as f32);
                    let (f, s2, t2) = label(sky.sample(dir));
                    assert_eq!((f, s2, t2), (face, s, t), "{dir}");
                }
            }
        }
    }

    #[test]
    fn the_sky_painter_uses_the_opengl_table() {
        for face in 0..6 {
            for (s, t) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.35), (0.3, 0.95)] {
                let painted = crate::generate::sky::face_direction(face, s, t);
                let expected = opengl_direction(face, s, t);
                assert!(
                    (painted - expected).length() < 1e-6,
                    "face {face} ({s}, {t})"
                );
            }
        }
    }

    /// A sky painted with a smooth function of the direction (through the
    /// table, not the sampler) is smooth across every one of the cube's
    /// twelve edges: a swapped or mirrored face breaks it at its edges.
    #[test]
    fn the_sky_is_continuous_across_all_twelve_cube_edges() {
        let size = 64;
        let colour = |d: Vec3A| d.normalize() * 0.5 + 0.5;
        let sky = Skybox::from_fn(size, |face, s, t| colour(opengl_direction(face, s, t)));
        // A texel spans about 2 / size radians at a face's edge.
        let texel = 2.0 / size as f32;
        let axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
        let mut edges = 0;
        for a in 0..3 {
            for b in a + 1..3 {
                let c = 3 - a - b;
                for (sa, sb) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                    edges += 1;
                    for k in 0..=20 {
                        let w = -0.95 + 0.095 * k as f32;
                        let on_edge = axes[a] * sa + axes[b] * sb + axes[c] * w;
                        // Just inside each of the two faces.
                        let into_a = sky.sample(on_edge + axes[a] * sa * 1e-3);
                        let into_b = sky.sample(on_edge + axes[b] * sb * 1e-3);
                        let truth = colour(on_edge);
                        for seen in [into_a, into_b] {
                            assert!(
                                (seen - truth).abs().max_element() < texel,
                                "edge {sa}{a} {sb}{b} at {on_edge}: {seen} vs {truth}"
                            );
                        }
                    }
                }
            }
        }
        assert_eq!(edges, 12);
    }

    #[test]
    fn upright_turns_the_top_face_onto_the_scene_up() {
        let sky = labelled_sky(4);
        // y up: nothing turns.
        assert_eq!(sky.clone().upright(Vec3::Y), sky);
        let z_up = sky.clone().upright(Vec3::new(0.0, 0.0, 2.0));
        assert_eq!(label(z_up.sample(Vec3A::Z)).0, 2, "zenith on top");
        assert_eq!(label(z_up.sample(Vec3A::NEG_Z)).0, 3, "ground below");
        // The horizon of a z-up scene is the cube's side faces.
        for dir in [Vec3A::X, Vec3A::NEG_X, Vec3A::Y, Vec3A::NEG_Y] {
            let face = label(z_up.sample(dir)).0;
            assert!(![2, 3].contains(&face), "{dir}: face {face}");
        }
        // A tilted up gets the zenith too, and a zero up changes nothing.
        let up = Vec3::new(0.3, -0.2, 1.0);
        let tilted = sky.clone().upright(up);
        assert_eq!(label(tilted.sample(Vec3A::from(up))).0, 2);
        assert_eq!(sky.clone().upright(Vec3::ZERO), sky);
    }

    /// Through a camera: each pixel shows the texel the table puts in the
    /// direction of the pixel's eye ray, for cameras facing several faces.
    #[test]
    fn camera_pixels_see_the_texels_of_their_directions() {
        use crate::accel::{AccelKind, SceneIndex};
        use crate::render::{RenderSettings, render};
        use crate::scene::{Limits, parse_scene};
        use crate::world::World;
        use std::sync::Arc;

        let size = 64;
        // Nearest-texel lookup: a direction is within half a texel
        // diagonal, about 0.71 * 2 / size radians, of its texel's centre.
        let texel = 1.5 / size as f32;
        for (from, at, up) in [
            ("0 0 0", "0 0 1", "0 1 0"),
            ("0 0 0", "1 0 0", "0 1 0"),
            ("1 2 3", "1 -5 3", "0 0 1"),
            ("0 0 0", "-1 0.6 -0.8", "0.2 1 0"),
        ] {
            let text = format!(
                "env sky
v from {from} at {at} up {up} angle 70 hither 0 resolution 24 16
"
            );
            let scene = parse_scene(&text, None, &Limits::default()).unwrap();
            let world = Arc::new(World::build_with_skybox(&scene, |_| Ok(labelled_sky(size))));
            let settings = RenderSettings {
                width: 24,
                height: 16,
                ..RenderSettings::default()
            };
            let camera = settings.render_camera(&world.view).unwrap();
            let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
            let (film, _) = render(world, index, settings, Some(1)).unwrap();
            for y in 0..16 {
                for x in 0..24 {
                    let dir = camera
                        .ray(x as f32 + 0.5, y as f32 + 0.5, glam::Vec2::ZERO)
                        .dir
                        .normalize();
                    let (face, s, t) = label(film.pixel(x, y).unwrap());
                    let seen = opengl_direction(face, s, t);
                    let angle = seen.dot(dir).clamp(-1.0, 1.0).acos();
                    assert!(
                        angle < texel,
                        "camera at {from} to {at}, pixel ({x}, {y}): texel ({face}, {s}, {t}) \
                         is {angle} rad off the ray {dir}"
                    );
                }
            }
        }
    }

    #[test]
    fn loads_six_faces_from_a_folder_and_samples_them() {
        let dir = crate::scratch::Scratch::new("skybox");
        for (i, name) in FACE_NAMES.iter().enumerate() {
            let v = (i as u8 + 1) * 40;
            let img = image::RgbImage::from_pixel(4, 4, image::Rgb([v, 0, 0]));
            img.save(dir.join(format!("{name}.png"))).unwrap();
        }
        let sky = Skybox::load(&dir).unwrap();
        let c = sky.sample(Vec3A::NEG_Y);
        assert!((c.x - 160.0 / 255.0).abs() < 1e-6, "{c}");
        std::fs::remove_file(dir.join("back.png")).unwrap();
        assert!(matches!(
            Skybox::load(&dir),
            Err(SkyboxError::MissingFace { face: "back", .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(matches!(
            Skybox::load(&dir),
            Err(SkyboxError::MissingFolder(_))
        ));
    }

    /// Faces decoded ahead of time are read in place, texel for texel as
    /// the same image decoded at run time; bytes that are not a face's
    /// RGB texels are an error naming the face, not a panic.
    #[test]
    fn rgb8_faces_read_as_their_decoded_image() {
        static BYTES: [u8; 12] = [0, 51, 255, 10, 20, 30, 40, 50, 60, 255, 128, 1];
        let face = Rgb8Face {
            width: 2,
            height: 2,
            bytes: &BYTES,
        };
        let sky = Skybox::from_rgb8([face; 6]).unwrap();
        let image = image::RgbImage::from_raw(2, 2, BYTES.to_vec()).unwrap();
        let decoded = face_from_image(image::DynamicImage::ImageRgb8(image));
        assert_eq!(sky.faces[0], decoded);

        let short = Rgb8Face {
            bytes: &BYTES[..11],
            ..face
        };
        let mut faces = [face; 6];
        faces[3] = short;
        let error = Skybox::from_rgb8(faces).unwrap_err().to_string();
        assert!(error.contains("bottom") && error.contains("2x2"), "{error}");
        let empty = Rgb8Face {
            width: 0,
            height: 0,
            bytes: &[],
        };
        assert!(Skybox::from_rgb8([empty; 6]).is_err());
    }

    /// An 8-bit face keeps its bytes, yet every texel reads back as the
    /// very float `to_rgb32f` gives (the image is the same bit for bit); a
    /// 16-bit face keeps floats.
    #[test]
    fn an_8_bit_face_reads_as_image_converts_it() {
        let ramp = image::RgbImage::from_fn(256, 2, |x, y| {
            let v = x as u8;
            image::Rgb([v, v.wrapping_mul(7), (255 - v) ^ y as u8])
        });
        let face = face_from_image(image::DynamicImage::ImageRgb8(ramp.clone()));
        assert!(matches!(face.texels, Texels::Bytes(_)));
        let floats = image::DynamicImage::ImageRgb8(ramp).to_rgb32f();
        for (i, p) in floats.pixels().enumerate() {
            assert_eq!(face.texels.get(i), Vec3A::from(p.0), "texel {i}");
        }
        let deep = image::DynamicImage::ImageRgb16(image::ImageBuffer::from_pixel(
            2,
            2,
            image::Rgb([65535u16, 1, 32768]),
        ));
        let face = face_from_image(deep);
        assert!(matches!(face.texels, Texels::Floats(_)));
        assert_eq!(face.texels.get(3).x, 1.0);
        assert!(face.texels.get(3).y > 0.0 && face.texels.get(3).y < 1.0 / 255.0);
    }
}
