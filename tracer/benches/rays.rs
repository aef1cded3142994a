//! Ray throughput of the acceleration structures alone, without shading,
//! on the scenes of the speed issue: the eye rays (closest hit) and, from
//! the points they hit, shadow rays to the first light (any hit), as
//! Embree's `rtcIntersect1`/`rtcOccluded1` figures were measured. One
//! thread; throughput is rays, so criterion reports rays per second. The
//! grid is timed on balls_medium only (on the others it is far slower).

mod common;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec2;
use tracer::accel::{AccelKind, SceneIndex};
use tracer::geometry::Ray;
use tracer::stats::Counters;

/// Every 4th pixel in each direction (16 384 rays at 512 x 512).
const STRIDE: u32 = 4;

/// The scenes timed, with the structures timed on each.
const SCENES: [(&str, &[(&str, AccelKind)]); 9] = [
    (
        "balls_medium",
        &[("bvh", AccelKind::Bvh), ("grid", AccelKind::Grid)],
    ),
    ("balls_high", BVH),
    ("mount_high", BVH),
    ("mount_very_high", BVH),
    ("mesh_large", BVH),
    ("shells", BVH),
    ("jacks", BVH),
    ("sombrero", BVH),
    ("lattice", BVH),
];

const BVH: &[(&str, AccelKind)] = &[("bvh", AccelKind::Bvh)];

fn rays(c: &mut Criterion) {
    for (scene_name, structures) in SCENES {
        scene_rays(c, scene_name, structures);
    }
}

fn scene_rays(c: &mut Criterion, scene_name: &str, structures: &[(&str, AccelKind)]) {
    let (scene, world) = common::load(&format!("{scene_name}.p3f"));
    let frame = common::bench_frame(&scene, &world, AccelKind::Bvh);
    let camera = &frame.camera;
    let eye: Vec<Ray> = (0..camera.height())
        .step_by(STRIDE as usize)
        .flat_map(|y| {
            (0..camera.width())
                .step_by(STRIDE as usize)
                .map(move |x| camera.ray(x as f32 + 0.5, y as f32 + 0.5, Vec2::ZERO))
        })
        .collect();
    let light = world
        .lights
        .first()
        .expect("the scenes timed have lights")
        .position;
    let reference = SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0);
    let mut counters = Counters::default();
    // Shadow rays start just off the hit point, as the tracer's do, and
    // end at the light.
    let shadow: Vec<(Ray, f32)> = eye
        .iter()
        .filter_map(|ray| {
            let hit =
                reference.closest_hit(&world.shapes, ray, 0.0, f32::INFINITY, &mut counters)?;
            let p = ray.at(hit.t);
            let origin = p + (light - p).normalize() * 1e-4;
            let to_light = light - origin;
            Some((Ray::new(origin, to_light), to_light.length()))
        })
        .collect();

    for &(name, accel) in structures {
        let index = SceneIndex::build(&world.shapes, accel, 2.0);
        let mut group = c.benchmark_group(format!("rays/{scene_name}/closest_hit"));
        group.throughput(Throughput::Elements(eye.len() as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let mut counters = Counters::default();
                let mut sum = 0.0;
                for ray in &eye {
                    if let Some(hit) =
                        index.closest_hit(&world.shapes, ray, 0.0, f32::INFINITY, &mut counters)
                    {
                        sum += hit.t;
                    }
                }
                black_box(sum)
            })
        });
        group.finish();
        let mut group = c.benchmark_group(format!("rays/{scene_name}/any_hit"));
        group.throughput(Throughput::Elements(shadow.len() as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let mut counters = Counters::default();
                shadow
                    .iter()
                    .filter(|(ray, distance)| {
                        index.any_hit(&world.shapes, ray, 0.0, *distance, &mut counters)
                    })
                    .count()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, rays);
criterion_main!(benches);
