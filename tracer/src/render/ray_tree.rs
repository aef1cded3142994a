//! The ray-tree inspector: every ray one sample of one pixel spawned, with
//! what each hit and what it added to the pixel. The tree is recorded by a
//! [`TraceRecorder`] on [`RenderPlan::sample`], the function the render itself
//! calls, with the same random numbers, so it is exactly the sample the
//! image holds.

use glam::Vec3A;

use crate::accel::{Traversal, Visit};
use crate::geometry::Ray;
use crate::stats::Counters;
use crate::world::Surface;

use super::trace::{RayKind, ShadowSample, SurfaceHit, TraceRecorder};
use super::{RenderPlan, Tracer};

/// One sample's rays, parents before their children.
#[derive(Debug, Clone, PartialEq)]
pub struct RayTree {
    /// Pixel column, 0 at the left.
    pub x: u32,
    /// Pixel row, 0 at the top.
    pub y: u32,
    /// The sample (the pass that traced it).
    pub sample: u32,
    /// The radiance the render traced for this sample.
    pub colour: Vec3A,
    /// The rays; a node's `parent` is an index into this list.
    pub nodes: Vec<RayNode>,
    /// The grid cells, or BVH nodes and leaves, the eye ray's traversal
    /// visited, in order (none with brute force).
    pub eye_visits: Vec<Visit>,
    /// The eye ray's closest-hit query's own work: its
    /// `intersection_tests` are what the visits tested
    /// ([`crate::accel::Tally`]) plus the unbounded shapes tested after
    /// the walk.
    pub eye_counters: Counters,
}

impl RayTree {
    /// What all nodes add up to: the traced colour, up to rounding.
    pub fn contributions(&self) -> Vec3A {
        self.nodes.iter().map(|n| n.contribution).sum()
    }

    /// The children of node `index` (or the roots for `None`), in order.
    pub fn children(&self, index: Option<usize>) -> impl Iterator<Item = usize> + '_ {
        (0..self.nodes.len()).filter(move |&i| self.nodes[i].parent == index)
    }
}

/// One ray of the tree.
#[derive(Debug, Clone, PartialEq)]
pub struct RayNode {
    /// Eye, reflected, refracted or shadow ray.
    pub kind: RayKind,
    /// Bounces above it: the eye ray and its shadow rays are depth 0.
    pub depth: u32,
    /// Index of the ray that spawned it in [`RayTree::nodes`]; `None` for the eye ray.
    pub parent: Option<usize>,
    /// Where the ray starts, in world space.
    pub origin: Vec3A,
    /// Its direction, unit length.
    pub dir: Vec3A,
    /// The product of the weights from the eye to this ray: what one unit
    /// of its radiance is worth in the pixel.
    pub weight: Vec3A,
    /// What it met.
    pub outcome: Outcome,
    /// What this node itself adds to the pixel, after its weights: the
    /// ambient term at a hit (with shadows off, its whole local shading),
    /// the background on a miss, the light a shadow ray lets through. The
    /// nodes' contributions sum to the sample's colour.
    pub contribution: Vec3A,
    /// The radiance the ray brought back, before its weight (shadow rays:
    /// the light sample's, zero when blocked).
    pub radiance: Vec3A,
}

/// What a ray met.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// It hit a surface.
    Surface(SurfaceRecord),
    /// The ray left the scene and took the background (or sky).
    Background,
    /// A shadow ray towards a light sample.
    Light {
        /// Index into the world's lights.
        light: usize,
        /// Distance from the ray's origin to the light sample.
        distance: f32,
        /// What blocked it (the nearest occluder), `None` when lit.
        occluder: Option<Occluder>,
    },
}

/// A surface hit with its material.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceRecord {
    /// Distance along the ray to the hit.
    pub t: f32,
    /// Index into the world's shapes.
    pub shape: u32,
    /// Index into the scene's objects.
    pub object: u32,
    /// The object's kind: "sphere", "mesh", ...
    pub object_kind: &'static str,
    /// Where the file declared the object (line, column); `None` for scenes built in code.
    pub object_position: Option<(u32, u32)>,
    /// The hit point, in world space.
    pub point: Vec3A,
    /// Shading normal, facing the incoming ray.
    pub normal: Vec3A,
    /// The ray came from outside the object (it enters a transmitter).
    pub outside: bool,
    /// The material at the hit.
    pub surface: Surface,
    /// For transmitters: the Fresnel reflectance and whether the refraction
    /// was lost to total internal reflection.
    pub fresnel: Option<(f32, bool)>,
}

/// The object that blocked a shadow ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Occluder {
    /// Distance along the shadow ray to the occluder.
    pub t: f32,
    /// Index into the world's shapes.
    pub shape: u32,
    /// Index into the scene's objects.
    pub object: u32,
    /// The object's kind: "sphere", "mesh", ...
    pub object_kind: &'static str,
    /// Where the file declared it (line, column).
    pub object_position: Option<(u32, u32)>,
}

impl RenderPlan {
    /// Records the ray tree of sample `sample` of pixel `(x, y)`: the same
    /// rays, random numbers and colour as the render's. `None` outside the
    /// image.
    pub fn inspect(&self, x: u32, y: u32, sample: u32) -> Option<RayTree> {
        if x >= self.settings.width || y >= self.settings.height {
            return None;
        }
        let tracer = Tracer::new(&self.world, &self.index, &self.settings);
        let mut recorder = TreeRecorder::default();
        let colour = self.sample(
            &tracer,
            x,
            y,
            sample,
            &mut Counters::default(),
            &mut recorder,
        );
        let mut nodes = recorder.nodes;
        for node in &mut nodes {
            self.complete(node);
        }
        let (eye_visits, eye_counters) = nodes
            .first()
            .filter(|n| n.kind == RayKind::Eye)
            .map(|eye| {
                let traversal = self.eye_traversal(eye);
                (traversal.visits, traversal.counters)
            })
            .unwrap_or_default();
        Some(RayTree {
            x,
            y,
            sample,
            colour,
            nodes,
            eye_visits,
            eye_counters,
        })
    }

    /// The eye ray's closest-hit query again, with what it visited: the
    /// recorded origin and direction are the traced ray's own, so it is
    /// the same query, bit for bit.
    fn eye_traversal(&self, eye: &RayNode) -> Traversal {
        let ray = Ray {
            origin: eye.origin,
            dir: eye.dir,
            inv_dir: eye.dir.recip(),
        };
        self.index.closest_hit_visits(
            &self.world.shapes,
            &ray,
            self.camera.hither(),
            f32::INFINITY,
        )
    }

    /// Fills in what the recorder could not know: the scene objects, the
    /// materials and the occluders of blocked shadow rays.
    fn complete(&self, node: &mut RayNode) {
        let world = &self.world;
        let object_of = |shape: u32| {
            let object = world.shape_object.get(shape as usize).copied().unwrap_or(0);
            let kind = world
                .object_kinds
                .get(object as usize)
                .copied()
                .unwrap_or("shape");
            (object, kind, world.object_positions.get(object as usize))
        };
        match &mut node.outcome {
            Outcome::Surface(record) => {
                (record.object, record.object_kind, record.object_position) =
                    object_of(record.shape);
                record.surface = *world.surface(record.shape);
            }
            Outcome::Light {
                distance,
                occluder: Some(occluder),
                ..
            } => {
                let ray = Ray::new(node.origin, node.dir);
                let scratch = &mut Counters::default();
                if let Some(hit) =
                    self.index
                        .closest_hit(&world.shapes, &ray, 0.0, *distance, scratch)
                {
                    let (object, object_kind, object_position) = object_of(hit.shape);
                    *occluder = Occluder {
                        t: hit.t,
                        shape: hit.shape,
                        object,
                        object_kind,
                        object_position,
                    };
                }
            }
            _ => {}
        }
    }
}

/// Builds the tree from the trace's calls.
#[derive(Default)]
struct TreeRecorder {
    nodes: Vec<RayNode>,
    /// The open rays, innermost last.
    open: Vec<usize>,
}

impl TreeRecorder {
    fn top(&mut self) -> Option<&mut RayNode> {
        let i = *self.open.last()?;
        self.nodes.get_mut(i)
    }
}

impl TraceRecorder for TreeRecorder {
    fn ray(&mut self, kind: RayKind, depth: u32, ray: &Ray, weight: Vec3A) {
        let parent = self.open.last().copied();
        let above = parent.map_or(Vec3A::ONE, |p| self.nodes[p].weight);
        self.open.push(self.nodes.len());
        self.nodes.push(RayNode {
            kind,
            depth,
            parent,
            origin: ray.origin,
            dir: ray.dir,
            weight: above * weight,
            outcome: Outcome::Background,
            contribution: Vec3A::ZERO,
            radiance: Vec3A::ZERO,
        });
    }

    fn hit(&mut self, hit: &SurfaceHit, ambient: Vec3A) {
        if let Some(node) = self.top() {
            node.contribution = node.weight * ambient;
            node.outcome = Outcome::Surface(SurfaceRecord {
                t: hit.t,
                shape: hit.shape,
                object: 0,
                object_kind: "",
                object_position: None,
                point: hit.point,
                normal: hit.normal,
                outside: hit.outside,
                surface: Surface {
                    diffuse: Vec3A::ZERO,
                    specular: Vec3A::ZERO,
                    shine: 0.0,
                    transmittance: 0.0,
                    ior: 1.0,
                },
                fresnel: None,
            });
        }
    }

    fn fresnel(&mut self, kr: f32, total_internal_reflection: bool) {
        if let Some(RayNode {
            outcome: Outcome::Surface(record),
            ..
        }) = self.top()
        {
            record.fresnel = Some((kr, total_internal_reflection));
        }
    }

    fn background(&mut self, background: Vec3A) {
        if let Some(node) = self.top() {
            node.contribution = node.weight * background;
            node.outcome = Outcome::Background;
        }
    }

    fn shadow(&mut self, sample: &ShadowSample) {
        let Some(&parent) = self.open.last() else {
            return;
        };
        let (depth, weight) = (self.nodes[parent].depth, self.nodes[parent].weight);
        let placeholder = Occluder {
            t: sample.distance,
            shape: 0,
            object: 0,
            object_kind: "",
            object_position: None,
        };
        self.nodes.push(RayNode {
            kind: RayKind::Shadow,
            depth,
            parent: Some(parent),
            origin: sample.ray.origin,
            dir: sample.ray.dir,
            weight,
            outcome: Outcome::Light {
                light: sample.light,
                distance: sample.distance,
                occluder: sample.blocked.then_some(placeholder),
            },
            contribution: weight * sample.radiance,
            radiance: sample.radiance,
        });
    }

    fn end(&mut self, radiance: Vec3A) {
        if let Some(i) = self.open.pop() {
            self.nodes[i].radiance = radiance;
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::accel::{AccelKind, SceneIndex, Tally};
    use crate::render::{RenderSettings, render};
    use crate::scene::{Limits, parse_scene};
    use crate::world::World;

    /// Object 0 a floor plane, 1 a mirror sphere in the middle of the
    /// view, 2 a ball between the mirror's front and the light (out of
    /// view), 3 a glass sphere to the right.
    const SCENE: &str = "\
bclr 0.2 0.3 0.5
v from 0 -10 1 at 0 0 1 up 0 0 1 angle 40 hither 0.01 resolution 41 41
l 0 -5 10 1 1 1
f 0.8 0.8 0.8 1 0 0 0 1
pl 0 0 0 1 0 0 0 1 0
f 1 1 1 0 1 100 0 1
s 0 0 1 1
f 0.5 0.5 0.5 1 0 0 0 1
s 0 -3 5.5 0.5
f 1 1 1 0.1 1 100 0.9 1.5
s 2.5 0 1 1
";

    fn plan(accel: AccelKind) -> RenderPlan {
        let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
        let world = Arc::new(World::build(&scene));
        let index = Arc::new(SceneIndex::build(&world.shapes, accel, 2.0));
        let settings = RenderSettings {
            width: 41,
            height: 41,
            accel,
            ..RenderSettings::default()
        };
        RenderPlan::new(world, index, settings).unwrap()
    }

    fn hit_object(node: &RayNode) -> Option<u32> {
        match &node.outcome {
            Outcome::Surface(s) => Some(s.object),
            _ => None,
        }
    }

    fn close(a: Vec3A, b: Vec3A) -> bool {
        (a - b).abs().max_element() <= 1e-5 * b.abs().max_element().max(1.0)
    }

    #[test]
    fn the_mirror_pixel_has_a_blocked_shadow_and_a_bounce_to_the_sky() {
        for accel in [AccelKind::None, AccelKind::Grid, AccelKind::Bvh] {
            let plan = plan(accel);
            let tree = plan.inspect(20, 20, 0).unwrap();
            let eye = &tree.nodes[0];
            assert_eq!((eye.kind, eye.depth, eye.parent), (RayKind::Eye, 0, None));
            assert_eq!(hit_object(eye), Some(1), "{accel:?}");
            let Outcome::Surface(s) = &eye.outcome else {
                unreachable!()
            };
            assert!((s.t - 9.0).abs() < 1e-3, "{}", s.t);
            assert!(s.outside && s.fresnel.is_none());
            assert_eq!(s.surface.specular, Vec3A::ONE);

            let children: Vec<&RayNode> = tree.children(Some(0)).map(|i| &tree.nodes[i]).collect();
            assert_eq!(children.len(), 2, "{children:#?}");
            let (shadow, bounce) = (children[0], children[1]);
            assert_eq!(shadow.kind, RayKind::Shadow);
            let Outcome::Light {
                light: 0,
                occluder: Some(o),
                ..
            } = shadow.outcome
            else {
                panic!("the ball blocks the light: {shadow:#?}")
            };
            assert_eq!((o.object, o.object_kind), (2, "sphere"));
            assert_eq!(o.object_position, Some((9, 1)), "the file's line 9");
            let Outcome::Surface(mirror) = &eye.outcome else {
                unreachable!()
            };
            assert_eq!(mirror.object_position, Some((7, 1)));
            assert_eq!(shadow.contribution, Vec3A::ZERO);
            assert_eq!((bounce.kind, bounce.depth), (RayKind::Reflection, 1));
            assert_eq!(bounce.outcome, Outcome::Background);
            // The mirror sends the ray straight back.
            assert!(close(bounce.dir, Vec3A::NEG_Y), "{:?}", bounce.dir);
            assert_eq!(bounce.contribution, Vec3A::new(0.2, 0.3, 0.5));
            assert!(close(tree.contributions(), tree.colour));
        }
    }

    #[test]
    fn the_eye_visits_lead_to_the_eye_hit() {
        let holds = |b: &crate::geometry::Aabb, p: Vec3A| {
            (p.cmpge(b.min - 1e-4) & p.cmple(b.max + 1e-4)).all()
        };
        for accel in [AccelKind::None, AccelKind::Grid, AccelKind::Bvh] {
            let tree = plan(accel).inspect(20, 20, 0).unwrap();
            let Outcome::Surface(mirror) = &tree.nodes[0].outcome else {
                unreachable!()
            };
            let visits = &tree.eye_visits;
            match accel {
                AccelKind::None => assert!(visits.is_empty()),
                // The walk stops in the cell of the hit.
                AccelKind::Grid => {
                    let last = visits.last().expect("cells walked");
                    assert!(matches!(last, Visit::Cell { .. }));
                    assert!(holds(&last.bounds(), mirror.point), "{last:?}");
                }
                // A tested leaf holds the hit.
                AccelKind::Bvh => {
                    assert!(matches!(visits[0], Visit::Node { depth: 0, .. }));
                    assert!(visits.iter().any(
                        |v| matches!(v, Visit::Leaf { .. }) && holds(&v.bounds(), mirror.point)
                    ));
                }
            }
            // What the visits tested and the plane after them are the
            // query's count; brute force, visiting nothing, tests every shape.
            let world = &plan(accel).world;
            let planes = world.shapes.iter().filter(|s| s.bounds().is_none()).count();
            let walked = match accel {
                AccelKind::None => world.shapes.len() - planes,
                _ => Tally::of(visits).primitives as usize,
            };
            assert_eq!(planes, 1);
            assert_eq!(
                (walked + planes) as u64,
                tree.eye_counters.intersection_tests
            );
        }
    }

    /// Shadows off: the mirror pixel's tree has no shadow ray (its light
    /// comes from its hits), and its parts still add up to the render's.
    #[test]
    fn without_shadows_the_tree_has_no_shadow_ray_and_still_adds_up() {
        let shadowed = plan(AccelKind::Bvh);
        let settings = RenderSettings {
            shadows: false,
            ..shadowed.settings.clone()
        };
        let plan = RenderPlan::new(shadowed.world, shadowed.index, settings).unwrap();
        let (film, _) = render(
            plan.world.clone(),
            plan.index.clone(),
            plan.settings.clone(),
            Some(1),
        )
        .unwrap();
        let tree = plan.inspect(20, 20, 0).unwrap();
        assert!(tree.nodes.iter().all(|n| n.kind != RayKind::Shadow));
        assert!(tree.nodes.iter().any(|n| n.kind == RayKind::Reflection));
        assert_eq!(Some(tree.colour), film.pixel(20, 20));
        assert!(close(tree.contributions(), tree.colour));
    }

    #[test]
    fn the_glass_pixel_refracts_through_and_every_tree_adds_up() {
        let plan = plan(AccelKind::Bvh);
        let tree = plan.inspect(34, 20, 0).unwrap();
        let eye = &tree.nodes[0];
        assert_eq!(hit_object(eye), Some(3));
        let Outcome::Surface(s) = &eye.outcome else {
            unreachable!()
        };
        let (kr, tir) = s.fresnel.expect("glass reports its Fresnel term");
        assert!(kr > 0.0 && kr < 0.2 && !tir, "{kr}");
        let inside = tree
            .children(Some(0))
            .map(|i| &tree.nodes[i])
            .find(|n| n.kind == RayKind::Refraction)
            .expect("a refraction");
        assert_eq!(inside.depth, 1);
        let Outcome::Surface(back) = &inside.outcome else {
            panic!("the refracted ray meets the sphere's back: {inside:#?}")
        };
        assert_eq!(back.object, 3);
        assert!(!back.outside, "it meets the back from inside");
        assert!(
            tree.nodes
                .iter()
                .all(|n| n.depth <= plan.settings.max_depth + 1)
        );

        // Every pixel: the tree's colour is the render's, and its parts add up.
        let (film, _) = render(
            plan.world.clone(),
            plan.index.clone(),
            plan.settings.clone(),
            Some(1),
        )
        .unwrap();
        for (x, y) in [(0, 0), (20, 20), (34, 20), (20, 40), (5, 30), (37, 23)] {
            let tree = plan.inspect(x, y, 0).unwrap();
            assert_eq!(Some(tree.colour), film.pixel(x, y), "({x}, {y})");
            assert!(close(tree.contributions(), tree.colour), "({x}, {y})");
        }
        assert!(plan.inspect(41, 0, 0).is_none());
    }

    #[test]
    fn a_sample_replays_the_random_numbers_of_its_pass() {
        let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
        let world = Arc::new(World::build(&scene));
        let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
        let settings = RenderSettings {
            width: 41,
            height: 41,
            antialiasing: true,
            samples: 2,
            soft_shadows: true,
            light_size: 3.0,
            ..RenderSettings::default()
        };
        let plan = RenderPlan::new(world.clone(), index.clone(), settings.clone()).unwrap();
        let (film, _) = render(world, index, settings, Some(1)).unwrap();
        for (x, y) in [(20, 20), (34, 20), (10, 35)] {
            let trees: Vec<RayTree> = (0..4).map(|k| plan.inspect(x, y, k).unwrap()).collect();
            let mean = trees.iter().map(|t| t.colour).sum::<Vec3A>() / 4.0;
            assert!(close(mean, film.pixel(x, y).unwrap()), "({x}, {y})");
            assert_ne!(trees[0].nodes[0].dir, trees[1].nodes[0].dir, "jittered");
        }
    }
}
