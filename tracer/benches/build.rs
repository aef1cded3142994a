//! Building the acceleration structures over a large mesh: mesh_large, a
//! Sierpinski tetrahedron of 262 144 triangles. Throughput is primitives,
//! so criterion reports primitives per second.

mod common;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tracer::accel::{AccelKind, SceneIndex};

fn builds(c: &mut Criterion) {
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

criterion_group!(benches, builds);
criterion_main!(benches);
