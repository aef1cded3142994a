//! Whole frames of balls_medium (512 x 512, one sample per pixel, hard
//! shadows, depth 4) with each acceleration structure, on one thread.
//! Throughput is rays of every kind, so criterion reports rays per second.

mod common;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tracer::accel::AccelKind;

fn frames(c: &mut Criterion) {
    let (scene, world) = common::load("balls_medium.p3f");
    let mut group = c.benchmark_group("frame/balls_medium");
    // A frame takes 0.1 s (BVH) to 0.5 s (none): few samples suffice.
    group.sample_size(10);
    for (name, accel) in [
        ("bvh", AccelKind::Bvh),
        ("grid", AccelKind::Grid),
        ("none", AccelKind::None),
    ] {
        let plan = common::bench_frame(&scene, &world, accel);
        let rays = common::render_frame(&plan).total_rays();
        group.throughput(Throughput::Elements(rays));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| black_box(common::render_frame(&plan)))
        });
    }
    group.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
