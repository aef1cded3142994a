//! The P3F writer gives back exactly the scene it was given.

use glam::Vec3;

use super::{assert_round_trip, parse_ok};
use crate::scene::{LightSpec, Material, Object, Primitive, Scene, write_p3f};

#[test]
fn every_command_round_trips() {
    let scene = parse_ok(
        "accel 1 spp 3 b 0.1 0.2 0.3 env sky_box\n\
         v from 1e-7 2 3 at 0 0 0 up 0 0 1 angle 33.3 hither 0.001 resolution 320 200 aperture 2 focal 0.7\n\
         l 1 2 3 l 4 5 6 0.5 0.25 1 al 0 9 0 0 0 0 3 2 al 0 9 0 0 0 0 3 2 1 0.5 0.25\n\
         s 0 0 0 1 s 1 1 1 -0.1\n\
         f 1 0.9 0.7 0.5 0.4 100000 0 1\n\
         f 1 1 1 0.1 0.957 0.639 0.536 1 190.0827 0.5 1.5\n\
         pl 0 0 0 1 0 0 0 1 0 p 4 0 0 0 1 0 0 1 1 0 0 1 0\n\
         pp 3 0 0 0 0 0 1 1 0 0 0 0 1 0 1 0 0 0 1\n\
         c 0 0 0 -1 0 0 2 -0.5 box 1 2 3 -1 -2 -3\n\
         mesh 4 2 0 0 0 1 0 0 1 1 0 0 1 0 1 2 3 -4 -2 -1\n\
         f 0.3 0.3 0.3 1 0 1 0 1\n\
         f 0.2 0.2 0.2 1 0 1 0 1\n",
    );
    assert_eq!(scene.materials.len(), 5);
    assert_round_trip(&scene);
}

#[test]
fn empty_scene_round_trips() {
    assert_round_trip(&Scene::default());
}

#[test]
fn extreme_floats_come_back_bit_exact() {
    let values = [f32::MAX, f32::MIN_POSITIVE, 1e-45, -3.4e38, 0.1, 1.0 / 3.0];
    let scene = Scene {
        lights: values
            .iter()
            .map(|&v| LightSpec::Point {
                position: Vec3::splat(v),
                color: Some(Vec3::new(v, -v, 0.0)),
            })
            .collect(),
        ..Scene::default()
    };
    assert_round_trip(&scene);
}

#[test]
fn material_written_once_before_its_first_object() {
    let scene = Scene {
        materials: vec![Material::default(), Material::default()],
        objects: vec![
            Object {
                primitive: Primitive::Box {
                    min: Vec3::ZERO,
                    max: Vec3::ONE,
                },
                material: 1,
            };
            2
        ],
        ..Scene::default()
    };
    let text = write_p3f(&scene);
    assert_eq!(text.matches("\nf ").count(), 2, "{text}");
    assert!(text.trim_end().ends_with("box 0 0 0 1 1 1"), "{text}");
    assert_round_trip(&scene);
}
