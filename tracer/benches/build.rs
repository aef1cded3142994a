//! Building the acceleration structures over large meshes. Throughput is
//! primitives, so criterion reports primitives per second.
//!
//! - `build/100k_triangles`: the BVH over the first 100 000 triangles of
//!   `mount_very_high` (the fractal mountain, `gen mount --level 8`,
//!   131 072 triangles): the size the build target names, measured
//!   rather than extrapolated from the larger meshes.
//! - `build/mesh_large`: BVH and grid over a Sierpinski tetrahedron of
//!   262 144 triangles.

mod common;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tracer::accel::{AccelKind, Bvh, BvhParams, SceneIndex};
use tracer::geometry::Shape;

/// Triangles in the `build/100k_triangles` case.
const TRIANGLES: usize = 100_000;

fn bvh_100k_triangles(c: &mut Criterion) {
    let (_, world) = common::load("mount_very_high.p3f");
    let ids: Vec<u32> = (0u32..)
        .zip(&world.shapes)
        .filter(|(_, shape)| matches!(shape, Shape::Triangle(_)))
        .map(|(id, _)| id)
        .take(TRIANGLES)
        .collect();
    assert_eq!(
        ids.len(),
        TRIANGLES,
        "mount_very_high has too few triangles"
    );
    let mut group = c.benchmark_group("build/100k_triangles");
    group.sample_size(10);
    group.throughput(Throughput::Elements(TRIANGLES as u64));
    let params = BvhParams::default();
    group.bench_function(BenchmarkId::from_parameter("bvh"), |b| {
        b.iter(|| black_box(Bvh::build(&world.shapes, &ids, &params)))
    });
    group.finish();
}

fn mesh_large(c: &mut Criterion) {
    let (_, world) = common::load("mesh_large.p3f");
    let mut group = c.benchmark_group("build/mesh_large");
    group.sample_size(10);
    group.throughput(Throughput::Elements(world.shapes.len() as u64));
    for (name, accel) in [("bvh", AccelKind::Bvh), ("grid", AccelKind::Grid)] {
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| black_box(SceneIndex::build(&world.shapes, accel, 2.0)))
        });
    }
    group.finish();
}

criterion_group!(benches, bvh_100k_triangles, mesh_large);
criterion_main!(benches);
