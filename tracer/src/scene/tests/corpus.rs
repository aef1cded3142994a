//! Every real scene file of the shared corpus parses into what it says.

use std::path::{Path, PathBuf};

use super::{assert_round_trip, corpus_dir};
use crate::scene::{Limits, Primitive, Scene, parse_scene_file};

fn corpus_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = ["p3d", "spd"]
        .iter()
        .filter_map(|sub| std::fs::read_dir(dir.join(sub)).ok())
        .flatten()
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|path| path.extension().is_some_and(|e| e == "p3f" || e == "nff"))
        .collect();
    files.sort();
    files
}

fn load(name: &str) -> Option<Scene> {
    let path = corpus_dir()?.join(name);
    Some(parse_scene_file(&path, &Limits::default()).unwrap_or_else(|e| panic!("{e}")))
}

fn count(scene: &Scene, kind: fn(&Primitive) -> bool) -> usize {
    scene.objects.iter().filter(|o| kind(&o.primitive)).count()
}

fn is_sphere(p: &Primitive) -> bool {
    matches!(p, Primitive::Sphere { .. })
}

fn is_polygon(p: &Primitive) -> bool {
    matches!(p, Primitive::Polygon { .. })
}

#[test]
fn every_corpus_file_parses_and_round_trips() {
    let Some(dir) = corpus_dir() else {
        return;
    };
    let files = corpus_files(dir);
    assert!(files.len() >= 12, "found only {files:?}");
    for path in files {
        let scene = parse_scene_file(&path, &Limits::default()).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.objects.is_empty(), "{}", path.display());
        assert_eq!(scene.base_dir.as_deref(), path.parent());
        assert_round_trip(&scene);
    }
}

#[test]
fn course_scenes_hold_what_they_declare() {
    let Some(scene) = load("p3d/balls_medium.p3f") else {
        return;
    };
    assert_eq!(count(&scene, is_sphere), 91);
    assert_eq!(count(&scene, is_polygon), 2);
    assert_eq!((scene.accel, scene.spp), (Some(2), Some(2)));
    assert_eq!(scene.env.as_deref(), Some("skybox"));
    assert_eq!((scene.materials.len(), scene.lights.len()), (2, 3));

    let plane = load("p3d/balls_medium_plane.p3f").unwrap_or_default();
    assert!(matches!(
        plane.objects[0].primitive,
        Primitive::Plane { .. }
    ));
    let boxed = load("p3d/balls_box.p3f").unwrap_or_default();
    assert!(
        boxed
            .objects
            .iter()
            .any(|o| matches!(o.primitive, Primitive::Box { .. }))
    );

    let dof = load("p3d/dof.p3f").unwrap_or_default();
    assert_eq!((dof.view.aperture, dof.view.focal), (12.0, 1.5));
    assert_eq!(load("p3d/dof_crlf.p3f"), Some(dof));
}

#[test]
fn spd_scenes_hold_what_they_declare() {
    let Some(gears) = load("spd/gears_s4.nff") else {
        return;
    };
    assert_eq!(count(&gears, is_polygon), 9345);
    let big = gears.objects.iter().filter(
        |o| matches!(&o.primitive, Primitive::Polygon { vertices } if vertices.len() == 144),
    );
    assert_eq!(big.count(), 128);
    assert_eq!((gears.materials.len(), gears.lights.len()), (65, 5));

    let rings = load("spd/rings_s7.nff").unwrap_or_default();
    let cones = count(&rings, |p| matches!(p, Primitive::Cone { .. }));
    assert_eq!((cones, count(&rings, is_sphere)), (4200, 4200));
    assert_eq!(rings.materials.len(), 841);

    let balls = load("spd/balls_s2.nff").unwrap_or_default();
    assert_eq!(count(&balls, is_sphere), 91);
    assert_eq!(balls.lights.len(), 3);
    let tetra = load("spd/tetra_s6.nff").unwrap_or_default();
    assert_eq!(count(&tetra, is_polygon), 4096);
}
