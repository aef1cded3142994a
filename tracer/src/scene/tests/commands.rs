//! Every command parses into the document it describes.

use glam::Vec3;

use super::parse_ok;
use crate::scene::{LightSpec, Material, Object, Primitive, Viewpoint};

#[test]
fn view_fields_come_in_any_order_and_spill_over_lines() {
    let scene = parse_ok(
        "v resolution 640\n480 angle 30 up 0 0 1 at 1 2\n3\tfrom 4 5 6 focal 2 aperture 1.5 hither 0.01\ns 0 0 0 1",
    );
    assert_eq!(
        scene.view,
        Viewpoint {
            from: Vec3::new(4.0, 5.0, 6.0),
            at: Vec3::new(1.0, 2.0, 3.0),
            up: Vec3::Z,
            angle: 30.0,
            hither: 0.01,
            width: 640,
            height: 480,
            aperture: 1.5,
            focal: 2.0,
        }
    );
    assert_eq!(scene.objects.len(), 1);
}

#[test]
fn view_defaults_to_pinhole_focused_on_the_view_plane() {
    let scene = parse_ok("v from 0 0 1 at 0 0 0 up 0 1 0 angle 45 hither 0 resolution 8 8");
    assert_eq!(scene.view.aperture, 0.0);
    assert_eq!(scene.view.focal, 1.0);
}

#[test]
fn background_both_spellings_env_accel_spp_adaptive() {
    let scene = parse_ok("v\nb 0.1 0.2 0.3");
    assert_eq!(scene.background, Vec3::new(0.1, 0.2, 0.3));
    let scene = parse_ok("v\nbclr 1 +2 3e-1\nenv skybox\naccel 2\nspp 4");
    assert_eq!(scene.background, Vec3::new(1.0, 2.0, 0.3));
    assert_eq!(scene.env.as_deref(), Some("skybox"));
    assert_eq!((scene.accel, scene.spp), (Some(2), Some(4)));
    let scene = parse_ok("v accel 0 spp 0");
    assert_eq!((scene.accel, scene.spp), (Some(0), Some(0)));
    assert_eq!(scene.adaptive, None);
    let scene = parse_ok("v spp 12 adaptive 0.007");
    assert_eq!((scene.spp, scene.adaptive), (Some(12), Some(0.007)));
}

#[test]
fn lights_with_and_without_color() {
    let scene =
        parse_ok("v\nl 1 2 3\nl 4 5 6 0.5 0.5 1\nal 0 5 0 0 0 0 2 1\nal 0 5 0 0 0 0 2 1 1 1 0");
    assert_eq!(
        scene.lights,
        vec![
            LightSpec::Point {
                position: Vec3::new(1.0, 2.0, 3.0),
                color: None
            },
            LightSpec::Point {
                position: Vec3::new(4.0, 5.0, 6.0),
                color: Some(Vec3::new(0.5, 0.5, 1.0))
            },
            LightSpec::Area {
                centre: Vec3::new(0.0, 5.0, 0.0),
                aim: Vec3::ZERO,
                width: 2.0,
                height: 1.0,
                color: None
            },
            LightSpec::Area {
                centre: Vec3::new(0.0, 5.0, 0.0),
                aim: Vec3::ZERO,
                width: 2.0,
                height: 1.0,
                color: Some(Vec3::new(1.0, 1.0, 0.0))
            },
        ]
    );
}

#[test]
fn materials_in_both_forms_and_the_default_before_any_f() {
    let scene = parse_ok(
        "s 0 0 0 1\nf 1 0.9 0.7 0.5 0.4 100000 0 1\ns 0 0 0 2\nf 1 1 1 0.0 0.957 0.639 0.536 1 190.0827 0.5 1.5\nf 0 0 0 0 0 0 0 0 0 0 0\ns 0 0 0 3",
    );
    assert_eq!(
        scene.materials,
        vec![
            Material::default(),
            Material {
                diffuse: Vec3::new(1.0, 0.9, 0.7),
                kd: 0.5,
                specular: Vec3::ONE,
                ks: 0.4,
                shine: 100000.0,
                transmittance: 0.0,
                ior: 1.0,
            },
            Material {
                diffuse: Vec3::ONE,
                kd: 0.0,
                specular: Vec3::new(0.957, 0.639, 0.536),
                ks: 1.0,
                shine: 190.0827,
                transmittance: 0.5,
                ior: 1.5,
            },
            Material {
                diffuse: Vec3::ZERO,
                kd: 0.0,
                specular: Vec3::ZERO,
                ks: 0.0,
                shine: 0.0,
                transmittance: 0.0,
                ior: 0.0,
            },
        ]
    );
    let indices: Vec<u32> = scene.objects.iter().map(|o| o.material).collect();
    assert_eq!(indices, [0, 1, 3]);
}

#[test]
fn default_material_is_pushed_once_and_only_when_needed() {
    let scene = parse_ok("s 0 0 0 1 s 1 1 1 1");
    assert_eq!(scene.materials, vec![Material::default()]);
    assert!(parse_ok("v f 1 1 1 1 0 1 0 1").objects.is_empty());
    assert!(parse_ok("v").materials.is_empty());
}

fn primitives(text: &str) -> Vec<Primitive> {
    parse_ok(text)
        .objects
        .into_iter()
        .map(|Object { primitive, .. }| primitive)
        .collect()
}

#[test]
fn spheres_planes_and_boxes() {
    assert_eq!(
        primitives("s 1 2 3 0.5 s 0 0 0 -2 pl 0 0 0 1 0 0 0 1 0 box 1 2 3 -1 -2 -3"),
        vec![
            Primitive::Sphere {
                centre: Vec3::new(1.0, 2.0, 3.0),
                radius: 0.5,
                inside_only: false
            },
            Primitive::Sphere {
                centre: Vec3::ZERO,
                radius: 2.0,
                inside_only: true
            },
            Primitive::Plane {
                points: [Vec3::ZERO, Vec3::X, Vec3::Y]
            },
            Primitive::Box {
                min: Vec3::new(-1.0, -2.0, -3.0),
                max: Vec3::new(1.0, 2.0, 3.0)
            },
        ]
    );
}

#[test]
fn polygons_patches_and_cones() {
    assert_eq!(
        primitives(
            "p 3 0 0 0\n1 0 0\n0 1 0\npp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\nc 0 0 0 -1 0 0 2 -0.5\nc 0 0 0 1 0 0 2 0"
        ),
        vec![
            Primitive::Polygon {
                vertices: vec![Vec3::ZERO, Vec3::X, Vec3::Y]
            },
            Primitive::Patch {
                vertices: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
                normals: vec![Vec3::Z; 3]
            },
            Primitive::Cone {
                base: Vec3::ZERO,
                base_radius: 1.0,
                apex: Vec3::new(0.0, 0.0, 2.0),
                apex_radius: 0.5
            },
            Primitive::Cone {
                base: Vec3::ZERO,
                base_radius: 1.0,
                apex: Vec3::new(0.0, 0.0, 2.0),
                apex_radius: 0.0
            },
        ]
    );
}

#[test]
fn mesh_indices_are_one_based_or_negative_from_the_end() {
    assert_eq!(
        primitives("mesh 4 2\n0 0 0 1 0 0 1 1 0 0 1 0\n1 2 3\n-4 -2 -1"),
        vec![Primitive::Mesh {
            vertices: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }]
    );
}

#[test]
fn comments_crlf_tabs_and_number_spellings() {
    let scene = parse_ok(
        "#background color azulada\r\n# full line\r\nbclr\t1e0 .5 -0.\r\n#pl 12 12 -0.5 x y z\r\ns 1.11022e-16 +2 3E+1 4 # trailing # comment\r\n",
    );
    assert_eq!(scene.background, Vec3::new(1.0, 0.5, 0.0));
    assert_eq!(
        scene.objects[0].primitive,
        Primitive::Sphere {
            centre: Vec3::new(1.11022e-16, 2.0, 30.0),
            radius: 4.0,
            inside_only: false
        }
    );
}

#[test]
fn parse_scene_file_sets_base_dir_and_names_the_file() {
    let dir = crate::scratch::Scratch::new("parse");
    let path = dir.join("scene.nff");
    std::fs::write(&path, "s 0 0 0 1\n").unwrap();
    let scene = crate::scene::parse_scene_file(&path, &Default::default()).unwrap();
    assert_eq!(scene.base_dir.as_deref(), Some(&*dir));
    std::fs::write(&path, "s 0 0 0 0\n").unwrap();
    let error = crate::scene::parse_scene_file(&path, &Default::default()).unwrap_err();
    assert_eq!(error.file.as_deref(), Some(path.as_path()));
}
