//! `mesh_file`: paths relative to the scene file, the optional transform,
//! materials, and errors that name both the scene's line and the mesh
//! file's; and the empty-scene error.

use std::path::Path;

use glam::Vec3;

use super::parse;
use crate::scene::{Limits, ParseErrorKind, Primitive, parse_scene_file};
use crate::scratch::Scratch;

/// A folder holding `scene.p3f` with `scene` and `models/tri.ply`.
fn scene_folder(test: &str, scene: &str) -> Scratch {
    let dir = Scratch::new(&format!("mesh-file-{test}"));
    std::fs::create_dir_all(dir.join("models")).unwrap();
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::fs::write(dir.join("models/tri.ply"), ply).unwrap();
    std::fs::write(dir.join("scene.p3f"), scene).unwrap();
    dir
}

fn parse_file(dir: &Path) -> Result<crate::scene::Scene, crate::scene::ParseError> {
    parse_scene_file(&dir.join("scene.p3f"), &Limits::default())
}

#[test]
fn a_mesh_file_is_read_relative_to_the_scene_and_transformed() {
    let text = "v from 0 0 5 at 0 0 0\nf 1 0 0 1 0 1 0 1\n\
                mesh_file models/tri.ply scale 2 translate 10 0 0\ns 0 0 0 1\n";
    let dir = scene_folder("relative", text);
    let scene = parse_file(&dir).unwrap();
    assert_eq!(scene.objects.len(), 2);
    let Primitive::Mesh {
        vertices,
        triangles,
    } = &scene.objects[0].primitive
    else {
        panic!("a mesh");
    };
    assert_eq!(vertices[1], Vec3::new(12.0, 0.0, 0.0));
    assert_eq!(triangles, &vec![[0, 1, 2]]);
    // The material in force (red) for the mesh and the sphere after it.
    assert_eq!(scene.objects[0].material, 0);
    assert_eq!(scene.objects[1].material, 0);
}

#[test]
fn a_missing_mesh_file_names_it_and_the_scene_line() {
    let dir = scene_folder(
        "missing",
        "v from 0 0 5 at 0 0 0\n  mesh_file models/gone.obj\n",
    );
    let error = parse_file(&dir).unwrap_err();
    assert_eq!((error.line, error.column), (2, 13));
    assert_eq!(error.command.as_deref(), Some("mesh_file"));
    let text = error.to_string();
    assert!(text.contains("scene.p3f:2:13: in `mesh_file`: "), "{text}");
    assert!(
        text.contains("gone.obj: cannot read the mesh file"),
        "{text}"
    );
}

#[test]
fn a_broken_mesh_file_names_its_own_line_too() {
    let dir = scene_folder("broken", "v from 0 0 5 at 0 0 0\nmesh_file bad.obj\n");
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n").unwrap();
    let text = parse_file(&dir).unwrap_err().to_string();
    assert!(text.contains("scene.p3f:2:11: in `mesh_file`: "), "{text}");
    assert!(text.contains("bad.obj:3: "), "{text}");
}

#[test]
fn mesh_file_arguments_are_checked() {
    let dir = scene_folder("arguments", "mesh_file models/tri.ply scale 0\n");
    let error = parse_file(&dir).unwrap_err();
    assert_eq!((error.line, error.column), (1, 32));
    let dir = scene_folder("no-path", "v from 0 0 5 at 0 0 0\nmesh_file");
    let error = parse_file(&dir).unwrap_err();
    assert!(matches!(error.kind, ParseErrorKind::MissingValue { .. }));
    // The mesh counts against the primitive limit.
    let dir = scene_folder(
        "limit",
        "mesh_file models/tri.ply\nmesh_file models/tri.ply\n",
    );
    let limits = Limits {
        max_primitives: 1,
        ..Limits::default()
    };
    let error = parse_scene_file(&dir.join("scene.p3f"), &limits).unwrap_err();
    assert_eq!((error.line, error.column), (2, 11), "{error}");
}

#[test]
fn an_empty_scene_says_what_is_missing() {
    for text in ["", "# only a comment\n\n", "  \n\t\n"] {
        let error = parse(text).unwrap_err();
        assert_eq!((error.line, error.column), (0, 0));
        assert!(
            error.to_string().contains("no command (only comments"),
            "{error}"
        );
    }
    let error = parse("b 0 0 0\nl 1 1 1\n").unwrap_err();
    let text = error.to_string();
    assert!(text.contains("no camera (`v`) and no objects"), "{text}");
    // A camera alone, or objects alone, is a scene.
    assert!(parse("v from 0 0 5 at 0 0 0").is_ok());
    assert!(parse("s 0 0 0 1").is_ok());
}

#[test]
fn a_mesh_files_warnings_reach_the_world_with_the_scene_line() {
    let dir = scene_folder("mtl-warning", "v from 0 0 5 at 0 0 0\nmesh_file tri.obj\n");
    let obj = "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    std::fs::write(dir.join("tri.obj"), obj).unwrap();
    let scene = parse_file(&dir).unwrap();
    let warnings = scene.warnings.join("\n");
    assert!(
        warnings.contains("scene.p3f:2:11: in `mesh_file`: ") && warnings.contains("gone.mtl"),
        "{warnings}"
    );
    let world = crate::world::World::build(&scene);
    assert!(
        world.warnings.iter().any(|w| w.contains("gone.mtl")),
        "{:?}",
        world.warnings
    );
}
