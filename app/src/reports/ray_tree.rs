//! The ray-tree inspector, headless: record the tree of one pixel sample
//! under some settings, and say it as an indented tree or JSON. The command
//! line and the window's inspector panel share it.

use std::sync::Arc;

use anyhow::{Result, anyhow};
use glam::Vec3A;
use tracer::accel::{SceneIndex, Tally, Visit};
use tracer::render::{Outcome, RayNode, RayTree, RenderPlan, RenderSettings};
use tracer::world::World;

use crate::figures::overlay::VisitStep;

/// The ray tree of sample `sample` of pixel `(x, y)` under `settings`,
/// reusing `index` when it was built for them.
pub(crate) fn inspect(
    world: &Arc<World>,
    index: Option<Arc<SceneIndex>>,
    settings: &RenderSettings,
    (x, y): (u32, u32),
    sample: u32,
) -> Result<RayTree> {
    settings.validate()?;
    if sample >= settings.samples_per_pixel() && !settings.keep_refining {
        return Err(anyhow!(
            "sample {sample} does not exist: these settings take {} sample(s) per pixel",
            settings.samples_per_pixel()
        ));
    }
    let index = index
        .filter(|i| i.matches(settings.accel, settings.grid_multiplier))
        .unwrap_or_else(|| {
            Arc::new(SceneIndex::build(
                &world.shapes,
                settings.accel,
                settings.grid_multiplier,
            ))
        });
    let frame = RenderPlan::new(world.clone(), index, settings.clone())?;
    frame.inspect(x, y, sample).ok_or_else(|| {
        anyhow!(
            "pixel ({x}, {y}) is outside the {}x{} image",
            settings.width,
            settings.height
        )
    })
}

/// A colour or vector as `(r, g, b)` with 3 decimals.
pub(crate) fn triple(v: Vec3A) -> String {
    format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z)
}

/// The first line: the pixel, its colour and the sum of the contributions.
pub(crate) fn headline(tree: &RayTree) -> String {
    format!(
        "pixel ({}, {}), sample {}: colour {}, contributions add up to {}",
        tree.x,
        tree.y,
        tree.sample,
        triple(tree.colour),
        triple(tree.contributions())
    )
}

/// An object as `sphere #3 (line 12:1)`: kind, index in the file and
/// where the file declares it.
pub(crate) fn object_name(kind: &str, index: u32, position: Option<(u32, u32)>) -> String {
    match position {
        Some((line, column)) => format!("{kind} #{index} (line {line}:{column})"),
        None => format!("{kind} #{index}"),
    }
}

/// One node in one line: its kind, what it met and what it added.
pub(crate) fn describe_node(node: &RayNode) -> String {
    let kind = node.kind.name();
    let adds = format!("adds {}", triple(node.contribution));
    match &node.outcome {
        Outcome::Surface(s) => {
            let m = &s.surface;
            let fresnel = match s.fresnel {
                Some((kr, true)) => format!(", Fresnel {kr:.3}, total internal reflection"),
                Some((kr, false)) => format!(", Fresnel {kr:.3}"),
                None => String::new(),
            };
            format!(
                "{kind} (depth {}): hit {} at t {:.4}, normal {}{}; Kd {} Ks {} shine {} T {} ior {}{fresnel}; {adds}",
                node.depth,
                object_name(s.object_kind, s.object, s.object_position),
                s.t,
                triple(s.normal),
                if s.outside { "" } else { " (from inside)" },
                triple(m.diffuse),
                triple(m.specular),
                m.shine,
                m.transmittance,
                m.ior,
            )
        }
        Outcome::Background => format!("{kind} (depth {}): background; {adds}", node.depth),
        Outcome::Light {
            light,
            occluder: Some(o),
            ..
        } => format!(
            "shadow to light {light}: blocked by {} at t {:.4}",
            object_name(o.object_kind, o.object, o.object_position),
            o.t
        ),
        Outcome::Light { light, .. } => format!("shadow to light {light}: lit; {adds}"),
    }
}

/// The tree indented two spaces per generation, children under parents,
/// then what the eye ray's traversal visited.
pub(crate) fn text(tree: &RayTree) -> String {
    let mut out = nodes_text(tree);
    out.push_str(&visits_text(&tree.eye_visits));
    out
}

/// The headline and the rays, without the traversal (which can run to a
/// line per BVH node).
pub(crate) fn nodes_text(tree: &RayTree) -> String {
    let mut out = headline(tree);
    out.push('\n');
    let mut stack: Vec<(usize, usize)> = tree.children(None).map(|i| (i, 0)).collect();
    stack.reverse();
    while let Some((i, level)) = stack.pop() {
        out.push_str(&"  ".repeat(level));
        out.push_str(&describe_node(&tree.nodes[i]));
        out.push('\n');
        let children: Vec<usize> = tree.children(Some(i)).collect();
        stack.extend(children.into_iter().rev().map(|c| (c, level + 1)));
    }
    out
}

/// What the eye ray's traversal visited: a heading with the counts, then
/// one line per cell, node or leaf in visiting order.
pub(crate) fn visits_text(visits: &[Visit]) -> String {
    let mut out = visits_heading(visits);
    out.push_str(if visits.is_empty() { "\n" } else { ":\n" });
    for visit in visits {
        out.push_str("  ");
        out.push_str(&describe_visit(visit));
        out.push('\n');
    }
    out
}

/// How many cells, or nodes and leaves, the eye ray visited.
pub(crate) fn visits_heading(visits: &[Visit]) -> String {
    let nodes = visits
        .iter()
        .filter(|v| matches!(v, Visit::Node { .. }))
        .count();
    match visits.first() {
        None => "eye ray: no cells or nodes visited (brute force, or it misses the structure)"
            .to_string(),
        Some(Visit::Cell { .. }) => format!("eye ray walked {} grid cells", visits.len()),
        Some(_) => format!(
            "eye ray visited {nodes} BVH nodes and tested {} leaves",
            visits.len() - nodes
        ),
    }
}

/// One visit in one line: what it is, its box and what it tested.
pub(crate) fn describe_visit(visit: &Visit) -> String {
    let b = visit.bounds();
    let bounds = format!("box {} .. {}", triple(b.min), triple(b.max));
    match visit {
        Visit::Cell {
            cell: [x, y, z],
            tested,
            ..
        } => format!("cell ({x}, {y}, {z}), {bounds}, {tested} objects tested"),
        Visit::Node { depth, boxes, .. } => {
            format!("node at depth {depth}, {bounds}, {boxes} boxes tested")
        }
        Visit::Leaf {
            depth, primitives, ..
        } => format!("leaf at depth {depth}, {bounds}, {primitives} primitives tested"),
    }
}

/// What the eye ray's walk in `tree` had tested by the visit `step` is at,
/// against brute force's count (every one of the scene's `primitives`).
/// At the end of the walk, with the unbounded shapes (planes) tested after
/// it, it is the query's own count.
pub(crate) fn step_tally(tree: &RayTree, step: VisitStep, primitives: usize) -> String {
    let visits = &tree.eye_visits;
    let tally = Tally::of(&visits[..step.drawn(visits.len())]);
    let boxes = match visits.first() {
        Some(Visit::Cell { .. }) | None => String::new(),
        Some(_) => format!(" and {} boxes", tally.boxes),
    };
    let brute = format!("brute force tests {primitives}");
    let at_end = step
        .current(visits.len())
        .is_none_or(|k| k + 1 == visits.len());
    if !at_end {
        return format!(
            "so far: {} primitives{boxes} tested; {brute}",
            tally.primitives
        );
    }
    let all = tree.eye_counters.intersection_tests;
    let after = all.saturating_sub(tally.primitives);
    let planes = if after > 0 {
        format!(
            " ({} in the walk, {after} unbounded after it)",
            tally.primitives
        )
    } else {
        String::new()
    };
    format!("in all: {all} primitives{planes}{boxes} tested; {brute}")
}

/// One visit as JSON: its kind, box and what identifies it.
fn visit_json(visit: &Visit) -> serde_json::Value {
    let b = visit.bounds();
    let v = |v: Vec3A| [v.x, v.y, v.z];
    let mut out = match visit {
        Visit::Cell { cell, tested, .. } => {
            serde_json::json!({ "kind": "cell", "cell": cell, "tested": tested })
        }
        Visit::Node { depth, boxes, .. } => {
            serde_json::json!({ "kind": "node", "depth": depth, "boxes": boxes })
        }
        Visit::Leaf {
            depth, primitives, ..
        } => serde_json::json!({ "kind": "leaf", "depth": depth, "primitives": primitives }),
    };
    out["min"] = serde_json::json!(v(b.min));
    out["max"] = serde_json::json!(v(b.max));
    out
}

/// The tree as JSON: every node with its parent's index.
pub(crate) fn json(tree: &RayTree) -> serde_json::Value {
    let v = |v: Vec3A| [v.x, v.y, v.z];
    let nodes: Vec<serde_json::Value> = tree
        .nodes
        .iter()
        .map(|n| {
            let mut node = serde_json::json!({
                "kind": n.kind.name(),
                "depth": n.depth,
                "parent": n.parent,
                "origin": v(n.origin),
                "direction": v(n.dir),
                "weight": v(n.weight),
                "radiance": v(n.radiance),
                "contribution": v(n.contribution),
            });
            node["outcome"] = match &n.outcome {
                Outcome::Surface(s) => serde_json::json!({
                    "hit": "surface",
                    "t": s.t,
                    "shape": s.shape,
                    "object": s.object,
                    "object_kind": s.object_kind,
                    "line_column": s.object_position.map(|(l, c)| [l, c]),
                    "point": v(s.point),
                    "normal": v(s.normal),
                    "from_inside": !s.outside,
                    "material": {
                        "diffuse": v(s.surface.diffuse),
                        "specular": v(s.surface.specular),
                        "shine": s.surface.shine,
                        "transmittance": s.surface.transmittance,
                        "ior": s.surface.ior,
                    },
                    "fresnel": s.fresnel.map(|(kr, _)| kr),
                    "total_internal_reflection": s.fresnel.map(|(_, tir)| tir),
                }),
                Outcome::Background => serde_json::json!({ "hit": "background" }),
                Outcome::Light {
                    light,
                    distance,
                    occluder,
                } => serde_json::json!({
                    "hit": if occluder.is_some() { "blocked" } else { "light" },
                    "light": light,
                    "distance": distance,
                    "occluder": occluder.map(|o| serde_json::json!({
                        "t": o.t,
                        "shape": o.shape,
                        "object": o.object,
                        "object_kind": o.object_kind,
                        "line_column": o.object_position.map(|(l, c)| [l, c]),
                    })),
                }),
            };
            node
        })
        .collect();
    serde_json::json!({
        "pixel": [tree.x, tree.y],
        "sample": tree.sample,
        "colour": v(tree.colour),
        "sum_of_contributions": v(tree.contributions()),
        "nodes": nodes,
        "eye_visits": tree.eye_visits.iter().map(visit_json).collect::<Vec<_>>(),
        "eye_tests": tree.eye_counters.intersection_tests,
    })
}

#[cfg(test)]
mod tests {
    use tracer::geometry::Aabb;
    use tracer::stats::Counters;

    use super::*;

    /// A tree whose eye ray walked cells testing `tested` objects each, its
    /// query counting `planes` more after the walk.
    fn walked(tested: &[u32], planes: u64) -> RayTree {
        let bounds = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        let eye_visits: Vec<Visit> = (0..)
            .zip(tested)
            .map(|(x, &tested)| Visit::Cell {
                cell: [x, 0, 0],
                bounds,
                tested,
            })
            .collect();
        let eye_counters = Counters {
            intersection_tests: tested.iter().map(|&t| u64::from(t)).sum::<u64>() + planes,
            ..Counters::default()
        };
        RayTree {
            x: 0,
            y: 0,
            sample: 0,
            colour: Vec3A::ZERO,
            nodes: Vec::new(),
            eye_visits,
            eye_counters,
        }
    }

    #[test]
    fn a_step_counts_the_tests_so_far_and_the_end_the_querys() {
        let tree = walked(&[0, 3, 2], 1);
        let at = |step| step_tally(&tree, step, 93);
        assert_eq!(
            at(VisitStep::At(1)),
            "so far: 3 primitives tested; brute force tests 93"
        );
        let end = "in all: 6 primitives (5 in the walk, 1 unbounded after it) tested; \
                   brute force tests 93";
        assert_eq!(at(VisitStep::At(2)), end);
        assert_eq!(at(VisitStep::All), end);
        assert_eq!(
            step_tally(&walked(&[4], 0), VisitStep::All, 93),
            "in all: 4 primitives tested; brute force tests 93"
        );
    }
}
