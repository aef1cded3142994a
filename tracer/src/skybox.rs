//! The `env` skybox: six images on the faces of a cube around the scene,
//! looked up by ray direction with the usual (OpenGL) cube-map convention:
//! right = +x, left = -x, top = +y, bottom = -y, front = +z, back = -z.

use std::path::{Path, PathBuf};

use glam::Vec3A;

/// Face names in the order +x, -x, +y, -y, +z, -z.
pub const FACE_NAMES: [&str; 6] = ["right", "left", "top", "bottom", "front", "back"];

/// Why a skybox could not be loaded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SkyboxError {
    #[error("skybox folder {0} not found")]
    MissingFolder(PathBuf),
    #[error("skybox face `{face}` not found in {dir} (looked for .png, .jpg, .jpeg)")]
    MissingFace { dir: PathBuf, face: &'static str },
    #[error("skybox face {file}: {message}")]
    Unreadable { file: PathBuf, message: String },
}

/// One face: RGB values in [0, 1], as stored (no decoding: the renderer
/// writes values directly by default, so the sky looks as painted).
#[derive(Debug, Clone, PartialEq)]
struct Face {
    width: u32,
    height: u32,
    texels: Vec<Vec3A>,
}

/// Six faces of a sky cube.
#[derive(Debug, Clone, PartialEq)]
pub struct Skybox {
    faces: Vec<Face>,
}

/// Largest face accepted, so a hostile folder cannot exhaust memory.
const MAX_FACE_PIXELS: u64 = 4096 * 4096;

impl Skybox {
    /// Loads the six faces from `dir`.
    pub fn load(dir: &Path) -> Result<Skybox, SkyboxError> {
        if !dir.is_dir() {
            return Err(SkyboxError::MissingFolder(dir.to_path_buf()));
        }
        let faces = FACE_NAMES
            .iter()
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
        Ok(Skybox { faces })
    }

    /// Decodes six encoded images (PNG or JPEG bytes) in [`FACE_NAMES`]
    /// order, for skyboxes embedded in a binary.
    pub fn from_encoded(faces: [&[u8]; 6]) -> Result<Skybox, SkyboxError> {
        let faces = faces
            .iter()
            .zip(FACE_NAMES)
            .map(|(bytes, name)| {
                let img = image::load_from_memory(bytes).map_err(|e| SkyboxError::Unreadable {
                    file: PathBuf::from(name),
                    message: e.to_string(),
                })?;
                Ok(face_from_image(img.to_rgb32f()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Skybox { faces })
    }

    /// Builds a skybox from six faces given as functions of the face's
    /// `(s, t)` coordinates, for generators and tests.
    pub fn from_fn(size: u32, paint: impl Fn(usize, f32, f32) -> Vec3A) -> Skybox {
        let size = size.max(1);
        let faces = (0..6)
            .map(|f| Face {
                width: size,
                height: size,
                texels: (0..size * size)
                    .map(|i| {
                        let s = ((i % size) as f32 + 0.5) / size as f32;
                        let t = ((i / size) as f32 + 0.5) / size as f32;
                        paint(f, s, t)
                    })
                    .collect(),
            })
            .collect();
        Skybox { faces }
    }

    /// The sky's colour in direction `dir` (nearest texel).
    pub fn sample(&self, dir: Vec3A) -> Vec3A {
        let (face, s, t) = cube_face(dir);
        let f = &self.faces[face];
        let x = ((s * f.width as f32) as u32).min(f.width - 1);
        let y = ((t * f.height as f32) as u32).min(f.height - 1);
        f.texels[(y * f.width + x) as usize]
    }
}

/// The face index (in [`FACE_NAMES`] order) and the `(s, t)` coordinates in
/// `[0, 1]` (s to the right, t downwards in the image) that OpenGL's cube-map
/// rules give for `dir`.
pub fn cube_face(dir: Vec3A) -> (usize, f32, f32) {
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
    if w as u64 * h as u64 > MAX_FACE_PIXELS || w == 0 || h == 0 {
        return Err(unreadable(format!("{w}x{h} is outside 1x1..4096x4096")));
    }
    let img = image::open(file)
        .map_err(|e| unreadable(e.to_string()))?
        .to_rgb32f();
    Ok(face_from_image(img))
}

fn face_from_image(img: image::Rgb32FImage) -> Face {
    Face {
        width: img.width(),
        height: img.height(),
        texels: img.pixels().map(|p| Vec3A::from(p.0)).collect(),
    }
}

#[cfg(test)]
mod tests {
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

    #[test]
    fn top_of_side_faces_points_up() {
        // Looking along +z, up (+y) is at the top of the image (small t).
        let (_, _, t) = cube_face(Vec3A::new(0.0, 0.5, 1.0));
        assert!(t < 0.5);
        // Looking along +x, +z is to the left (small s), as seen from inside.
        let (_, s, _) = cube_face(Vec3A::new(1.0, 0.0, 0.5));
        assert!(s < 0.5);
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
}
