//! The observer's segments against the cameras and trees they draw.

use std::sync::Arc;

use tracer::accel::{AccelKind, SceneIndex};
use tracer::render::{RayKind, RenderPlan};
use tracer::scene::{Limits, parse_scene};

use super::*;
use crate::figures::projection::Projector;

/// A mirror sphere and a matte one on a floor under two lights, one of
/// them behind the mirror: reflections, hits, lit and blocked shadow rays.
const SCENE: &str = "\
v from 0 -6 2 at 0 0 0.6 up 0 0 1 angle 40 hither 0.01 resolution 40 30
l 3 -3 6 1 1 1
l -1 4 0.8 0.5 0.5 0.5
f 0.6 0.6 0.6 1 1 1 1 0 10 0 1
box -5 -5 -0.2 5 5 0
f 0.2 0.2 0.2 0.2 1 1 1 0.8 40 0 1
s -0.6 0 0.8 0.8
f 0.9 0.1 0.1 0.8 1 1 1 0.3 40 0 1
s 0.9 1.6 0.5 0.5
";

fn world_and_settings(aperture: f32) -> (Arc<World>, RenderSettings) {
    let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
    let settings = RenderSettings {
        lens_override: tracer::render::LensOverride {
            aperture: Some(aperture),
            focal: None,
        },
        depth_of_field: aperture > 0.0,
        ..RenderSettings::from_scene(&scene)
    };
    (Arc::new(World::build(&scene)), settings)
}

fn tree_of(world: &Arc<World>, settings: &RenderSettings, pixel: (u32, u32)) -> RayTree {
    let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
    let frame = RenderPlan::new(world.clone(), index, settings.clone()).unwrap();
    frame.inspect(pixel.0, pixel.1, 0).unwrap()
}

#[test]
fn the_eye_segment_starts_at_the_camera_through_its_pixel() {
    let (world, settings) = world_and_settings(0.0);
    let camera = settings.render_camera(&world.view).unwrap();
    let tree = tree_of(&world, &settings, (17, 12));
    let segments = ray_segments(&tree, stub_length(&world), 0);
    let eye = segments[0];
    assert_eq!(
        eye.part,
        Part::Ray {
            kind: RayKindName::Eye
        }
    );
    assert_eq!(eye.phase, 0);
    assert!((eye.ends[0] - camera.eye()).length() < 1e-5);
    // The pixel's centre on the image plane lies on the segment.
    let on_plane = camera.view_plane_point(17.5, 12.5);
    let (a, b) = (eye.ends[0], eye.ends[1]);
    let along = (on_plane - a).dot((b - a).normalize());
    let off = ((on_plane - a) - (b - a).normalize() * along).length();
    assert!(off < 1e-4 && along > 0.0, "{off} off the eye ray");
    // Through the image in the camera's own projection, at the pixel.
    let seen = Projector::new(&camera).point((a + b) * 0.5).unwrap();
    assert!(
        (seen - glam::Vec2::new(17.5, 12.5)).length() < 1e-2,
        "{seen}"
    );
}

#[test]
fn a_trees_segments_are_its_rays_in_number_kind_and_generation() {
    let (world, settings) = world_and_settings(0.0);
    // The mirror sphere: a reflection, and shadow rays at every hit.
    let tree = tree_of(&world, &settings, (15, 14));
    let segments = ray_segments(&tree, stub_length(&world), 1);
    let rays: Vec<&Segment> = segments
        .iter()
        .filter(|s| !matches!(s.part, Part::Normal))
        .collect();
    assert_eq!(rays.len(), tree.nodes.len());
    let hits = tree
        .nodes
        .iter()
        .filter(|n| matches!(n.outcome, Outcome::Surface(_)))
        .count();
    assert_eq!(segments.len() - rays.len(), hits, "a normal per hit");
    assert!(tree.nodes.iter().any(|n| n.kind == RayKind::Reflection));
    let last_bounce = tree.nodes.iter().map(|n| n.depth).max().unwrap();
    for (segment, node) in rays.iter().zip(&tree.nodes) {
        assert_eq!(segment.side, 1);
        match (segment.part, node.kind) {
            (Part::Ray { kind }, k) => assert_eq!(kind, RayKindName::from(k)),
            (Part::BlockedShadow, RayKind::Shadow) => {}
            (part, kind) => panic!("{part:?} for a {kind:?} ray"),
        }
        let phase = if node.kind == RayKind::Shadow {
            last_bounce + 1
        } else {
            node.depth
        };
        assert_eq!(segment.phase, phase);
    }
}

#[test]
fn a_blocked_shadow_ray_ends_at_its_occluder() {
    let (world, settings) = world_and_settings(0.0);
    // The floor behind the red sphere, in its shadow from the first light.
    let blocked = (0..40)
        .flat_map(|x| (0..30).map(move |y| (x, y)))
        .map(|p| tree_of(&world, &settings, p))
        .find_map(|tree| {
            tree.nodes.iter().find_map(|n| match &n.outcome {
                Outcome::Light {
                    occluder: Some(o),
                    distance,
                    ..
                } => Some((n.origin, n.dir, o.t, *distance, tree.clone())),
                _ => None,
            })
        });
    let (origin, dir, t, distance, tree) = blocked.expect("a blocked shadow ray somewhere");
    assert!(t < distance);
    let segment = ray_segments(&tree, 1.0, 0)
        .into_iter()
        .find(|s| s.part == Part::BlockedShadow)
        .unwrap();
    assert!((segment.ends[1] - (origin + dir * t)).length() < 1e-4);
}

#[test]
fn the_frustum_runs_through_the_images_corners() {
    let (world, settings) = world_and_settings(6.0);
    let camera = settings.render_camera(&world.view).unwrap();
    let segments = camera_segments(&camera);
    let frustum: Vec<&Segment> = segments
        .iter()
        .filter(|s| s.part == Part::Frustum)
        .collect();
    assert_eq!(frustum.len(), 4);
    let projector = Projector::new(&camera);
    let (w, h) = (camera.width() as f32, camera.height() as f32);
    let corners = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)];
    for (segment, (x, y)) in frustum.iter().zip(corners) {
        assert!((segment.ends[0] - camera.eye()).length() < 1e-5);
        // Beyond the plane the edge still projects onto its corner.
        let far = segment.ends[0] + (segment.ends[1] - segment.ends[0]) * 3.0;
        let seen = projector.point(far).unwrap();
        assert!(
            (seen - glam::Vec2::new(x, y)).length() < 1e-2,
            "{seen} vs {x} {y}"
        );
    }
    assert_eq!(
        segments
            .iter()
            .filter(|s| s.part == Part::ImagePlane)
            .count(),
        4
    );
    // The lens: a circle of the lens radius around the eye, and the focal
    // plane at the focal ratio (1 here: on the image plane's rectangle
    // scaled by 1).
    let lens: Vec<&Segment> = segments.iter().filter(|s| s.part == Part::Lens).collect();
    assert!(lens.len() >= 16);
    for s in lens {
        let r = (s.ends[0] - camera.eye()).length();
        assert!((r - camera.lens_radius()).abs() < 1e-5, "{r}");
    }
    assert!(segments.iter().any(|s| s.part == Part::FocalPlane));
    let pinhole = world_and_settings(0.0)
        .1
        .render_camera(&world.view)
        .unwrap();
    assert!(
        camera_segments(&pinhole)
            .iter()
            .all(|s| !matches!(s.part, Part::Lens | Part::FocalPlane))
    );
}

#[test]
fn a_segment_behind_a_sphere_is_hidden_from_the_observer() {
    let (world, settings) = world_and_settings(0.0);
    let scene_camera = settings.render_camera(&world.view).unwrap();
    // The observer looks at the mirror sphere from the side, along +x.
    let pose = CameraPose {
        from: glam::Vec3::new(-6.0, 0.0, 0.8),
        at: glam::Vec3::new(-0.6, 0.0, 0.8),
        up: glam::Vec3::Z,
    };
    let observer = RenderSettings {
        width: 60,
        height: 60,
        camera: Some(pose),
        ..settings.clone()
    };
    let camera = observer.render_camera(&world.view).unwrap();
    let projector = Projector::new(&camera);
    let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
    let (_, depth) = render_with_depth(world.clone(), index, observer, Some(1)).unwrap();
    // A segment across the sphere's far side is hidden; the same in front
    // of it is not.
    let behind = [Vec3A::new(0.6, -0.3, 0.8), Vec3A::new(0.6, 0.3, 0.8)];
    let in_front = [Vec3A::new(-2.0, -0.3, 0.8), Vec3A::new(-2.0, 0.3, 0.8)];
    assert!(depth.split(&projector, behind, 8).iter().all(|(_, h)| *h));
    assert!(
        depth
            .split(&projector, in_front, 8)
            .iter()
            .all(|(_, h)| !*h)
    );
    // Framing fits the scene camera in the observer's view.
    let framed = framing(&world, &scene_camera, 40.0, 0.75);
    let framed_settings = RenderSettings {
        camera: Some(framed),
        ..settings
    };
    let framed_camera = framed_settings.render_camera(&world.view).unwrap();
    let p = Projector::new(&framed_camera)
        .point(scene_camera.eye())
        .unwrap();
    assert!(p.x > 0.0 && p.y > 0.0 && p.x < 40.0 && p.y < 30.0, "{p}");
}

#[test]
fn the_framing_takes_in_a_light_above_the_scene_but_not_a_far_sun() {
    let text = format!("{SCENE}l 0 0 14\nl 0 0 900\n");
    let scene = parse_scene(&text, None, &Limits::default()).unwrap();
    let world = Arc::new(World::build(&scene));
    let settings = RenderSettings::from_scene(&scene);
    let scene_camera = settings.render_camera(&world.view).unwrap();
    let framed = RenderSettings {
        camera: Some(framing(&world, &scene_camera, 40.0, 0.75)),
        ..settings
    };
    let camera = framed.render_camera(&world.view).unwrap();
    let inside = |p: Vec3A| {
        Projector::new(&camera)
            .point(p)
            .is_some_and(|p| p.x > 0.0 && p.y > 0.0 && p.x < 40.0 && p.y < 30.0)
    };
    assert!(inside(Vec3A::new(0.0, 0.0, 14.0)), "the light above");
    assert!(inside(scene_camera.eye()), "the camera");
    assert!(!inside(Vec3A::new(0.0, 0.0, 900.0)), "the sun is left out");
}

/// The observer renders the scene's own settings (depth, seed) from its
/// pose at its size, one sharp sample per pixel, once, with a BVH whatever
/// structure the scene asks for (`accel 0` over a large mesh took minutes).
#[test]
fn the_observer_renders_the_scenes_settings_sharp_from_its_pose() {
    let (world, mut scene) = world_and_settings(0.3);
    scene.antialiasing = true;
    scene.soft_shadows = true;
    scene.keep_refining = true;
    scene.accel = AccelKind::None;
    scene.max_depth = 3;
    let camera = scene.render_camera(&world.view).unwrap();
    let pose = framing(&world, &camera, 40.0, 0.75);
    let observer = render_settings(&scene, pose, 320, 240);
    assert_eq!(
        (observer.width, observer.height, observer.camera),
        (320, 240, Some(pose))
    );
    assert!(!observer.antialiasing && !observer.depth_of_field);
    assert!(!observer.soft_shadows && !observer.keep_refining);
    assert_eq!(observer.samples_per_pixel(), 1);
    assert_eq!(
        (observer.accel, observer.max_depth, observer.seed),
        (AccelKind::Bvh, scene.max_depth, scene.seed)
    );
    observer.validate().unwrap();
}

/// Every pixel's tree of [`SCENE`].
fn every_tree() -> (Arc<World>, Vec<RayTree>) {
    let (world, settings) = world_and_settings(0.0);
    let trees = (0..40)
        .flat_map(|x| (0..30).map(move |y| (x, y)))
        .map(|p| tree_of(&world, &settings, p))
        .collect();
    (world, trees)
}

#[test]
fn a_rays_share_is_what_it_and_its_children_add_to_the_pixel() {
    let (_, trees) = every_tree();
    let luminance = |c: Vec3A| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let mut blocked = 0;
    for tree in trees.iter().filter(|t| luminance(t.colour) > 1e-3) {
        let shares = ray_shares(tree);
        let total = luminance(tree.contributions());
        for (i, node) in tree.nodes.iter().enumerate() {
            let children: f32 = tree.children(Some(i)).map(|c| shares[c]).sum();
            let own = luminance(node.contribution) / total;
            assert!(
                (shares[i] - (own + children)).abs() < 1e-4,
                "pixel ({}, {}) node {i}: {} != {own} + {children}",
                tree.x,
                tree.y,
                shares[i]
            );
            match node.parent {
                None => assert!((shares[i] - 1.0).abs() < 1e-4, "the eye ray is the pixel"),
                Some(p) => assert!(shares[i] <= shares[p] + 1e-6),
            }
            if matches!(
                node.outcome,
                Outcome::Light {
                    occluder: Some(_),
                    ..
                }
            ) {
                assert_eq!(shares[i], 0.0, "a blocked shadow ray adds nothing");
                blocked += 1;
            }
        }
    }
    assert!(blocked > 0, "the scene has shadows");
}

#[test]
fn the_filter_hides_misses_thin_rays_and_deeper_bounces() {
    let (world, trees) = every_tree();
    let stub = stub_length(&world);
    let rays = |tree: &RayTree, filter: RayFilter| -> Vec<Segment> {
        filtered_ray_segments(tree, stub, 0, &filter)
            .into_iter()
            .filter(|s| s.part != Part::Normal)
            .collect()
    };
    let (mut misses, mut deeper, mut thin) = (0, 0, 0);
    for tree in &trees {
        let shares = ray_shares(tree);
        assert_eq!(
            filtered_ray_segments(tree, stub, 0, &RayFilter::default()),
            ray_segments(tree, stub, 0),
            "the default filter hides nothing"
        );
        let hits = tree
            .nodes
            .iter()
            .filter(|n| !matches!(n.outcome, Outcome::Background))
            .count();
        let no_misses = RayFilter {
            hide_misses: true,
            ..RayFilter::default()
        };
        assert_eq!(rays(tree, no_misses).len(), hits);
        misses += tree.nodes.len() - hits;

        let first = RayFilter {
            max_depth: Some(0),
            ..RayFilter::default()
        };
        let shown = rays(tree, first);
        assert!(shown.iter().all(|s| s.depth == 0));
        let at_0 = tree.nodes.iter().filter(|n| n.depth == 0).count();
        assert_eq!(shown.len(), at_0);
        deeper += tree.nodes.len() - at_0;

        let thick = RayFilter {
            min_share: 0.1,
            ..RayFilter::default()
        };
        let shown = rays(tree, thick);
        assert!(shown.iter().all(|s| s.share >= 0.1));
        let enough = shares.iter().filter(|&&s| s >= 0.1).count();
        assert_eq!(shown.len(), enough);
        thin += tree.nodes.len() - enough;
    }
    // Each filter had something to hide.
    assert!(
        misses > 0 && deeper > 0 && thin > 0,
        "{misses} {deeper} {thin}"
    );
}
