//! Ray throughput of the acceleration structures alone, without shading,
//! on the scenes of the speed issue and on the ray set `workbench bench
//! --rays` casts ([`tracer::ray_set`]: eye rays through every pixel centre
//! in 16 x 16 tiles, closest hit; shadow rays from their hits to each
//! light the surface faces, any hit), the set Embree's
//! `rtcIntersect1`/`rtcOccluded1` figures are measured on. One thread;
//! throughput is rays, so criterion reports rays per second. The grid is
//! timed on balls_medium only (on the others it is far slower).

mod common;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tracer::accel::{AccelKind, SceneIndex};
use tracer::ray_set::{RaySet, cast_eye, cast_shadow};
use tracer::stats::Counters;

/// The scenes timed, with the structures timed on each.
const SCENES: [(&str, &[(&str, AccelKind)]); 6] = [
    (
        "balls_medium",
        &[("bvh", AccelKind::Bvh), ("grid", AccelKind::Grid)],
    ),
    ("balls_high", BVH),
    ("mount_high", BVH),
    ("mount_very_high", BVH),
    ("mesh_large", BVH),
    ("sombrero", BVH),
];

const BVH: &[(&str, AccelKind)] = &[("bvh", AccelKind::Bvh)];

fn rays(c: &mut Criterion) {
    for (scene_name, structures) in SCENES {
        scene_rays(c, scene_name, structures);
    }
}

fn scene_rays(c: &mut Criterion, scene_name: &str, structures: &[(&str, AccelKind)]) {
    let (scene, world) = common::load(&format!("{scene_name}.p3f"));
    let plan = common::bench_frame(&scene, &world, AccelKind::Bvh);
    let set = RaySet::new(&world, &plan.index, &plan.camera);
    for &(name, accel) in structures {
        let index = SceneIndex::build(&world.shapes, accel, 2.0);
        let mut group = c.benchmark_group(format!("rays/{scene_name}/closest_hit"));
        group.throughput(Throughput::Elements(set.eye.len() as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                cast_eye(
                    &index,
                    &world,
                    &set.eye,
                    set.hither,
                    &mut Counters::default(),
                )
            })
        });
        group.finish();
        let mut group = c.benchmark_group(format!("rays/{scene_name}/any_hit"));
        group.throughput(Throughput::Elements(set.shadow.len() as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| cast_shadow(&index, &world, &set.shadow, &mut Counters::default()))
        });
        group.finish();
    }
}

criterion_group!(benches, rays);
criterion_main!(benches);
