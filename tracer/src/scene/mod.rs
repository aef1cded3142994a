//! The scene document: what an NFF/P3F file says, command by command, before
//! anything is prepared for rendering. Parsing produces it, the P3F writer
//! serialises it back, and [`crate::world::World`] is built from it.

pub mod edit;
mod error;
mod lexer;
mod limits;
pub mod mesh_io;
mod parse;
mod rules;
mod write;

#[cfg(test)]
mod tests;

pub use error::{ParseError, ParseErrorKind};
pub use limits::Limits;
pub use parse::{COMMANDS, VIEW_FIELDS, parse_scene, parse_scene_file};
pub use rules::{
    DEFAULT_NOISE_THRESHOLD, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES, NOISE_THRESHOLD,
};
pub use write::{write_p3f, write_p3f_in};

use std::path::PathBuf;

use glam::Vec3;

/// The camera block exactly as the `v` command states it (NFF calls it
/// the viewpoint): where the camera stands, looks and how wide it sees.
#[derive(Debug, Clone, PartialEq)]
pub struct Viewpoint {
    /// The eye's position, in scene units.
    pub from: Vec3,
    /// The point seen at the image's centre.
    pub at: Vec3,
    /// Which way is up in the image; need not be perpendicular to the view, only not parallel.
    pub up: Vec3,
    /// Full vertical field of view in degrees, between the centres of the top
    /// and bottom pixel rows.
    pub angle: f32,
    /// Near clipping distance for eye rays; may be 0.
    pub hither: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Lens diameter as a multiple of the pixel size; 0 is a pinhole.
    pub aperture: f32,
    /// Focal distance as a multiple of the view-plane distance `|at - from|`.
    pub focal: f32,
}

impl Default for Viewpoint {
    fn default() -> Self {
        Self {
            from: Vec3::new(0.0, 0.0, 5.0),
            at: Vec3::ZERO,
            up: Vec3::Y,
            angle: 45.0,
            hither: 0.0,
            width: 512,
            height: 512,
            aperture: 0.0,
            focal: 1.0,
        }
    }
}

impl Viewpoint {
    /// The scene's lens: the viewpoint owns it, so an edit of the camera
    /// is the lens every render of the scene uses, unless the render's
    /// settings override it.
    pub fn lens(&self) -> Lens {
        Lens {
            aperture: self.aperture,
            focal: self.focal,
        }
    }
}

/// A thin lens, as `v` states it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lens {
    /// Diameter as a multiple of the pixel size; 0 is a pinhole.
    pub aperture: f32,
    /// Focal distance as a multiple of the view-plane distance `|at - from|`.
    pub focal: f32,
}

impl Lens {
    /// What a render without depth of field sees through.
    pub const PINHOLE: Lens = Lens {
        aperture: 0.0,
        focal: 1.0,
    };
}

/// A surface material (the `f` command). The NFF 8-number form has a white
/// specular colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Diffuse colour, linear RGB, each 0..1.
    pub diffuse: Vec3,
    /// Diffuse weight, usually 0..1.
    pub kd: f32,
    /// Highlight and mirror colour, linear RGB, each 0..1.
    pub specular: Vec3,
    /// Scales both the highlight and the mirror reflection.
    pub ks: f32,
    /// Blinn-Phong exponent.
    pub shine: f32,
    /// Transmittance; > 0 makes a refracting, two-sided object.
    pub transmittance: f32,
    /// Index of refraction, used only when `transmittance > 0`.
    pub ior: f32,
}

impl Default for Material {
    /// Matte white, for objects that come before any `f` command.
    fn default() -> Self {
        Self {
            diffuse: Vec3::ONE,
            kd: 1.0,
            specular: Vec3::ONE,
            ks: 0.0,
            shine: 1.0,
            transmittance: 0.0,
            ior: 1.0,
        }
    }
}

/// A light as the file states it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightSpec {
    /// `l x y z [r g b]`; a missing colour is left to [`crate::world`] to
    /// decide (white at 1/sqrt(number of lights)).
    Point {
        /// Where the light is.
        position: Vec3,
        /// Linear RGB; `None` leaves it to the world.
        color: Option<Vec3>,
    },
    /// `al x y z ax ay az w h [r g b]`: a rectangle centred at `centre`
    /// facing `aim`, `width` by `height`.
    Area {
        /// The rectangle's centre.
        centre: Vec3,
        /// A point the rectangle faces.
        aim: Vec3,
        /// Extent along the first side, in scene units.
        width: f32,
        /// Extent along the second side, in scene units.
        height: f32,
        /// Linear RGB; `None` leaves it to the world.
        color: Option<Vec3>,
    },
}

impl LightSpec {
    /// Where the light stands: a point light's position, an area light's
    /// centre (what `light N position` edits).
    pub fn position(&self) -> Vec3 {
        match self {
            LightSpec::Point { position, .. } => *position,
            LightSpec::Area { centre, .. } => *centre,
        }
    }

    /// The colour the file gives, if any.
    pub fn color(&self) -> Option<Vec3> {
        match self {
            LightSpec::Point { color, .. } | LightSpec::Area { color, .. } => *color,
        }
    }
}

/// One geometric object as the file states it.
#[derive(Debug, Clone, PartialEq)]
pub enum Primitive {
    /// `s`: a negative radius in the file means only the inside is visible;
    /// `radius` is the absolute value and `inside_only` keeps the flag.
    Sphere {
        /// The centre.
        centre: Vec3,
        /// The radius, > 0.
        radius: f32,
        /// The file gave a negative radius: only the inside is seen.
        inside_only: bool,
    },
    /// `pl`: the infinite plane through three points.
    Plane {
        /// Three points on the plane, not on one line; their winding gives the normal.
        points: [Vec3; 3],
    },
    /// `p`: a planar polygon, possibly concave, n >= 3.
    Polygon {
        /// The corners in order, all in one plane.
        vertices: Vec<Vec3>,
    },
    /// `pp`: a polygon with a normal per vertex (smooth shading).
    Patch {
        /// The corners in order, all in one plane.
        vertices: Vec<Vec3>,
        /// One normal per vertex, interpolated across the polygon.
        normals: Vec<Vec3>,
    },
    /// `c`: an open cone or cylinder between base and apex.
    Cone {
        /// Centre of the base circle.
        base: Vec3,
        /// Radius at the base.
        base_radius: f32,
        /// Centre of the apex circle.
        apex: Vec3,
        /// Radius at the apex; equal radii make a cylinder.
        apex_radius: f32,
    },
    /// `box`: an axis-aligned box.
    Box {
        /// The corner with the smallest coordinates.
        min: Vec3,
        /// The corner with the largest coordinates.
        max: Vec3,
    },
    /// `mesh`: triangles as zero-based vertex indices (the parser has
    /// resolved 1-based and negative indices and checked the range).
    Mesh {
        /// The vertex positions.
        vertices: Vec<Vec3>,
        /// Each triangle's three indices into `vertices`.
        triangles: Vec<[u32; 3]>,
    },
}

impl Primitive {
    /// What the inspector and the statistics call it: "sphere", "mesh", ...
    pub fn kind(&self) -> &'static str {
        match self {
            Primitive::Sphere { .. } => "sphere",
            Primitive::Plane { .. } => "plane",
            Primitive::Polygon { .. } => "polygon",
            Primitive::Patch { .. } => "patch",
            Primitive::Cone { .. } => "cone",
            Primitive::Box { .. } => "box",
            Primitive::Mesh { .. } => "mesh",
        }
    }
}

/// A primitive with the material in force when it was declared.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// Its geometry.
    pub primitive: Primitive,
    /// Index into [`Scene::materials`].
    pub material: u32,
}

/// Where each object was declared in its file, as 1-based (line, column)
/// parallel to [`Scene::objects`]: empty for scenes built in code. Where
/// something was written is not what it is, so positions never make two
/// documents differ (a written and re-read scene equals the original).
#[derive(Debug, Clone, Default)]
pub struct ObjectPositions(
    /// (line, column) of object i, both 1-based.
    pub Vec<(u32, u32)>,
);

impl PartialEq for ObjectPositions {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl ObjectPositions {
    /// Where object `index` was declared, if the scene came from a file.
    pub fn get(&self, index: usize) -> Option<(u32, u32)> {
        self.0.get(index).copied()
    }
}

/// The whole document. Commands may come in any order in the file; the
/// document keeps what they declare, not their order (except objects).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The camera (`v`).
    pub view: Viewpoint,
    /// Colour of rays that hit nothing when there is no `env`, linear RGB (`b`).
    pub background: Vec3,
    /// `env NAME`: a skybox folder, resolved relative to `base_dir`.
    pub env: Option<String>,
    /// The lights (`l`, `al`), in file order.
    pub lights: Vec<LightSpec>,
    /// The materials (`f`), in file order; objects refer to them by index.
    pub materials: Vec<Material>,
    /// The objects, in file order: the index edits and the inspector use.
    pub objects: Vec<Object>,
    /// Where each object was declared (for the inspector).
    pub object_positions: ObjectPositions,
    /// `accel k`: 0 none, 1 uniform grid, 2 BVH.
    pub accel: Option<u32>,
    /// `spp n`: 0 one centred sample, n > 0 n x n jittered samples.
    pub spp: Option<u32>,
    /// `adaptive T`: anti-aliasing spends its samples adaptively, each
    /// pixel refining until its estimated error is below the noise
    /// threshold T, from N^2 / 4 to (2N)^2 samples with `spp`'s N (a
    /// workbench extension of P3F, as `spp` suggests, not imposes).
    pub adaptive: Option<f32>,
    /// Folder of the scene file, for resolving `env`; `None` for in-memory text.
    pub base_dir: Option<PathBuf>,
    /// What the parser noticed that did not stop it (a `mesh_file`'s
    /// missing MTL materials), each naming file, line and column: shown
    /// with the world's warnings.
    pub warnings: Vec<String>,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            view: Viewpoint::default(),
            background: Vec3::ZERO,
            env: None,
            lights: Vec::new(),
            materials: Vec::new(),
            objects: Vec::new(),
            object_positions: ObjectPositions::default(),
            accel: None,
            spp: None,
            adaptive: None,
            base_dir: None,
            warnings: Vec::new(),
        }
    }
}
