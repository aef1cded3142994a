//! Edits: every field and its inverse, the `--set` text both ways, bad
//! values refused with their message and the scene unchanged, random edits
//! undone in reverse order, the world kept in step, and moved objects
//! found alike by every structure.

use glam::{Vec3, Vec3A};
use proptest::prelude::*;

use super::{
    CameraChange, Edit, EditError, GeometryChange, LightChange, MaterialField, ObjectChange,
    apply_all,
};
use crate::accel::{AccelKind, SceneIndex};
use crate::geometry::Ray;
use crate::sampling::SampleStream;
use crate::scene::{LightSpec, Limits, Material, Scene, parse_scene, write_p3f};
use crate::stats::Counters;
use crate::world::World;

/// Every kind of object and light: material 0 shared by two spheres (one
/// inside-only), a glass sphere with a material of its own, an opaque
/// material with `ior 0` for the rest, and an unused last material.
const SCENE: &str = "\
v from 0 -12 3 at 0 0 0 up 0 0 1 angle 40 resolution 32 24
l 4 -4 6
al 0 0 8 0 0 0 2 1 1 0.9 0.8
f 1 0 0 0.7 1 1 1 0.3 30 0 1
s -2 0 0 1
s 2 0 0 -0.5
f 0.9 0.9 1 0.1 1 1 1 0.2 100 0.9 1.5
s 0 0 1.5 0.75
f 0.5 0.5 0.5 0.8 0 0 0 0 1 0 0
pl 0 0 -1 1 0 -1 0 1 -1
p 4 -1 -1 2 1 -1 2 1 1 2 -1 1 2
pp 3 0 0 3 0 0 1 1 0 3 0 0 1 0 1 3 0 0 1
c 3 3 0 1 3 3 2 0.5
box -4 -4 -1 -3 -3 0
mesh 4 2 0 2 0 1 2 0 1 3 0 0 3 1 1 2 3 1 3 4
f 0 1 0 1 0 0 0 0 1 0 1
";

fn scene() -> Scene {
    parse_scene(SCENE, None, &Limits::default()).unwrap()
}

fn edit(text: &str) -> Edit {
    text.parse()
        .unwrap_or_else(|e| panic!("'{text}' does not parse: {e}"))
}

/// One edit of every field of every target.
const EVERY_FIELD: &[&str] = &[
    // A shared material: object 0 gets its own copy.
    "object 0 diffuse 0 1 0.5",
    "object 0 kd 0.25",
    "object 1 specular 0.5 0.5 0.25",
    "object 1 ks 0.75",
    "object 0 shine 5",
    "object 0 t 0.5",
    "object 0 ior 1.25",
    // A material of its own: changed in place.
    "object 2 kd 0.3",
    "object 2 t 1",
    "object 2 ior 1.33",
    "object 2 own 1 1 1 1 0 0 0 0 1 0 1",
    "object 0 own 0.5 0.5 0.5 1 1 1 1 0.5 10 0.5 1.5",
    "object 0 centre 1 1 1",
    "object 0 center 1 2 3",
    "object 0 radius 2",
    "object 0 radius -2",
    "object 1 radius 0.25",
    "object 0 translate 1 0 0.1",
    "object 3 translate 0.1 0.2 0.3",
    "object 4 translate 0.1 0.2 0.3",
    "object 5 translate 0.1 0.2 0.3",
    "object 6 translate 0.1 0.2 0.3",
    "object 7 translate 0.1 0.2 0.3",
    "object 8 translate 0.1 0.2 0.3",
    "object 8 shape s 0 0 0 1",
    "object 2 shape mesh 3 1 0 0 0 1 0 0 0 1 0 1 2 3",
    "material 0 diffuse 0.1 0.2 0.3",
    "material 0 kd 0.1",
    "material 1 specular 0 0 1",
    "material 1 ks 0.9",
    "material 2 shine 200",
    "material 1 t 0.25",
    "material 1 ior 2",
    "material 3 kd 0.5",
    "light 0 position 1 2 3",
    "light 1 position 0 1 7",
    "light 0 colour 1 0 0",
    "light 1 color 0 0 1",
    "light 1 colour default",
    "light 1 aim 1 1 0",
    "light 1 size 3 0.5",
    "light 0 remove",
    "light 1 remove",
    "light 2 add l 1 2 3",
    "light 0 add al 0 0 5 0 0 0 1 2 0.5 0.5 0.5",
    "camera from 1 -10 2",
    "camera at 0 0 1",
    "camera up 0 1 1",
    "camera angle 60",
    "camera aperture 8",
    "camera focal 0.5",
];

/// Apply, undo, redo: each edit changes the scene, its inverse gives the
/// original back (equal, and byte-identical as P3F), and the inverse's
/// inverse redoes it. Each edit and inverse reads back from its text.
#[test]
fn every_field_round_trips() {
    let original = scene();
    let original_text = write_p3f(&original);
    for text in EVERY_FIELD {
        let forward = edit(text);
        assert_eq!(edit(&forward.to_string()), forward, "{text}");
        let mut edited = original.clone();
        let inverse = forward
            .apply(&mut edited)
            .unwrap_or_else(|e| panic!("'{text}' refused: {e}"));
        let edited_text = write_p3f(&edited);
        assert_ne!(edited_text, original_text, "'{text}' changed nothing");
        assert_eq!(edit(&inverse.to_string()), inverse, "{text}: {inverse}");
        let mut undone = edited.clone();
        let redo = inverse.apply(&mut undone).unwrap();
        assert_eq!(undone, original, "'{text}' undone by '{inverse}'");
        assert_eq!(write_p3f(&undone), original_text, "'{text}' undone");
        let mut redone = undone;
        redo.apply(&mut redone).unwrap();
        assert_eq!(
            write_p3f(&redone),
            edited_text,
            "'{text}' redone by '{redo}'"
        );
    }
}

#[test]
fn an_object_edit_copies_a_shared_material_and_a_material_edit_does_not() {
    let original = scene();
    let mut one = original.clone();
    let inverse = edit("object 0 kd 0.2").apply(&mut one).unwrap();
    assert_eq!(inverse, edit("object 0 share 0"));
    assert_eq!(one.materials.len(), original.materials.len() + 1);
    assert_eq!(one.objects[0].material as usize, original.materials.len());
    assert_eq!(one.materials.last().unwrap().kd, 0.2);
    // Object 1 keeps material 0 as it was.
    assert_eq!(one.objects[1].material, 0);
    assert_eq!(one.materials[0], original.materials[0]);

    let mut all = original.clone();
    edit("material 0 kd 0.2").apply(&mut all).unwrap();
    assert_eq!(all.materials.len(), original.materials.len());
    assert_eq!(all.materials[0].kd, 0.2);
    assert_eq!((all.objects[0].material, all.objects[1].material), (0, 0));
}

/// A translation's inverse restores the exact geometry, where adding the
/// opposite offset back would round.
#[test]
fn a_translation_is_undone_exactly() {
    let mut scene = scene();
    let original = scene.clone();
    let by = edit("object 4 translate 0 0 0.1");
    let inverse = by.apply(&mut scene).unwrap();
    assert!(matches!(
        inverse,
        Edit::Object {
            change: ObjectChange::Geometry(GeometryChange::Shape(_)),
            ..
        }
    ));
    let mut back = scene.clone();
    edit("object 4 translate 0 0 -0.1")
        .apply(&mut back)
        .unwrap();
    assert_ne!(back, original, "the fixture should round off");
    inverse.apply(&mut scene).unwrap();
    assert_eq!(scene, original);
}

/// What each bad edit says; the scene stays as it was.
#[test]
fn bad_edits_are_refused_with_their_message() {
    let object_fields = "diffuse, kd, specular, ks, shine, t, ior, translate, shape, own, share";
    let sphere_fields =
        "diffuse, kd, specular, ks, shine, t, ior, centre, radius, translate, shape, own, share";
    let cases: &[(&str, String)] = &[
        (
            "object 12 kd 0.5",
            "object 12: the scene has 9 objects (0..8)".into(),
        ),
        (
            "object 0 iorr 1.5",
            format!("no field 'iorr' for a sphere; fields: {sphere_fields}"),
        ),
        (
            "object 3 radius 1",
            format!("no field 'radius' for a plane; fields: {object_fields}"),
        ),
        (
            "object 8 centre 0 0 0",
            format!("no field 'centre' for a mesh; fields: {object_fields}"),
        ),
        (
            "object 0 kd nan",
            "kd must be a finite number, found nan".into(),
        ),
        (
            "object 0 translate 0 inf 0",
            "translate must be a finite number, found inf".into(),
        ),
        (
            "object 0 kd much",
            "kd: expected a number, found 'much'".into(),
        ),
        ("object 0 ior 1 2", "ior takes 1 number, found 2".into()),
        (
            "object 0 diffuse 1 1",
            "diffuse takes 3 numbers (X Y Z), found 2".into(),
        ),
        (
            "object 0 radius 0",
            "invalid sphere radius: must not be zero".into(),
        ),
        (
            "object 0 t 1.5",
            "invalid transmittance: must lie in 0..1, found 1.5".into(),
        ),
        (
            "material 1 t -0.5",
            "invalid transmittance: must lie in 0..1, found -0.5".into(),
        ),
        (
            "object 3 t 0.5",
            "invalid index of refraction: must be greater than 0 for a transmitting material \
             (T 0.5), found 0"
                .into(),
        ),
        (
            "object 2 ior 0",
            "invalid index of refraction: must be greater than 0 for a transmitting material \
             (T 0.9), found 0"
                .into(),
        ),
        (
            "object 7 translate 3.4e38 0 0",
            "invalid box: it has zero thickness along an axis".into(),
        ),
        (
            "object x kd 1",
            "object 'x': not an index (objects count from 0)".into(),
        ),
        (
            "object 2 share 0",
            "object 2: its material 1 is not its own (the scene's last, used by it alone), so it \
             cannot go back to sharing"
                .into(),
        ),
        (
            "object 0 shape s 0 0 0 0",
            "shape: <input>:1:9: in `s`: invalid sphere radius: must not be zero".into(),
        ),
        (
            "object 0 shape l 0 0 0",
            "shape: expected a P3F shape command (s, pl, p, pp, c, box, mesh), found 'l'".into(),
        ),
        (
            "object 0 shape s 0 0 0 1 s 1 1 1 1",
            "shape: give exactly one shape command".into(),
        ),
        (
            "material 4 kd 1",
            "material 4: the scene has 4 materials (0..3)".into(),
        ),
        (
            "material 0 radius 1",
            "no field 'radius' for a material; fields: diffuse, kd, specular, ks, shine, t, ior"
                .into(),
        ),
        (
            "light 2 position 0 0 0",
            "light 2: the scene has 2 lights (0..1)".into(),
        ),
        (
            "light 0 aim 1 1 1",
            "no field 'aim' for a point light; fields: position, colour, remove, add".into(),
        ),
        (
            "light 0 dim 1",
            "no field 'dim' for a light; fields: position, colour, aim, size, remove, add".into(),
        ),
        (
            "light 1 size 0 1",
            "invalid area light size: must be greater than 0, found 0".into(),
        ),
        (
            "light 1 aim 0 0 8",
            "invalid area light: it faces its own centre".into(),
        ),
        (
            "light 0 remove now",
            "remove takes no values, found 1".into(),
        ),
        (
            "light 3 add l 0 0 0",
            "light 3: a new light goes at 0..2 (the scene has 2 lights)".into(),
        ),
        (
            "light 0 add al 0 0 1 0 0 0 0 1",
            "add: <input>:1:16: in `al`: invalid area light size: must be greater than 0, found 0"
                .into(),
        ),
        (
            "camera at 0 -12 3",
            "invalid camera: `from` and `at` are the same point".into(),
        ),
        (
            "camera up 0 12 -3",
            "invalid camera: `up` is parallel to the view direction".into(),
        ),
        (
            "camera angle 180",
            "invalid field of view angle: must lie strictly between 0 and 180 degrees, found 180"
                .into(),
        ),
        (
            "camera aperture -1",
            "invalid aperture: must not be negative, found -1".into(),
        ),
        (
            "camera focal 0",
            "invalid focal distance: must be greater than 0".into(),
        ),
        (
            "camera zoom 2",
            "no field 'zoom' for the camera; fields: from, at, up, angle, aperture, focal".into(),
        ),
        (
            "wobble 1",
            "unknown edit 'wobble': an edit starts with object, material, light or camera".into(),
        ),
        (
            "  ",
            "empty edit: give e.g. 'object 0 kd 0.5' or 'camera aperture 8'".into(),
        ),
    ];
    let original = scene();
    for (text, message) in cases {
        let mut scene = original.clone();
        let error = Edit::parse_in(text, &scene)
            .and_then(|e| e.apply(&mut scene))
            .expect_err(text);
        assert_eq!(&error.to_string(), message, "{text}");
        assert_eq!(write_p3f(&scene), write_p3f(&original), "{text}");
    }
}

/// Edits built in code are checked as text is: no NaN, no infinity.
#[test]
fn edits_built_in_code_refuse_non_finite_numbers() {
    let mut scene = scene();
    let original = scene.clone();
    let nan = [
        Edit::Material {
            index: 0,
            field: MaterialField::Ior(f32::NAN),
        },
        Edit::Camera(CameraChange::Aperture(f32::INFINITY)),
        Edit::Light {
            index: 0,
            change: LightChange::Colour(Some(Vec3::new(1.0, f32::NAN, 0.0))),
        },
        Edit::AddLight {
            index: 0,
            light: LightSpec::Point {
                position: Vec3::splat(f32::INFINITY),
                color: None,
            },
        },
        Edit::Object {
            index: 0,
            change: ObjectChange::Own(Material {
                shine: f32::NAN,
                ..Material::default()
            }),
        },
    ];
    for edit in nan {
        let error = edit.apply(&mut scene).expect_err(&format!("{edit:?}"));
        assert!(error.to_string().contains("finite"), "{error}");
    }
    assert_eq!(scene, original);
}

/// The parser refuses in a file what an edit refuses, in the same words.
#[test]
fn the_parser_and_edits_share_their_rules() {
    let cases = [
        ("s 0 0 0 0", "object 0 radius 0"),
        ("f 1 1 1 1 0 1 1.5 1", "material 0 t 1.5"),
        ("f 1 1 1 1 0 1 0.5 0", "material 2 t 0.5"),
        ("al 0 0 1 0 0 0 0 1", "light 1 size 0 1"),
        ("v from 0 0 5 at 0 0 0 angle 180", "camera angle 180"),
        ("v from 0 0 5 at 0 0 0 focal 0", "camera focal 0"),
        ("v from 0 0 5 at 0 0 0 aperture -1", "camera aperture -1"),
    ];
    for (file, set) in cases {
        let parsed = parse_scene(file, None, &Limits::default()).expect_err(file);
        let edited = edit(set).apply(&mut scene()).expect_err(set);
        assert_eq!(
            parsed.kind.to_string(),
            edited.to_string(),
            "{file} / {set}"
        );
    }
}

#[test]
fn a_batch_is_all_or_nothing() {
    let mut scene = scene();
    let original = scene.clone();
    let edits = [
        "object 0 kd 0.1",
        "light 0 position 0 0 9",
        "object 12 kd 1",
    ]
    .map(edit);
    let (failed, error) = apply_all(&edits, &mut scene).unwrap_err();
    assert_eq!(failed, 2);
    assert!(matches!(error, EditError::NoSuch { .. }));
    assert_eq!(write_p3f(&scene), write_p3f(&original));
    let undo = apply_all(&edits[..2], &mut scene).unwrap();
    assert_ne!(scene, original);
    apply_all(&undo, &mut scene).unwrap();
    assert_eq!(scene, original);
}

#[test]
fn descriptions_name_objects_as_the_inspector_does() {
    let scene = scene();
    let cases = [
        ("object 2 ior 1.33", "sphere #2 ior 1.33"),
        ("object 8 translate 1 0 0", "mesh #8 translate 1 0 0"),
        ("object 0 share 3", "sphere #0 shares material 3"),
        ("object 7 shape s 0 0 0 1", "box #7 reshaped as a sphere"),
        ("material 1 kd 0.5", "material 1 kd 0.5"),
        ("light 1 remove", "light 1 removed"),
        ("camera aperture 8", "camera aperture 8"),
    ];
    for (text, description) in cases {
        assert_eq!(edit(text).describe(&scene), description);
    }
}

/// The parts of two worlds that rendering reads.
fn assert_same_world(updated: &World, built: &World, context: &str) {
    assert_eq!(updated.shapes, built.shapes, "{context}");
    assert_eq!(updated.shape_surface, built.shape_surface, "{context}");
    assert_eq!(updated.shape_object, built.shape_object, "{context}");
    assert_eq!(updated.object_kinds, built.object_kinds, "{context}");
    assert_eq!(updated.surfaces, built.surfaces, "{context}");
    assert_eq!(updated.lights, built.lights, "{context}");
    assert_eq!(updated.view, built.view, "{context}");
    assert_eq!(updated.bounds, built.bounds, "{context}");
    assert_eq!(updated.counts, built.counts, "{context}");
}

fn vec3(range: std::ops::Range<f32>) -> impl Strategy<Value = Vec3> {
    [range.clone(), range.clone(), range].prop_map(Vec3::from)
}

fn material_field() -> impl Strategy<Value = MaterialField> {
    use MaterialField as F;
    prop_oneof![
        vec3(0.0..1.0).prop_map(F::Diffuse),
        (0.0f32..1.0).prop_map(F::Kd),
        vec3(0.0..1.0).prop_map(F::Specular),
        (0.0f32..1.0).prop_map(F::Ks),
        (1.0f32..500.0).prop_map(F::Shine),
        // Some out of 0..1, some needing an ior the material lacks.
        (-0.2f32..1.2).prop_map(F::Transmittance),
        (-0.5f32..2.5).prop_map(F::Ior),
    ]
}

/// Edits of every kind, some with indices past the end or values the
/// rules refuse.
fn any_edit() -> impl Strategy<Value = Edit> {
    use GeometryChange as G;
    prop_oneof![
        (0usize..11, material_field()).prop_map(|(index, f)| Edit::Object {
            index,
            change: ObjectChange::Material(f)
        }),
        (0usize..5, material_field()).prop_map(|(index, field)| Edit::Material { index, field }),
        (0usize..11, 0u32..6).prop_map(|(index, m)| Edit::Object {
            index,
            change: ObjectChange::Share(m)
        }),
        (0usize..11, 0.0f32..1.0).prop_map(|(index, kd)| Edit::Object {
            index,
            change: ObjectChange::Own(Material {
                kd,
                ..Material::default()
            })
        }),
        (0usize..11, vec3(-2.0..2.0)).prop_map(|(index, by)| Edit::Object {
            index,
            change: ObjectChange::Geometry(G::Translate(by))
        }),
        (0usize..3, vec3(-3.0..3.0)).prop_map(|(index, at)| Edit::Object {
            index,
            change: ObjectChange::Geometry(G::Centre(at))
        }),
        (0usize..3, -2.0f32..2.0).prop_map(|(index, r)| Edit::Object {
            index,
            change: ObjectChange::Geometry(G::Radius(r))
        }),
        (0usize..3, vec3(-5.0..5.0)).prop_map(|(index, p)| Edit::Light {
            index,
            change: LightChange::Position(p)
        }),
        (0usize..3, prop::option::of(vec3(0.0..1.0))).prop_map(|(index, c)| Edit::Light {
            index,
            change: LightChange::Colour(c)
        }),
        (0usize..3, 0.0f32..2.0, 0.0f32..2.0).prop_map(|(index, width, height)| Edit::Light {
            index,
            change: LightChange::Size { width, height }
        }),
        (0usize..4, vec3(-5.0..5.0)).prop_map(|(index, position)| Edit::AddLight {
            index,
            light: LightSpec::Point {
                position,
                color: None
            }
        }),
        (0usize..3).prop_map(Edit::RemoveLight),
        vec3(-1.0..1.0).prop_map(|at| Edit::Camera(CameraChange::At(at))),
        (0.0f32..200.0).prop_map(|a| Edit::Camera(CameraChange::Angle(a))),
        (-1.0f32..10.0).prop_map(|a| Edit::Camera(CameraChange::Aperture(a))),
    ]
}

/// Random rays through the scene's region, the same for every structure.
fn rays(seed: u64, count: u32) -> impl Iterator<Item = Ray> {
    (0..count).filter_map(move |i| {
        let mut random = SampleStream::new(seed, i, 0);
        let mut point = |scale: f32| {
            Vec3A::new(random.next_1d(), random.next_1d(), random.next_1d()) * (2.0 * scale) - scale
        };
        let origin = point(8.0);
        let dir = point(1.0);
        (dir.length_squared() > 1e-6).then(|| Ray::new(origin, dir))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random edits applied in turn (refused ones change nothing), then
    /// their inverses in reverse order, give the original scene back; the
    /// world updated edit by edit is the world built from the edited scene.
    #[test]
    fn random_edits_and_their_inverses_restore_the_scene(
        edits in prop::collection::vec(any_edit(), 1..12)
    ) {
        let original = scene();
        let mut scene = original.clone();
        let mut world = World::build(&scene);
        let mut undo = Vec::new();
        for edit in &edits {
            let before = scene.clone();
            match edit.apply(&mut scene) {
                Ok(inverse) => {
                    world.update(&scene, edit);
                    undo.push(inverse);
                }
                Err(_) => prop_assert_eq!(&scene, &before, "{} refused", edit),
            }
        }
        assert_same_world(&world, &World::build(&scene), &format!("{edits:?}"));
        for inverse in undo.iter().rev() {
            inverse.apply(&mut scene).unwrap();
            world.update(&scene, inverse);
        }
        prop_assert_eq!(&scene, &original);
        prop_assert_eq!(write_p3f(&scene), write_p3f(&original));
        assert_same_world(&world, &World::build(&original), "undone");
    }

    /// Moving objects (the world updated in place) leaves no structure
    /// behind: none, the grid and the BVH find the same hits.
    #[test]
    fn moved_objects_are_hit_alike_by_every_structure(
        moves in prop::collection::vec((0usize..9, vec3(-3.0..3.0)), 1..6),
        seed in any::<u64>(),
    ) {
        let mut scene = scene();
        let mut world = World::build(&scene);
        for (index, by) in moves {
            let edit = Edit::Object {
                index,
                change: ObjectChange::Geometry(GeometryChange::Translate(by)),
            };
            edit.apply(&mut scene).unwrap();
            world.update(&scene, &edit);
        }
        // The reference: brute force over the world built from scratch.
        let built = World::build(&scene);
        let reference = SceneIndex::build(&built.shapes, AccelKind::None, 2.0);
        let shapes = &world.shapes;
        let indices = AccelKind::ALL.map(|kind| SceneIndex::build(shapes, kind, 2.0));
        let counters = &mut Counters::default();
        for ray in rays(seed, 400) {
            let expected =
                reference.closest_hit(&built.shapes, &ray, 0.0, f32::INFINITY, counters);
            for index in &indices {
                let hit = index.closest_hit(shapes, &ray, 0.0, f32::INFINITY, counters);
                prop_assert_eq!(hit, expected, "{:?} on {:?}", index.kind(), ray);
            }
        }
    }

    /// Any edit's `--set` line reads back as the same edit.
    #[test]
    fn the_set_text_reads_back(edit in any_edit()) {
        let text = edit.to_string();
        prop_assert_eq!(text.parse::<Edit>(), Ok(edit), "{}", text);
    }
}
