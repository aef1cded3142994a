//! The scene prepared for rendering: polygons and meshes become triangles,
//! materials are pre-multiplied, lights get their colours and areas, the
//! skybox is loaded. Built once per scene, shared by every render of it.

use std::ops::Range;
use std::sync::Arc;

use glam::Vec3A;

use crate::geometry::{AaBox, Aabb, Cone, Plane, Shape, Sphere, Triangle, triangulate_polygon};
use crate::optics::bounded;
use crate::scene::edit::{Edit, Effect};
use crate::scene::{LightSpec, Material, Primitive, Scene, Viewpoint};
use crate::skybox::{Skybox, SkyboxError};
use crate::stats::SceneCounts;

/// Which shapes [`World::update_shapes`] changed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ShapeChange {
    /// None: a structure over the shapes stays valid as it is.
    None,
    /// These shapes (one object's) were made again in their place, as many
    /// as before, each of the kind it was (a sphere is still a sphere): a
    /// structure over them can be refitted around them.
    InPlace(Range<u32>),
    /// Shapes were added, removed or changed kind (a polygon triangulated
    /// anew into fewer triangles): the structure must be built again.
    Renumbered,
}

/// A material in the form shading wants it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Diffuse colour times Kd, each component within
    /// `optics::MAX_RADIANCE` (a product of two huge but finite
    /// numbers would be infinite).
    pub diffuse: Vec3A,
    /// Specular colour times Ks, bounded the same way: weights both the
    /// highlight and the mirror.
    pub specular: Vec3A,
    /// The Blinn-Phong exponent, at least 0: a negative one would make the
    /// highlight grow without bound away from the mirror direction.
    pub shine: f32,
    /// Share of light passing through, 0..1; > 0 refracts.
    pub transmittance: f32,
    /// Index of refraction, used when `transmittance > 0`.
    pub ior: f32,
}

impl From<&Material> for Surface {
    fn from(m: &Material) -> Self {
        Self {
            diffuse: bounded(Vec3A::from(m.diffuse) * m.kd),
            specular: bounded(Vec3A::from(m.specular) * m.ks),
            shine: m.shine.max(0.0),
            transmittance: m.transmittance,
            ior: m.ior,
        }
    }
}

/// A light ready for shading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// The point light's position, or the centre of an area light.
    pub position: Vec3A,
    /// Within `optics::MAX_RADIANCE`, like a surface's colours.
    pub color: Vec3A,
    /// For `al` lights, the rectangle's two edge vectors (full width and
    /// height); point lights get a square of the "light size" setting when
    /// soft shadows are on.
    pub area: Option<(Vec3A, Vec3A)>,
}

/// Everything the tracer needs about a scene, independent of render settings.
#[derive(Debug, Clone)]
pub struct World {
    /// The scene's camera block.
    pub view: Viewpoint,
    /// The shapes rays test; acceleration structures index into this list.
    pub shapes: Vec<Shape>,
    /// Index into `surfaces` for each shape.
    pub shape_surface: Vec<u32>,
    /// Index of the scene object (`Scene::objects`) each shape came from:
    /// a mesh's triangles share one, for the views and the inspector.
    pub shape_object: Vec<u32>,
    /// Each scene object's kind ("sphere", "mesh", ...).
    pub object_kinds: Vec<&'static str>,
    /// Where each scene object was declared in its file (line, column).
    pub object_positions: crate::scene::ObjectPositions,
    /// The materials; `shape_surface` gives each shape's.
    pub surfaces: Vec<Surface>,
    /// The lights, each with its colour decided.
    pub lights: Vec<Light>,
    /// Colour of rays that hit nothing, without a sky; linear RGB.
    pub background: Vec3A,
    /// Shared, so that a world cloned to follow an edit does not copy
    /// the sky's six faces (most of a material edit's time, before).
    pub skybox: Option<Arc<Skybox>>,
    /// Bounds of all bounded shapes (empty when there are none).
    pub bounds: Aabb,
    /// What the scene holds, for the statistics.
    pub counts: SceneCounts,
    /// Things the user should know that did not stop the build (a missing
    /// skybox, degenerate triangles skipped).
    pub warnings: Vec<String>,
}

impl World {
    /// Prepares `scene` for rendering. Never fails: what cannot be rendered
    /// (degenerate triangles, a missing skybox) is skipped with a warning.
    pub fn build(scene: &Scene) -> World {
        Self::build_with_skybox(scene, |name| {
            let dir = scene
                .base_dir
                .as_deref()
                .unwrap_or_else(|| std::path::Path::new("."))
                .join(name);
            Skybox::load(&dir)
        })
    }

    /// Like [`World::build`], with `load_skybox` resolving the `env` name:
    /// for scenes that do not come from a folder (embedded in a binary).
    pub fn build_with_skybox(
        scene: &Scene,
        load_skybox: impl FnOnce(&str) -> Result<Skybox, SkyboxError>,
    ) -> World {
        let mut builder = Builder::default();
        let mut shape_object = Vec::new();
        let mut object_kinds = Vec::with_capacity(scene.objects.len());
        for (i, object) in scene.objects.iter().enumerate() {
            let kind = builder.add(&object.primitive, object.material);
            shape_object.resize(builder.shapes.len(), i as u32);
            object_kinds.push(kind);
        }

        let mut warnings = scene.warnings.clone();
        if builder.degenerate > 0 {
            warnings.push(format!(
                "skipped {} degenerate primitive(s) (zero area or zero size)",
                builder.degenerate
            ));
        }
        if scene.objects.is_empty() {
            warnings.push("the scene has no objects: the image shows only the background".into());
        }
        let skybox = scene.env.as_ref().and_then(|name| match load_skybox(name) {
            Ok(sky) => Some(Arc::new(sky)),
            Err(e) => {
                warnings.push(format!("{e}; using the background colour"));
                None
            }
        });

        let lights = lights(&scene.lights);
        let surfaces = surfaces(&scene.materials);
        let shape_surface = clamped(&surfaces, builder.materials.iter().copied()).collect();
        World {
            view: scene.view.clone(),
            counts: SceneCounts {
                objects_by_kind: kind_counts(&object_kinds),
                primitives: builder.shapes.len(),
                triangles: triangle_count(&builder.shapes),
                lights: lights.len(),
            },
            bounds: bounds(&builder.shapes),
            shapes: builder.shapes,
            shape_surface,
            shape_object,
            object_kinds,
            object_positions: scene.object_positions.clone(),
            surfaces,
            lights,
            background: Vec3A::from(scene.background),
            skybox,
            warnings,
        }
    }

    /// Brings the world in step with `scene` after `edit` was applied to
    /// it, rebuilding only what the edit's [`Effect`] touches: the surfaces
    /// for a material, one object's shapes for a move, the lights, the
    /// view. The skybox and every other shape are kept, so the structure
    /// over the shapes stays valid unless the effect is
    /// [`Effect::Geometry`]. The result is what [`World::build`] makes of
    /// the edited scene (tested), but for the warnings: an edit adds one if
    /// it skips degenerate shapes, and keeps those of the first build.
    pub fn update(&mut self, scene: &Scene, edit: &Edit) {
        self.update_shapes(scene, edit);
    }

    /// [`World::update`], saying which shapes it changed, for the
    /// structure over them to follow ([`crate::accel::SceneIndex::refit`]).
    pub fn update_shapes(&mut self, scene: &Scene, edit: &Edit) -> ShapeChange {
        match edit.kind() {
            Effect::Geometry => {
                return match edit {
                    Edit::Object { index, .. } => self.update_object(scene, *index),
                    _ => ShapeChange::Renumbered,
                };
            }
            Effect::Shading => {
                self.surfaces = surfaces(&scene.materials);
                let materials = self.shape_object.iter().map(|&o| {
                    let object = scene.objects.get(o as usize);
                    object.map_or(u32::MAX, |object| object.material)
                });
                let shape_surface: Vec<u32> = clamped(&self.surfaces, materials).collect();
                self.shape_surface = shape_surface;
            }
            Effect::Lights => {
                self.lights = lights(&scene.lights);
                self.counts.lights = self.lights.len();
            }
            Effect::Camera => self.view = scene.view.clone(),
        }
        ShapeChange::None
    }

    /// Object `index`'s shapes built again from `scene`, in their place
    /// (a world's shapes are in object order).
    fn update_object(&mut self, scene: &Scene, index: usize) -> ShapeChange {
        let (Some(object), Some(kind)) =
            (scene.objects.get(index), self.object_kinds.get_mut(index))
        else {
            return ShapeChange::Renumbered;
        };
        let start = self.shape_object.partition_point(|&o| (o as usize) < index);
        let end = self
            .shape_object
            .partition_point(|&o| (o as usize) <= index);
        let mut builder = Builder::default();
        *kind = builder.add(&object.primitive, object.material);
        let count = builder.shapes.len();
        let same_kinds = count == end - start
            && (self.shapes[start..end].iter())
                .zip(&builder.shapes)
                .all(|(old, new)| std::mem::discriminant(old) == std::mem::discriminant(new));
        let change = if same_kinds {
            ShapeChange::InPlace(start as u32..end as u32)
        } else {
            ShapeChange::Renumbered
        };
        let materials = clamped(&self.surfaces, builder.materials.iter().copied());
        self.shape_surface.splice(start..end, materials);
        self.shapes.splice(start..end, builder.shapes);
        let owner = std::iter::repeat_n(index as u32, count);
        self.shape_object.splice(start..end, owner);
        self.counts.objects_by_kind = kind_counts(&self.object_kinds);
        self.counts.primitives = self.shapes.len();
        self.counts.triangles = triangle_count(&self.shapes);
        self.bounds = bounds(&self.shapes);
        if builder.degenerate > 0 {
            self.warnings.push(format!(
                "object {index}: skipped {} degenerate primitive(s) (zero area or zero size)",
                builder.degenerate
            ));
        }
        change
    }

    /// The surface of shape `index`.
    #[inline]
    pub fn surface(&self, shape: u32) -> &Surface {
        &self.surfaces[self.shape_surface[shape as usize] as usize]
    }

    /// Radiance seen along a ray that hits nothing.
    #[inline]
    pub fn background(&self, dir: Vec3A) -> Vec3A {
        match &self.skybox {
            Some(sky) => sky.sample(dir),
            None => self.background,
        }
    }
}

/// The surfaces of `materials`; the default material's alone when there
/// are none, so every shape has one.
fn surfaces(materials: &[Material]) -> Vec<Surface> {
    let mut surfaces: Vec<Surface> = materials.iter().map(Surface::from).collect();
    if surfaces.is_empty() {
        surfaces.push(Surface::from(&Material::default()));
    }
    surfaces
}

/// Material indices as surface indices. An index beyond the table can
/// only come from a hand-built scene: clamped instead of panicking in the
/// hot loop.
fn clamped(
    surfaces: &[Surface],
    materials: impl Iterator<Item = u32>,
) -> impl Iterator<Item = u32> {
    let last = surfaces.len().saturating_sub(1) as u32;
    materials.map(move |m| m.min(last))
}

/// How many objects of each kind, sorted by kind.
fn kind_counts(kinds: &[&'static str]) -> Vec<(&'static str, usize)> {
    let mut counts: Vec<(&'static str, usize)> = Vec::new();
    for &kind in kinds {
        match counts.iter_mut().find(|(k, _)| *k == kind) {
            Some((_, n)) => *n += 1,
            None => counts.push((kind, 1)),
        }
    }
    counts.sort_unstable();
    counts
}

fn triangle_count(shapes: &[Shape]) -> usize {
    shapes
        .iter()
        .filter(|s| matches!(s, Shape::Triangle(_)))
        .count()
}

/// Bounds of all bounded shapes.
fn bounds(shapes: &[Shape]) -> Aabb {
    shapes
        .iter()
        .filter_map(Shape::bounds)
        .fold(Aabb::empty(), |acc, b| acc.union(&b))
}

/// Lights with their colours resolved: NFF leaves a light's intensity to the
/// renderer, and a light without a colour is white at `1 / sqrt(n)` for `n`
/// lights in the scene (Eric Haines's suggestion), so adding lights does not
/// simply wash the image out.
fn lights(specs: &[LightSpec]) -> Vec<Light> {
    let default_color = Vec3A::splat(1.0 / (specs.len().max(1) as f32).sqrt());
    specs
        .iter()
        .map(|spec| match *spec {
            LightSpec::Point { position, color } => Light {
                position: position.into(),
                color: color.map_or(default_color, |c| bounded(c.into())),
                area: None,
            },
            LightSpec::Area {
                centre,
                aim,
                width,
                height,
                color,
            } => {
                let centre = Vec3A::from(centre);
                let normal = (Vec3A::from(aim) - centre).normalize_or(Vec3A::NEG_Y);
                let (u, v) = perpendicular_basis(normal);
                Light {
                    position: centre,
                    color: color.map_or(default_color, |c| bounded(c.into())),
                    area: Some((u * width, v * height)),
                }
            }
        })
        .collect()
}

/// Two unit vectors perpendicular to `n` and to each other.
pub(crate) fn perpendicular_basis(n: Vec3A) -> (Vec3A, Vec3A) {
    let helper = if n.x.abs() < 0.9 { Vec3A::X } else { Vec3A::Y };
    let u = n.cross(helper).normalize();
    (u, n.cross(u))
}

#[derive(Default)]
struct Builder {
    shapes: Vec<Shape>,
    materials: Vec<u32>,
    degenerate: usize,
}

impl Builder {
    /// Adds the shapes of one primitive; returns its kind for the counts.
    fn add(&mut self, primitive: &Primitive, material: u32) -> &'static str {
        self.add_shapes(primitive, material);
        primitive.kind()
    }

    fn add_shapes(&mut self, primitive: &Primitive, material: u32) {
        match primitive {
            Primitive::Sphere { centre, radius, .. } => {
                self.push(
                    Some(Shape::Sphere(Sphere::new((*centre).into(), *radius))),
                    material,
                );
            }
            Primitive::Plane { points } => {
                let plane = Plane::from_points(points.map(Vec3A::from)).map(Shape::Plane);
                self.push(plane, material);
            }
            Primitive::Polygon { vertices } => {
                self.add_polygon(vertices, None, material);
            }
            Primitive::Patch { vertices, normals } => {
                self.add_polygon(vertices, Some(normals), material);
            }
            Primitive::Cone {
                base,
                base_radius,
                apex,
                apex_radius,
            } => {
                let cone = Cone::new((*base).into(), *base_radius, (*apex).into(), *apex_radius);
                self.push(cone.map(Shape::Cone), material);
            }
            Primitive::Box { min, max } => {
                let b = AaBox::new(Vec3A::from(*min), Vec3A::from(*max));
                self.push(Some(Shape::Box(b)), material);
            }
            Primitive::Mesh {
                vertices,
                triangles,
            } => {
                self.shapes.reserve(triangles.len());
                self.materials.reserve(triangles.len());
                for tri in triangles {
                    let [a, b, c] = tri.map(|i| vertices.get(i as usize).map(|&v| Vec3A::from(v)));
                    let shape = match (a, b, c) {
                        (Some(a), Some(b), Some(c)) => Triangle::new(a, b, c).map(Shape::Triangle),
                        _ => None,
                    };
                    self.push(shape, material);
                }
            }
        }
    }

    fn add_polygon(
        &mut self,
        vertices: &[glam::Vec3],
        normals: Option<&[glam::Vec3]>,
        material: u32,
    ) {
        let points: Vec<Vec3A> = vertices.iter().map(|&v| v.into()).collect();
        let Ok(triangles) = triangulate_polygon(&points) else {
            self.degenerate += 1;
            return;
        };
        for [a, b, c] in triangles {
            let [a, b, c] = [a, b, c].map(|i| i as usize);
            let corners = [points.get(a), points.get(b), points.get(c)];
            let [Some(&pa), Some(&pb), Some(&pc)] = corners else {
                self.degenerate += 1;
                continue;
            };
            let shape = match normals {
                Some(ns) => match (ns.get(a), ns.get(b), ns.get(c)) {
                    (Some(&na), Some(&nb), Some(&nc)) => {
                        Triangle::with_normals(pa, pb, pc, [na.into(), nb.into(), nc.into()])
                    }
                    _ => None,
                },
                None => Triangle::new(pa, pb, pc),
            };
            self.push(shape.map(Shape::Triangle), material);
        }
    }

    fn push(&mut self, shape: Option<Shape>, material: u32) {
        match shape {
            Some(shape) => {
                self.shapes.push(shape);
                self.materials.push(material);
            }
            None => self.degenerate += 1,
        }
    }
}
