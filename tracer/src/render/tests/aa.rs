//! Anti-aliasing's strata: over each round of N x N passes, the samples of
//! every pixel fall once in each of the pixel's N x N sub-cells.

use glam::Vec3A;

use super::{index, world};
use crate::accel::AccelKind;
use crate::geometry::Ray;
use crate::render::{RayKind, RenderPlan, RenderSettings, TraceRecorder, Tracer};
use crate::stats::Counters;

/// Keeps the eye ray of a traced sample.
#[derive(Default)]
struct EyeRay(Option<Ray>);

impl TraceRecorder for EyeRay {
    fn ray(&mut self, kind: RayKind, _depth: u32, ray: &Ray, _weight: Vec3A) {
        if kind == RayKind::Eye {
            self.0 = Some(*ray);
        }
    }
}

#[test]
fn each_round_of_passes_visits_every_stratum_of_every_pixel_once() {
    let w = world(
        "v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 hither 0 resolution 9 7\n\
         f 1 1 1 1 0 0 0 0 1 0 1\ns 0 0 0 1\n",
    );
    let idx = index(&w, AccelKind::Bvh);
    for n in [1, 2, 3, 4, 5, 8] {
        let settings = RenderSettings {
            width: 9,
            height: 7,
            antialiasing: true,
            samples: n,
            keep_refining: true,
            ..RenderSettings::default()
        };
        let plan = RenderPlan::new(w.clone(), idx.clone(), settings.clone()).unwrap();
        let tracer = Tracer::new(&w, &idx, &settings);
        let count = n * n;
        assert_eq!(plan.passes_target(), count);
        for (x, y) in [(0, 0), (4, 3), (8, 6), (2, 5)] {
            // Two rounds: refining past the target starts a fresh one.
            for round in 0..2 {
                let mut hits = vec![0u32; count as usize];
                for pass in round * count..(round + 1) * count {
                    let mut eye = EyeRay::default();
                    plan.sample(&tracer, x, y, pass, &mut Counters::default(), &mut eye);
                    let ray = eye.0.expect("an eye ray");
                    let p = plan.camera.project(ray.origin + ray.dir).unwrap();
                    let (fx, fy) = (p.x - x as f32, p.y - y as f32);
                    assert!(
                        (0.0..1.0).contains(&fx) && (0.0..1.0).contains(&fy),
                        "N = {n}, pixel ({x}, {y}), pass {pass}: sample at {p} is outside"
                    );
                    let (i, j) = ((fx * n as f32) as u32, (fy * n as f32) as u32);
                    hits[(j * n + i) as usize] += 1;
                }
                assert!(
                    hits.iter().all(|&h| h == 1),
                    "N = {n}, pixel ({x}, {y}), round {round}: strata hit {hits:?}"
                );
            }
        }
    }
}
