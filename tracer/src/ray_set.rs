//! The rays `workbench bench --rays` and the `rays` criterion bench cast,
//! the set Embree's `rtcIntersect1`/`rtcOccluded1` figures are measured on,
//! so our rays/s and theirs compare the structure, not the ray mix:
//!
//! - eye rays: one through each pixel centre, tile by tile (16 x 16 pixels,
//!   row-major inside a tile and tiles row by row), closest hit, so
//!   neighbouring rays follow each other as in a frame;
//! - shadow rays: for each eye ray that hits, one per light the surface
//!   faces (its geometric normal, turned towards the eye, has N . L > 0),
//!   from the hit point lifted `SHADOW_OFFSET` along that normal, ending
//!   at the light; any hit.

use glam::Vec3A;

use crate::accel::SceneIndex;
use crate::camera::Camera;
use crate::geometry::Ray;
use crate::render::Tile;
use crate::stats::Counters;
use crate::world::World;

/// Side of the square tiles eye rays are cast in, in pixels.
pub(crate) const RAY_TILE: u32 = 16;

/// How far shadow rays start off the surface, along its normal (the
/// Embree benchmark's offset, in scene units).
pub(crate) const SHADOW_OFFSET: f32 = 1e-4;

/// A shadow ray and the distance to its light, where it stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowRay {
    /// From the surface towards the light sample.
    pub ray: Ray,
    /// Distance to the light sample: occluders beyond it do not count.
    pub distance: f32,
}

/// The eye rays of one frame in tile order and the shadow rays from their
/// hits, in the same order (a hit's rays light by light).
#[derive(Debug, Clone)]
pub struct RaySet {
    /// One per pixel, tile after tile (`RAY_TILE` pixels square).
    pub eye: Vec<Ray>,
    /// Eye rays ignore hits nearer than this (the camera's hither).
    pub hither: f32,
    /// How many eye rays each tile has, in order: tile `i`'s rays follow
    /// tile `i - 1`'s.
    pub tile_rays: Vec<usize>,
    /// The shadow rays, tile by tile.
    pub shadow: Vec<ShadowRay>,
}

impl RaySet {
    /// The ray set of `camera`'s frame of `world`; the shadow rays start
    /// from the hits `index` finds (every structure finds the same ones).
    pub fn new(world: &World, index: &SceneIndex, camera: &Camera) -> RaySet {
        let tiles = Tile::grid(camera.width(), camera.height(), RAY_TILE);
        let mut eye = Vec::with_capacity(camera.width() as usize * camera.height() as usize);
        for tile in &tiles {
            for y in tile.y..tile.y + tile.height {
                for x in tile.x..tile.x + tile.width {
                    eye.push(camera.ray(x as f32 + 0.5, y as f32 + 0.5, glam::Vec2::ZERO));
                }
            }
        }
        let hither = camera.hither();
        let mut counters = Counters::default();
        let mut shadow = Vec::new();
        for ray in &eye {
            let Some(hit) =
                index.closest_hit(&world.shapes, ray, hither, f32::INFINITY, &mut counters)
            else {
                continue;
            };
            let p = ray.at(hit.t);
            let n = world.shapes[hit.shape as usize].normal_at(p).geometric;
            let n = if n.dot(ray.dir) > 0.0 { -n } else { n };
            shadow.extend(shadow_rays(p + n * SHADOW_OFFSET, n, world));
        }
        RaySet {
            tile_rays: tiles.iter().map(Tile::pixel_count).collect(),
            eye,
            hither,
            shadow,
        }
    }

    /// The eye rays tile by tile.
    pub fn eye_tiles(&self) -> impl Iterator<Item = &[Ray]> {
        let mut rest = self.eye.as_slice();
        self.tile_rays.iter().map(move |&n| {
            let (tile, tail) = rest.split_at(n);
            rest = tail;
            tile
        })
    }
}

/// The shadow rays from `origin` on a surface with normal `n` to each
/// light of `world` the surface faces.
fn shadow_rays(origin: Vec3A, n: Vec3A, world: &World) -> impl Iterator<Item = ShadowRay> + '_ {
    world.lights.iter().filter_map(move |light| {
        let to_light = light.position - origin;
        (to_light.dot(n) > 0.0).then(|| ShadowRay {
            ray: Ray::new(origin, to_light),
            distance: to_light.length(),
        })
    })
}

/// Casts `rays` for their closest hits from `t_min`, counting the work in
/// `counters`; returns how many hit.
pub fn cast_eye(
    index: &SceneIndex,
    world: &World,
    rays: &[Ray],
    t_min: f32,
    counters: &mut Counters,
) -> u64 {
    rays.iter()
        .filter(|ray| {
            index
                .closest_hit(&world.shapes, ray, t_min, f32::INFINITY, counters)
                .is_some()
        })
        .count() as u64
}

/// Casts `rays` for any hit before their light, counting the work in
/// `counters`; returns how many are blocked.
pub fn cast_shadow(
    index: &SceneIndex,
    world: &World,
    rays: &[ShadowRay],
    counters: &mut Counters,
) -> u64 {
    rays.iter()
        .filter(|s| index.any_hit(&world.shapes, &s.ray, 0.0, s.distance, counters))
        .count() as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::scene::{Limits, parse_scene};

    /// A floor (z = 0) seen from above, lit by a light above it and one
    /// below it, and a sphere standing on it.
    const SCENE: &str = "\
v
from 0 -8 6
at 0 0 0
up 0 0 1
angle 50
resolution 40 24
l 2 -2 5
l 0 0 -3
f 0.6 0.6 0.6 1 0 0 1 0 0 0 1
p 4
-6 -6 0  6 -6 0  6 6 0  -6 6 0
s 0 0 1 1
";

    fn ray_set(width: u32, height: u32) -> (World, RaySet) {
        let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
        let world = World::build(&scene);
        let index = SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0);
        let camera = Camera::new(&world.view, width, height, 0.0, 1.0).unwrap();
        let set = RaySet::new(&world, &index, &camera);
        (world, set)
    }

    #[test]
    fn one_eye_ray_per_pixel_tile_by_tile() {
        let (world, set) = ray_set(40, 24);
        assert_eq!(set.eye.len(), 40 * 24);
        // 40 x 24 is 3 x 2 tiles: 16 + 16 + 8 wide, 16 + 8 high.
        assert_eq!(
            set.tile_rays,
            [256, 256, 128, 128, 128, 64],
            "row by row, cut at the edges"
        );
        let camera = Camera::new(&world.view, 40, 24, 0.0, 1.0).unwrap();
        let through = |x: u32, y: u32| camera.ray(x as f32 + 0.5, y as f32 + 0.5, glam::Vec2::ZERO);
        // Row-major inside a tile: ray 16 is the tile's second row.
        assert_eq!(set.eye[0], through(0, 0));
        assert_eq!(set.eye[15], through(15, 0));
        assert_eq!(set.eye[16], through(0, 1));
        assert_eq!(set.eye[255], through(15, 15));
        // The second tile starts at x = 16; the third is 8 wide.
        assert_eq!(set.eye[256], through(16, 0));
        assert_eq!(set.eye[512], through(32, 0));
        assert_eq!(set.eye[512 + 8], through(32, 1));
        // The second row of tiles starts at y = 16.
        assert_eq!(set.eye[640], through(0, 16));
        let tiles: Vec<usize> = set.eye_tiles().map(<[Ray]>::len).collect();
        assert_eq!(tiles, set.tile_rays);
    }

    /// Only the floor, seen from above, and the second light at height
    /// `second_light_z`: its ray set and how many eye rays hit.
    fn floor_only(second_light_z: f32) -> (World, RaySet, u64) {
        let text = SCENE
            .replace("l 0 0 -3", &format!("l 0 0 {second_light_z}"))
            .replace("s 0 0 1 1\n", "");
        let scene = parse_scene(&text, None, &Limits::default()).unwrap();
        let world = World::build(&scene);
        let index = SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0);
        let camera = Camera::new(&world.view, 40, 24, 0.0, 1.0).unwrap();
        let set = RaySet::new(&world, &index, &camera);
        let hits = cast_eye(
            &index,
            &world,
            &set.eye,
            set.hither,
            &mut Counters::default(),
        );
        (world, set, hits)
    }

    /// One shadow ray per hit towards the light above the floor, none
    /// towards the one below; raised above the floor, the second light
    /// is faced too and every hit sends two.
    #[test]
    fn shadow_rays_only_towards_lights_the_surface_faces() {
        let (world, below, hits) = floor_only(-3.0);
        assert!(hits > 0 && hits < below.eye.len() as u64, "{hits}");
        assert_eq!(below.shadow.len() as u64, hits);
        let above = world.lights[0].position;
        for s in &below.shadow {
            assert!((s.ray.at(s.distance) - above).length() < 1e-4, "{s:?}");
            let lift = s.ray.origin.z - SHADOW_OFFSET;
            assert!(lift.abs() < 1e-6, "lifted along the normal: {s:?}");
        }
        let (_, both, hits) = floor_only(9.0);
        assert_eq!(both.shadow.len() as u64, 2 * hits);
    }

    /// The shadow rays end at their lights, and casting counts the blocked
    /// ones: the floor behind the sphere is in its shadow.
    #[test]
    fn casting_shadow_rays_finds_the_sphere_s_shadow() {
        let (world, set) = ray_set(40, 24);
        let index = SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0);
        let mut counters = Counters::default();
        let blocked = cast_shadow(&index, &world, &set.shadow, &mut counters);
        assert!(
            blocked > 0 && blocked < set.shadow.len() as u64,
            "{blocked}"
        );
        for kind in [AccelKind::None, AccelKind::Grid] {
            let other = SceneIndex::build(&world.shapes, kind, 2.0);
            let mut c = Counters::default();
            assert_eq!(cast_shadow(&other, &world, &set.shadow, &mut c), blocked);
        }
    }
}
