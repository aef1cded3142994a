//! Section 1, the run: the scene, its camera, the settings, the machine and
//! how every number of the page was measured.

use tracer::accel::AccelKind;

use super::html::{facts, titled_section};
use super::{Lab, QUICK_RUNS, QUICK_SIDE};
use crate::measure::benchmark::SamplingColumn;
use crate::reports::render_stats::describe_objects;

fn triple(v: glam::Vec3) -> String {
    format!("({}, {}, {})", v.x, v.y, v.z)
}

pub(crate) fn section(lab: &Lab) -> String {
    let request = &lab.request;
    let counts = &request.world.counts;
    let view = &request.scene.view;
    let s = &lab.base;
    let (from, at, up) = match &s.camera {
        Some(pose) => (pose.from, pose.at, pose.up),
        None => (view.from, view.at, view.up),
    };
    let scene = facts(&[
        ("file", request.scene_name.clone()),
        ("objects", describe_objects(counts)),
        (
            "primitives",
            format!("{} ({} triangles)", counts.primitives, counts.triangles),
        ),
        ("lights", counts.lights.to_string()),
        (
            "edits",
            if request.edits.is_empty() {
                "none".into()
            } else {
                request.edits.join("; ")
            },
        ),
    ]);
    let chosen = s.chosen_lens(view);
    let lens = lab
        .row(AccelKind::Bvh, false, SamplingColumn::AntialiasingDof)
        .map_or(chosen.aperture, |m| m.lens.aperture);
    let camera = facts(&[
        ("from", triple(from)),
        ("at", triple(at)),
        ("up", triple(up)),
        ("field of view", format!("{}°", view.angle)),
        (
            "lens of the depth-of-field frames",
            format!("aperture {} px, focal {}", lens, chosen.focal),
        ),
    ]);
    let settings = facts(&[
        (
            "image",
            format!(
                "{} x {} (the scene asks for {} x {})",
                s.width, s.height, request.base.width, request.base.height
            ),
        ),
        ("maximum depth", s.max_depth.to_string()),
        (
            "N",
            format!(
                "{} ({} samples per pixel with AA or DOF)",
                s.samples,
                s.samples.pow(2)
            ),
        ),
        (
            "soft shadows",
            format!("lights become squares of side {:.3}", s.light_size),
        ),
        ("ambient", s.ambient.to_string()),
        ("grid multiplier m", s.grid_multiplier.to_string()),
        ("seed", s.seed.to_string()),
    ]);
    let m = &lab.machine;
    let machine = facts(&[
        ("CPU", m.cpu.clone()),
        ("logical CPUs", m.cpus.to_string()),
        ("threads used", lab.threads.to_string()),
        ("OS", m.os.clone()),
        ("workbench", format!("{} (commit {})", m.version, m.commit)),
        ("date", m.date.clone()),
    ]);
    let quick = if request.quick {
        format!(
            "<p class=\"how\"><strong>Quick report</strong>: images at most {QUICK_SIDE} pixels on \
             their longer side and at most {QUICK_RUNS} runs per time, so its times are not those \
             of a full report.</p>\n"
        )
    } else {
        String::new()
    };
    let body = format!(
        "{quick}<p class=\"how\">Every time on this page is the median of {runs} frame(s) of the \
         same configuration, rendered one after another on {threads} thread(s), with its spread \
         (min..max and the median absolute deviation); structures are built once, apart from the \
         frames. Counts (rays, tests, steps) are exact and the same on every run.</p>\n\
         <div class=\"facts-row\"><div><h3>Scene</h3>\n{scene}<h3>Camera</h3>\n{camera}</div>\
         <div><h3>Settings</h3>\n{settings}<h3>Machine</h3>\n{machine}</div></div>\n",
        runs = lab.runs,
        threads = lab.threads,
    );
    titled_section("run", "1. The run", &body)
}
