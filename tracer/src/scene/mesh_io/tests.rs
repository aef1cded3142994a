//! OBJ and PLY reading on small files written by the tests: good files,
//! broken ones (each error's place and message), the limits, and the
//! framing of a bare mesh.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::*;
use crate::scene::{LightSpec, Primitive};
use crate::scratch::Scratch;
use crate::world::World;

/// A fresh folder for one test's files.
fn folder(test: &str) -> Scratch {
    Scratch::new(&format!("mesh-io-{test}"))
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn load(path: &Path) -> Result<MeshFile, MeshFileError> {
    load_with(path, &Limits::default())
}

fn load_with(path: &Path, limits: &Limits) -> Result<MeshFile, MeshFileError> {
    load_mesh_file(path, limits, limits.max_primitives, &mut |_| {})
}

const CUBE_OBJ: &str = "\
# a unit cube, quads, with a material library
mtllib cube.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
o cube
usemtl red
f 1 2 3 4
f 5 8 7 6
f 1 5 6 2
f 2 6 7 3
f 3 7 8 4
f -4 -8 -5 -1
";

const CUBE_MTL: &str = "newmtl red\nKd 0.9 0.1 0.1\nKs 0.5 0.5 0.5\nNs 50\n";

#[test]
fn an_obj_with_quads_and_mtl_colours_loads_as_triangles() {
    let dir = folder("obj-cube");
    write(&dir, "cube.mtl", CUBE_MTL.as_bytes());
    let mesh = load(&write(&dir, "cube.obj", CUBE_OBJ.as_bytes())).unwrap();
    assert!(mesh.warnings.is_empty(), "{:?}", mesh.warnings);
    assert_eq!(mesh.parts.len(), 1);
    let part = &mesh.parts[0];
    assert_eq!((part.vertices.len(), part.triangles.len()), (8, 12));
    let material = part.material.expect("the MTL colour");
    assert_eq!(material.diffuse, Vec3::new(0.9, 0.1, 0.1));
    assert_eq!((material.shine, material.ks), (50.0, 0.25));
    // Negative indices count back from the last vertex.
    assert!(part.triangles.iter().all(|t| t.iter().all(|&i| i < 8)));
}

#[test]
fn a_missing_mtl_is_a_warning_and_the_mesh_stays_grey() {
    let dir = folder("obj-no-mtl");
    let mesh = load(&write(&dir, "cube.obj", CUBE_OBJ.as_bytes())).unwrap();
    assert_eq!(mesh.parts[0].material, None);
    let warnings = mesh.warnings.join("; ");
    assert!(
        warnings.contains("cube.mtl") && warnings.contains("grey"),
        "{warnings}"
    );
}

/// Each broken OBJ gives its line and what is wrong, never a panic.
#[test]
fn a_broken_obj_names_the_line() {
    let dir = folder("obj-broken");
    let cases: [(&str, &str, &str); 5] = [
        ("v 0 0 0\nv 1 0\nf 1 2 3\n", ":2: ", "three numbers"),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n",
            ":4: ",
            "vertex indices",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            ":4: ",
            "not defined",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
            ":4: ",
            "not defined",
        ),
        (
            "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "",
            "not a finite number",
        ),
    ];
    for (i, (text, place, message)) in cases.into_iter().enumerate() {
        let path = write(&dir, &format!("broken{i}.obj"), text.as_bytes());
        let error = load(&path).unwrap_err().to_string();
        assert!(error.starts_with(&path.display().to_string()), "{error}");
        assert!(
            error.contains(place) && error.contains(message),
            "{text:?}: {error}"
        );
    }
}

#[test]
fn files_without_triangles_or_with_other_names_are_refused() {
    let dir = folder("no-triangles");
    let error = load(&write(&dir, "empty.obj", b"# nothing\n")).unwrap_err();
    assert_eq!(error.place, MeshPlace::File);
    assert!(error.message.contains("no triangle"), "{error}");
    let binary = write(&dir, "noise.obj", &[0xff, 0xfe, 0, 1, 2, 3, 0x80, 10]);
    assert!(load(&binary).is_err());
    let error = load(&write(&dir, "mesh.stl", b"solid")).unwrap_err();
    assert!(error.message.contains(".obj or .ply"), "{error}");
    let error = load(&dir.join("missing.ply")).unwrap_err();
    assert!(error.message.contains("cannot read"), "{error}");
    std::fs::create_dir_all(dir.join("folder.obj")).unwrap();
    let error = load(&dir.join("folder.obj")).unwrap_err();
    assert!(error.message.contains("not a regular file"), "{error}");
}

#[test]
fn limits_are_checked_before_the_mesh_is_kept() {
    let dir = folder("limits");
    let path = write(&dir, "cube.obj", CUBE_OBJ.as_bytes());
    let small = Limits {
        max_mesh_triangles: 11,
        ..Limits::default()
    };
    let error = load_with(&path, &small).unwrap_err().to_string();
    assert!(
        error.contains("triangle count 12 exceeds the limit of 11"),
        "{error}"
    );
    let tiny = Limits {
        max_file_bytes: 10,
        ..Limits::default()
    };
    let error = load_with(&path, &tiny).unwrap_err().to_string();
    assert!(error.contains("exceeds the limit of 10"), "{error}");

    let ply = write(&dir, "big.ply", ply_header(4_000_000_000, 1).as_bytes());
    let error = load(&ply).unwrap_err().to_string();
    assert!(error.contains("vertex count 4000000000 exceeds"), "{error}");
}

fn ply_header(vertices: u64, faces: u64) -> String {
    format!(
        "ply\nformat ascii 1.0\ncomment test\nelement vertex {vertices}\nproperty float x\n\
         property float y\nproperty float z\nelement face {faces}\n\
         property list uchar int vertex_indices\nend_header\n"
    )
}

#[test]
fn an_ascii_ply_loads_and_polygons_are_fanned() {
    let dir = folder("ply-ascii");
    let text = ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let mesh = load(&write(&dir, "quad.ply", text.as_bytes())).unwrap();
    let part = &mesh.parts[0];
    assert_eq!(part.name, "quad");
    assert_eq!(part.vertices[2], Vec3::new(1.0, 1.0, 0.0));
    assert_eq!(part.triangles, vec![[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn a_binary_ply_loads_with_extra_properties_and_elements() {
    let dir = folder("ply-binary");
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
        property double x\nproperty double y\nproperty double z\nproperty uchar red\n\
        element face 1\nproperty list uchar uint vertex_indices\n\
        element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
        .to_vec();
    for v in [[0.0f64, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]] {
        for c in v {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
        bytes.push(255);
    }
    bytes.push(3);
    for i in [0u32, 1, 2] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    for i in [0i32, 1] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let mesh = load(&write(&dir, "tri.ply", &bytes)).unwrap();
    assert_eq!(mesh.parts[0].vertices[1], Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(mesh.parts[0].triangles, vec![[0, 1, 2]]);

    // Cut off inside the face list: the element is named.
    let cut = write(&dir, "cut.ply", &bytes[..bytes.len() - 14]);
    let error = load(&cut).unwrap_err().to_string();
    assert!(error.contains("element `face`"), "{error}");
}

/// Each broken PLY gives its line (ASCII) or element, never a panic.
#[test]
fn a_broken_ply_names_the_line_or_element() {
    let dir = folder("ply-broken");
    let cases: [(String, &str); 6] = [
        ("plx\n".into(), ":1: "),
        (
            ply_header(3, 1) + "0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n",
            ":12: ",
        ),
        (
            ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
            ": face 0: ",
        ),
        (
            ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
            ": face 0: ",
        ),
        (
            ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            ": face 0: ",
        ),
        (
            ply_header(3, 2) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "element `face`",
        ),
    ];
    for (i, (text, place)) in cases.into_iter().enumerate() {
        let path = write(&dir, &format!("broken{i}.ply"), text.as_bytes());
        let error = load(&path).unwrap_err().to_string();
        assert!(error.contains(place), "{text:?}: {error}");
    }
    let no_faces = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n\
                    property float y\nproperty float z\nend_header\n0 0 0\n";
    let error = load(&write(&dir, "points.ply", no_faces.as_bytes())).unwrap_err();
    assert!(error.message.contains("no `face` element"), "{error}");
}

#[test]
fn a_bare_mesh_is_framed_whole_above_its_ground() {
    let dir = folder("framing");
    write(&dir, "cube.mtl", CUBE_MTL.as_bytes());
    let mut mesh = load(&write(&dir, "cube.obj", CUBE_OBJ.as_bytes())).unwrap();
    mesh.transform(10.0, Vec3::new(100.0, 5.0, 0.0));
    let scene = frame(mesh);
    let view = &scene.view;
    let centre = Vec3::new(105.0, 10.0, 5.0);
    assert!((view.at - centre).length() < 1e-4, "{}", view.at);
    // The whole bounding sphere (radius 5 sqrt 3) is inside the view cone.
    let radius = 5.0 * 3f32.sqrt();
    let distance = (view.from - view.at).length();
    let half_angle = (view.angle * 0.5).to_radians();
    assert!(radius / distance < half_angle.sin(), "{distance}");
    // Seen from above and in front.
    assert!(view.from.y > centre.y && view.from.z > centre.z);
    assert_eq!(scene.lights.len(), 2);
    assert!(
        scene
            .lights
            .iter()
            .all(|l| matches!(l, LightSpec::Point { position, .. } if position.y > centre.y))
    );
    // The ground plane touches the lowest point; the mesh keeps its MTL red.
    let Primitive::Plane { points } = &scene.objects[0].primitive else {
        panic!("the first object is the ground");
    };
    assert!(points.iter().all(|p| p.y == 5.0));
    let mesh_object = &scene.objects[1];
    assert_eq!(
        scene.materials[mesh_object.material as usize].diffuse,
        Vec3::new(0.9, 0.1, 0.1)
    );
    let world = World::build(&scene);
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    assert_eq!(world.counts.triangles, 12);
}

#[test]
fn a_mesh_without_mtl_gets_the_neutral_material() {
    let dir = folder("framing-grey");
    let text = ply_header(3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let scene = frame(load(&write(&dir, "tri.ply", text.as_bytes())).unwrap());
    let material = scene.objects[1].material as usize;
    assert_eq!(scene.materials[material], framing::neutral_material());
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Whatever lines an OBJ or PLY holds, reading it answers with a mesh
    /// or an error, never a panic.
    #[test]
    fn arbitrary_lines_never_panic(
        lines in proptest::collection::vec(
            proptest::prop_oneof![
                proptest::string::string_regex("(v|vn|vt|f|o|g|usemtl|mtllib) [-0-9/ .a-z]{0,24}").unwrap(),
                proptest::string::string_regex("(ply|format ascii 1.0|format binary_little_endian 1.0|end_header)").unwrap(),
                proptest::string::string_regex("(element (vertex|face) [0-9]{1,3}|property (float|uchar|int) [xyz]|property list uchar int vertex_indices)").unwrap(),
                proptest::string::string_regex("[-0-9 .]{0,20}").unwrap(),
            ],
            0..24,
        ),
        ply in proptest::bool::ANY,
    ) {
        let dir = folder("arbitrary");
        let name = if ply { "any.ply" } else { "any.obj" };
        let path = write(&dir, name, lines.join("\n").as_bytes());
        let _ = load(&path);
    }
}
