//! Serialises a scene document back to P3F, so generated or edited scenes
//! can be saved and a parsed scene can be checked by parsing it again.

use std::fmt::{self, Display, Formatter};
use std::path::Path;

use glam::Vec3;

use super::{LightSpec, Material, Object, Primitive, Scene};

/// The scene as P3F text that parses back to an equal [`Scene`] (except
/// `base_dir`). Numbers use Rust's shortest round-trip formatting, so they
/// come back bit-exact.
///
/// Materials are written in order, each `f` just before the first object
/// that uses it, so every object keeps its material index. A scene the
/// parser cannot have produced (an object going back to an earlier
/// material, an index past the end, an `env` name with whitespace) is
/// written as faithfully as P3F allows: such an object gets a repeated
/// `f` line (the default material for a bad index).
pub fn write_p3f(scene: &Scene) -> String {
    P3f(scene).to_string()
}

/// [`write_p3f`] for a file in `folder`: the skybox (`env`) is found
/// relative to the scene file's folder, so a relative `env` of a scene
/// from another folder is written as the absolute path of the same skybox.
pub fn write_p3f_in(scene: &Scene, folder: &Path) -> String {
    let same_folder = |base: &Path| match (base.canonicalize(), folder.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => base == folder,
    };
    let moved_env = match (&scene.env, &scene.base_dir) {
        (Some(env), Some(base)) if Path::new(env).is_relative() && !same_folder(base) => {
            std::path::absolute(base.join(env)).ok()
        }
        _ => None,
    };
    match moved_env.and_then(|p| p.to_str().map(str::to_owned)) {
        Some(env) if !env.contains(char::is_whitespace) => {
            let relocated = Scene {
                env: Some(env),
                ..scene.clone()
            };
            P3f(&relocated).to_string()
        }
        _ => P3f(scene).to_string(),
    }
}

/// One light as its P3F command on one line: the text an edit that adds a
/// light carries.
pub(crate) fn light_command(light: &LightSpec) -> String {
    one_line(|f| write_light(f, light))
}

/// One primitive as its P3F command on one line: the text an edit that
/// replaces an object's geometry carries.
pub(crate) fn primitive_command(primitive: &Primitive) -> String {
    one_line(|f| write_primitive(f, primitive))
}

/// What `write` writes, its lines joined by single spaces (P3F does not
/// care where a command's numbers break).
fn one_line(write: impl Fn(&mut Formatter<'_>) -> fmt::Result) -> String {
    struct Lines<F>(F);
    impl<F: Fn(&mut Formatter<'_>) -> fmt::Result> Display for Lines<F> {
        fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
            (self.0)(f)
        }
    }
    let text = Lines(write).to_string();
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

struct P3f<'a>(&'a Scene);

/// A vector as three space-separated numbers.
pub(crate) struct V(pub Vec3);

impl Display for V {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} {}", self.0.x, self.0.y, self.0.z)
    }
}

impl Display for P3f<'_> {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        let scene = self.0;
        writeln!(f, "# written by Whitted Workbench")?;
        if let Some(accel) = scene.accel {
            writeln!(f, "accel {accel}")?;
        }
        if let Some(spp) = scene.spp {
            writeln!(f, "spp {spp}")?;
        }
        if let Some(threshold) = scene.adaptive {
            writeln!(f, "adaptive {threshold}")?;
        }
        writeln!(f, "bclr {}", V(scene.background))?;
        if let Some(env) = &scene.env {
            writeln!(f, "env {env}")?;
        }
        let view = &scene.view;
        writeln!(f, "v")?;
        writeln!(f, "from {}", V(view.from))?;
        writeln!(f, "at {}", V(view.at))?;
        writeln!(f, "up {}", V(view.up))?;
        writeln!(f, "angle {}", view.angle)?;
        writeln!(f, "hither {}", view.hither)?;
        writeln!(f, "resolution {} {}", view.width, view.height)?;
        writeln!(f, "aperture {}", view.aperture)?;
        writeln!(f, "focal {}", view.focal)?;
        for light in &scene.lights {
            write_light(f, light)?;
        }
        write_objects(f, &scene.materials, &scene.objects)
    }
}

fn write_light(f: &mut Formatter<'_>, light: &LightSpec) -> fmt::Result {
    let color = match light {
        LightSpec::Point { position, color } => {
            write!(f, "l {}", V(*position))?;
            color
        }
        LightSpec::Area {
            centre,
            aim,
            width,
            height,
            color,
        } => {
            write!(f, "al {} {} {width} {height}", V(*centre), V(*aim))?;
            color
        }
    };
    match color {
        Some(color) => writeln!(f, " {}", V(*color)),
        None => writeln!(f),
    }
}

/// Objects in order, with every material written (in order) by the time
/// an object refers to it; unused trailing materials come last.
fn write_objects(f: &mut Formatter<'_>, materials: &[Material], objects: &[Object]) -> fmt::Result {
    let mut written = 0;
    let mut current = None;
    for object in objects {
        let index = usize::try_from(object.material).unwrap_or(usize::MAX);
        if current != Some(index) {
            if index >= written && index < materials.len() {
                for material in materials.get(written..=index).unwrap_or_default() {
                    write_material(f, material)?;
                }
                written = index + 1;
            } else {
                let material = materials.get(index).copied().unwrap_or_default();
                write_material(f, &material)?;
            }
            current = Some(index);
        }
        write_primitive(f, &object.primitive)?;
    }
    for material in materials.get(written..).unwrap_or_default() {
        write_material(f, material)?;
    }
    Ok(())
}

/// Always the 11-number P3F form, which keeps the specular color.
fn write_material(f: &mut Formatter<'_>, m: &Material) -> fmt::Result {
    writeln!(f, "f {}", MaterialValues(m))
}

/// A material's 11 numbers as the P3F `f` line gives them.
pub(crate) struct MaterialValues<'a>(pub &'a Material);

impl Display for MaterialValues<'_> {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        let m = self.0;
        write!(
            f,
            "{} {} {} {} {} {} {}",
            V(m.diffuse),
            m.kd,
            V(m.specular),
            m.ks,
            m.shine,
            m.transmittance,
            m.ior
        )
    }
}

fn write_primitive(f: &mut Formatter<'_>, primitive: &Primitive) -> fmt::Result {
    match primitive {
        Primitive::Sphere {
            centre,
            radius,
            inside_only,
        } => {
            let radius = if *inside_only { -radius } else { *radius };
            writeln!(f, "s {} {radius}", V(*centre))
        }
        Primitive::Plane { points: [a, b, c] } => {
            writeln!(f, "pl {} {} {}", V(*a), V(*b), V(*c))
        }
        Primitive::Polygon { vertices } => {
            writeln!(f, "p {}", vertices.len())?;
            vertices.iter().try_for_each(|v| writeln!(f, "{}", V(*v)))
        }
        Primitive::Patch { vertices, normals } => {
            writeln!(f, "pp {}", vertices.len().min(normals.len()))?;
            vertices
                .iter()
                .zip(normals)
                .try_for_each(|(v, n)| writeln!(f, "{} {}", V(*v), V(*n)))
        }
        Primitive::Cone {
            base,
            base_radius,
            apex,
            apex_radius,
        } => writeln!(f, "c {} {base_radius} {} {apex_radius}", V(*base), V(*apex)),
        Primitive::Box { min, max } => writeln!(f, "box {} {}", V(*min), V(*max)),
        Primitive::Mesh {
            vertices,
            triangles,
        } => {
            writeln!(f, "mesh {} {}", vertices.len(), triangles.len())?;
            for v in vertices {
                writeln!(f, "{}", V(*v))?;
            }
            triangles.iter().try_for_each(|[a, b, c]| {
                let one_based = |i: &u32| u64::from(*i) + 1;
                writeln!(f, "{} {} {}", one_based(a), one_based(b), one_based(c))
            })
        }
    }
}
