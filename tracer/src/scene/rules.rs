//! What makes a value valid in a scene document, said once: the parser
//! reports a broken rule at the offending token, an edit of a parsed scene
//! ([`super::edit`]) refuses the same values with the same words.

use std::ops::RangeInclusive;

use glam::{DVec3, Vec3};

use super::{LightSpec, Material, Primitive, Viewpoint};

/// A broken rule: what the value is and why it cannot be used, as
/// [`super::ParseErrorKind::InvalidValue`] shows them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Invalid {
    pub what: &'static str,
    pub why: String,
}

fn invalid(what: &'static str, why: impl Into<String>) -> Result<(), Invalid> {
    Err(Invalid {
        what,
        why: why.into(),
    })
}

/// Largest N (N x N samples per pixel) a scene file, a render's settings
/// or a slider may ask for.
pub const MAX_SAMPLES: u32 = 64;
/// Largest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest image, in pixels (64 Mi: about 1.3 GB of film).
pub const MAX_IMAGE_PIXELS: u64 = 64 << 20;

/// Adaptive sampling's noise thresholds, in display units: 0 refines every
/// pixel to its maximum, 1 (the whole range of a channel) stops every pixel
/// at its minimum, beyond is meaningless. A scene file's `adaptive`, the
/// command line's `--noise-threshold` (and so lessons) and the window's
/// slider all read this range.
pub const NOISE_THRESHOLD: RangeInclusive<f32> = 0.0..=1.0;
/// The threshold adaptive sampling starts from when none is given: 2.55
/// levels of 255.
pub const DEFAULT_NOISE_THRESHOLD: f32 = 0.01;

/// Whether `threshold` is in [`NOISE_THRESHOLD`].
pub(crate) fn noise_threshold(threshold: f32) -> Result<(), Invalid> {
    if !NOISE_THRESHOLD.contains(&threshold) {
        let (low, high) = NOISE_THRESHOLD.into_inner();
        let why = format!("must lie in {low}..{high}, found {threshold}");
        return invalid("noise threshold", why);
    }
    Ok(())
}

/// Largest sine of the angle between two plane edges that counts as
/// collinear.
const COLLINEAR_SINE: f64 = 1e-6;

/// Largest sine of the angle between `up` and the view direction that still
/// counts as parallel.
const PARALLEL_SINE: f64 = 1e-6;

/// A sphere's radius as the file gives it: a negative one is an
/// inside-only sphere, zero is nothing.
pub(crate) fn sphere_radius(radius: f32) -> Result<(), Invalid> {
    if radius == 0.0 {
        return invalid("sphere radius", "must not be zero");
    }
    Ok(())
}

/// `pl`: three points that span a plane.
pub(crate) fn plane(points: &[Vec3; 3]) -> Result<(), Invalid> {
    let [a, b, c] = points.map(|p| p.as_dvec3());
    let (u, v) = (b - a, c - a);
    if u.cross(v).length() <= COLLINEAR_SINE * u.length() * v.length() {
        return invalid("plane", "its three points are collinear");
    }
    Ok(())
}

/// `c`: the radii as the file gives them (both negative: inside-only).
pub(crate) fn cone_radii(base_radius: f32, apex_radius: f32) -> Result<(), Invalid> {
    let inside_only = base_radius < 0.0 && apex_radius < 0.0;
    if !inside_only && (base_radius < 0.0 || apex_radius < 0.0) {
        let why = "only both radii together may be negative (an inside-only cone)";
        return invalid("cone radius", why);
    }
    if base_radius == 0.0 && apex_radius == 0.0 {
        return invalid("cone radius", "both radii are zero");
    }
    Ok(())
}

/// `c`: an axis of some length.
pub(crate) fn cone_axis(base: Vec3, apex: Vec3) -> Result<(), Invalid> {
    if base == apex {
        return invalid("cone", "base and apex are the same point");
    }
    Ok(())
}

/// `box`: the component-wise corners of a box with volume.
pub(crate) fn aabox(min: Vec3, max: Vec3) -> Result<(), Invalid> {
    if min.cmpeq(max).any() {
        return invalid("box", "it has zero thickness along an axis");
    }
    Ok(())
}

/// `f`: a transmittance between 0 and 1, and an index of refraction
/// above 0 where it is used (opaque materials often carry `ior 0`).
pub(crate) fn material(m: &Material) -> Result<(), Invalid> {
    let t = m.transmittance;
    if !(0.0..=1.0).contains(&t) {
        return invalid("transmittance", format!("must lie in 0..1, found {t}"));
    }
    if t > 0.0 && m.ior <= 0.0 {
        let why = format!(
            "must be greater than 0 for a transmitting material (T {t}), found {}",
            m.ior
        );
        return invalid("index of refraction", why);
    }
    Ok(())
}

/// `al`: a rectangle that faces somewhere.
pub(crate) fn area_light_aim(centre: Vec3, aim: Vec3) -> Result<(), Invalid> {
    if centre == aim {
        return invalid("area light", "it faces its own centre");
    }
    Ok(())
}

/// `al`: one side of the rectangle.
pub(crate) fn area_light_side(side: f32) -> Result<(), Invalid> {
    if side > 0.0 {
        return Ok(());
    }
    invalid(
        "area light size",
        format!("must be greater than 0, found {side}"),
    )
}

/// `v angle`: a field of view that forms an image.
pub(crate) fn view_angle(angle: f32) -> Result<(), Invalid> {
    if angle > 0.0 && angle < 180.0 {
        return Ok(());
    }
    let why = format!("must lie strictly between 0 and 180 degrees, found {angle}");
    invalid("field of view angle", why)
}

/// `v hither` and `v aperture`.
pub(crate) fn non_negative(what: &'static str, value: f32) -> Result<(), Invalid> {
    if value >= 0.0 {
        return Ok(());
    }
    invalid(what, format!("must not be negative, found {value}"))
}

/// `v focal`.
pub(crate) fn focal(focal: f32) -> Result<(), Invalid> {
    if focal > 0.0 {
        return Ok(());
    }
    invalid("focal distance", "must be greater than 0")
}

pub(crate) const FROM_IS_AT: &str = "`from` and `at` are the same point";
pub(crate) const TOO_FAR: &str = "`from` and `at` are too far apart (their distance overflows)";

/// Whether the camera has a view direction and an `up` not parallel to it.
/// Computed in f64 so extreme but finite coordinates cannot overflow.
pub(crate) fn camera(view: &Viewpoint) -> Result<(), &'static str> {
    let wide = |v: Vec3| v.as_dvec3();
    let direction: DVec3 = wide(view.at) - wide(view.from);
    // The renderer works in f32: a distance that underflows to 0 or
    // overflows to infinity there leaves no view direction either.
    let length = (view.at - view.from).length();
    if direction == DVec3::ZERO || length == 0.0 {
        return Err(FROM_IS_AT);
    }
    if !length.is_finite() {
        return Err(TOO_FAR);
    }
    let up = wide(view.up);
    if up == DVec3::ZERO {
        return Err("`up` is the zero vector");
    }
    if direction.cross(up).length() <= PARALLEL_SINE * direction.length() * up.length() {
        return Err("`up` is parallel to the view direction");
    }
    Ok(())
}

/// Every number finite, as the parser reads them: for values an edit
/// computes (a translation can overflow).
fn finite(what: &'static str, values: &[Vec3]) -> Result<(), Invalid> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => invalid(what, format!("must be finite, found {v}")),
        None => Ok(()),
    }
}

/// A whole primitive, by the rules its command follows in the file: for
/// geometry an edit makes or moves rather than reads.
pub(crate) fn primitive(primitive: &Primitive) -> Result<(), Invalid> {
    match primitive {
        Primitive::Sphere { centre, radius, .. } => {
            finite("sphere centre", &[*centre])?;
            finite("sphere radius", &[Vec3::splat(*radius)])?;
            sphere_radius(*radius)
        }
        Primitive::Plane { points } => {
            finite("plane point", points)?;
            plane(points)
        }
        Primitive::Polygon { vertices } => {
            finite("polygon vertex", vertices)?;
            at_least_three("polygon vertex count", vertices.len())
        }
        Primitive::Patch { vertices, normals } => {
            finite("patch vertex", vertices)?;
            finite("patch vertex normal", normals)?;
            at_least_three("patch vertex count", vertices.len())?;
            if normals.len() != vertices.len() {
                let why = format!("{} vertices but {} normals", vertices.len(), normals.len());
                return invalid("patch", why);
            }
            Ok(())
        }
        Primitive::Cone {
            base,
            base_radius,
            apex,
            apex_radius,
        } => {
            finite("cone centre", &[*base, *apex])?;
            finite("cone radius", &[Vec3::new(*base_radius, *apex_radius, 0.0)])?;
            cone_radii(*base_radius, *apex_radius)?;
            cone_axis(*base, *apex)
        }
        Primitive::Box { min, max } => {
            finite("box corner", &[*min, *max])?;
            if min.cmpgt(*max).any() {
                return invalid("box", "its minimum corner is above its maximum");
            }
            aabox(*min, *max)
        }
        Primitive::Mesh {
            vertices,
            triangles,
        } => {
            finite("mesh vertex", vertices)?;
            at_least_three("mesh vertex count", vertices.len())?;
            if triangles.is_empty() {
                return invalid("mesh triangle count", "a mesh needs a triangle");
            }
            let count = vertices.len();
            match triangles.iter().flatten().find(|&&i| i as usize >= count) {
                Some(i) => invalid(
                    "mesh index",
                    format!("{} is out of range for {count} vertices", u64::from(*i) + 1),
                ),
                None => Ok(()),
            }
        }
    }
}

fn at_least_three(what: &'static str, count: usize) -> Result<(), Invalid> {
    if count < 3 {
        return invalid(what, format!("needs at least 3 vertices, found {count}"));
    }
    Ok(())
}

/// A whole light, by the rules of `l` and `al`.
pub(crate) fn light(light: &LightSpec) -> Result<(), Invalid> {
    match light {
        LightSpec::Point { position, color } => {
            finite("light position", &[*position])?;
            finite("light color", color.as_slice())
        }
        LightSpec::Area {
            centre,
            aim,
            width,
            height,
            color,
        } => {
            finite("area light centre", &[*centre, *aim])?;
            finite("light color", color.as_slice())?;
            area_light_aim(*centre, *aim)?;
            area_light_side(*width)?;
            area_light_side(*height)
        }
    }
}

/// A whole camera block, by the rules of `v`: the fields an edit changes.
pub(crate) fn viewpoint(view: &Viewpoint) -> Result<(), Invalid> {
    finite("camera vector", &[view.from, view.at, view.up])?;
    view_angle(view.angle)?;
    non_negative("aperture", view.aperture)?;
    focal(view.focal)?;
    camera(view).or_else(|why| invalid("camera", why))
}
