//! A bare mesh has no camera, lights or materials: [`frame`] gives it a
//! camera looking at its bounds from above and to the side, a key and a
//! fill light, a neutral material (or its MTL colours) and a ground plane
//! under it, so that opening a scanned model shows it at once.

use glam::Vec3;

use super::MeshFile;
use crate::scene::{LightSpec, Material, Object, Primitive, Scene, Viewpoint};

/// What [`frame`] added, for a status line.
pub const FRAMING_NOTE: &str = "framed bare mesh: camera, two lights, ground plane added";

/// Vertical field of view of the framing camera, in degrees.
const FIELD_OF_VIEW: f32 = 40.0;
/// Where the camera stands, seen from the mesh: degrees to the right of +z
/// and above the horizon.
const AZIMUTH: f32 = 35.0;
const ELEVATION: f32 = 16.0;

/// Light grey, a little glossy: shows shape without colouring it.
pub(super) fn neutral_material() -> Material {
    Material {
        diffuse: Vec3::splat(0.8),
        kd: 1.0,
        specular: Vec3::ONE,
        ks: 0.05,
        shine: 40.0,
        transmittance: 0.0,
        ior: 1.0,
    }
}

/// A matte mid grey for the ground.
fn ground_material() -> Material {
    Material {
        diffuse: Vec3::splat(0.55),
        ks: 0.0,
        ..neutral_material()
    }
}

/// The unit vector at `azimuth` degrees around +y from +z and `elevation`
/// degrees above the horizon.
fn direction(azimuth: f32, elevation: f32) -> Vec3 {
    let (az, el) = (azimuth.to_radians(), elevation.to_radians());
    Vec3::new(az.sin() * el.cos(), el.sin(), az.cos() * el.cos())
}

/// A whole scene around `mesh` (y up): its parts with their MTL materials
/// or the neutral one, a ground plane touching its lowest point, a camera
/// that fits its bounding sphere in view, and two white lights.
pub fn frame(mesh: MeshFile) -> Scene {
    let (min, max) = mesh
        .parts
        .iter()
        .flat_map(|p| &p.vertices)
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let (min, max) = if min.cmple(max).all() {
        (min, max)
    } else {
        (Vec3::ZERO, Vec3::ZERO)
    };
    let centre = (min + max) * 0.5;
    // Half the diagonal: the bounding sphere; a flat or point-like mesh
    // still gets a usable distance.
    let radius = ((max - min).length() * 0.5).max(1e-3 * centre.length().max(1.0));
    let distance = radius / (FIELD_OF_VIEW.to_radians() * 0.5).sin() * 1.1;
    let view = Viewpoint {
        from: centre + direction(AZIMUTH, ELEVATION) * distance,
        at: centre,
        up: Vec3::Y,
        angle: FIELD_OF_VIEW,
        width: 640,
        height: 480,
        ..Viewpoint::default()
    };
    let key = centre + direction(AZIMUTH - 60.0, 50.0) * distance * 1.5;
    let fill = centre + direction(AZIMUTH + 70.0, 15.0) * distance * 1.5;
    let lights = vec![
        LightSpec::Point {
            position: key,
            color: Some(Vec3::splat(0.8)),
        },
        LightSpec::Point {
            position: fill,
            color: Some(Vec3::splat(0.35)),
        },
    ];

    let mut materials = vec![neutral_material(), ground_material()];
    let mut objects = Vec::with_capacity(mesh.parts.len() + 1);
    let y = min.y;
    objects.push(Object {
        primitive: Primitive::Plane {
            points: [
                Vec3::new(centre.x, y, centre.z),
                Vec3::new(centre.x + radius, y, centre.z),
                Vec3::new(centre.x, y, centre.z - radius),
            ],
        },
        material: 1,
    });
    for part in mesh.parts {
        let material = match part.material {
            Some(m) => {
                materials.push(m);
                (materials.len() - 1) as u32
            }
            None => 0,
        };
        objects.push(Object {
            primitive: Primitive::Mesh {
                vertices: part.vertices,
                triangles: part.triangles,
            },
            material,
        });
    }
    Scene {
        view,
        background: Vec3::new(0.45, 0.52, 0.6),
        lights,
        materials,
        objects,
        ..Scene::default()
    }
}
