//! The Sierpinski tetrahedron (SPD `tetra.c`): a tetrahedron on alternate
//! corners of the cube [-1, 1]^3 replaced, `level` times, by the four
//! half-size tetrahedra at its corners. Mostly empty space, so it tests how
//! well an acceleration structure copes with holes.

use std::collections::HashMap;
use std::ops::RangeInclusive;

use glam::{UVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = subdivision steps; 4^level tetrahedra (level 8: 262,144 triangles).
pub(super) const LEVELS: RangeInclusive<u32> = 0..=8;

pub(super) fn tetrahedron_count(level: u32) -> u64 {
    4u64.pow(level)
}

pub(super) fn describe(level: u32) -> String {
    let n = tetrahedron_count(level);
    format!(
        "Sierpinski tetrahedron of {n} tetrahedra ({} triangles in one mesh), 2 lights",
        4 * n
    )
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(3.4, -2.5, 1.9), Vec3::ZERO);
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(4.0, -10.0, 8.0));
    b.light(Vec3::new(-6.0, -4.0, 3.0));
    b.material(material(
        Vec3::new(1.0, 0.2, 0.2),
        1.0,
        0.0,
        100.0,
        0.0,
        1.0,
    ));
    b.add(mesh(level));
    b.finish()
}

/// Corners live on an integer lattice of 2^level cells per cube edge, so
/// midpoints are exact and shared corners merge by value.
fn mesh(level: u32) -> Primitive {
    let n = 1u32 << level;
    let mut tetras = vec![[
        UVec3::new(n, n, n),
        UVec3::new(0, 0, n),
        UVec3::new(0, n, 0),
        UVec3::new(n, 0, 0),
    ]];
    for _ in 0..level {
        tetras = tetras
            .iter()
            .flat_map(|t| (0..4).map(move |k| t.map(|v| (v + t[k]) / 2)))
            .collect();
    }
    let mut index = HashMap::with_capacity(2 * tetras.len() + 2);
    let mut vertices = Vec::with_capacity(2 * tetras.len() + 2);
    let mut triangles = Vec::with_capacity(4 * tetras.len());
    let scale = 2.0 / n as f32;
    for t in &tetras {
        let ids = t.map(|v| {
            *index.entry(v).or_insert_with(|| {
                vertices.push(v.as_vec3() * scale - Vec3::ONE);
                (vertices.len() - 1) as u32
            })
        });
        // Wind each face so its normal points away from the fourth corner.
        let [a, b, c, d] = t.map(|v| v.as_i64vec3());
        let outward = (b - a).cross(c - a).dot(d - a) < 0;
        let faces = if outward {
            [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
        } else {
            [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
        };
        triangles.extend(faces.map(|f| f.map(|k| ids[k])));
    }
    Primitive::Mesh {
        vertices,
        triangles,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    fn parts(scene: &Scene) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        match &scene.objects[0].primitive {
            Primitive::Mesh {
                vertices,
                triangles,
            } => (vertices.clone(), triangles.clone()),
            other => panic!("not a mesh: {other:?}"),
        }
    }

    #[test]
    fn counts_per_level() {
        for level in 0..=6 {
            let scene = generate(level);
            assert_eq!(counts(&scene).3 as u64, 4 * tetrahedron_count(level));
            let (v, t) = parts(&scene);
            // Corners shared by touching tetrahedra are merged: 2 * 4^n + 2.
            assert_eq!(
                v.len() as u64,
                2 * tetrahedron_count(level) + 2,
                "level {level}"
            );
            assert!(t.iter().flatten().all(|&i| (i as usize) < v.len()));
        }
        assert_eq!(4 * tetrahedron_count(6), 16384);
    }

    #[test]
    fn fits_the_cube_and_faces_point_outwards() {
        let (v, t) = parts(&generate(3));
        assert!(v.iter().all(|p| p.abs().max_element() <= 1.0));
        for chunk in t.chunks(4) {
            let centroid: Vec3 =
                chunk.iter().flatten().map(|&i| v[i as usize]).sum::<Vec3>() / 12.0;
            for f in chunk {
                let [a, b, c] = f.map(|i| v[i as usize]);
                assert!((b - a).cross(c - a).dot(a - centroid) > 0.0);
            }
        }
    }
}
