//! Commands that declare geometry: `s pl p pp c box mesh`. Each checks what
//! would make its primitive degenerate and counts before reserving memory.

use super::Parser;
use crate::scene::lexer::Pos;
use crate::scene::{ParseError, Primitive, rules};

impl Parser<'_, '_> {
    /// `s cx cy cz r`; a negative radius means only the inside is visible.
    pub(super) fn sphere(&mut self, pos: Pos) -> Result<(), ParseError> {
        let centre = self.cursor.vec3("the sphere centre")?;
        let radius_pos = self.cursor.here();
        let radius = self.cursor.number("the sphere radius")?;
        self.rule(radius_pos, rules::sphere_radius(radius))?;
        let sphere = Primitive::Sphere {
            centre,
            radius: radius.abs(),
            inside_only: radius < 0.0,
        };
        self.push_object(sphere, pos)
    }

    /// `pl` and three points that must not be collinear.
    pub(super) fn plane(&mut self, pos: Pos) -> Result<(), ParseError> {
        let points = [
            self.cursor.vec3("a plane point")?,
            self.cursor.vec3("a plane point")?,
            self.cursor.vec3("a plane point")?,
        ];
        self.rule(pos, rules::plane(&points))?;
        self.push_object(Primitive::Plane { points }, pos)
    }

    /// `p n` and n >= 3 vertices. Concave polygons are fine; their
    /// triangulation is the geometry's business.
    pub(super) fn polygon(&mut self, pos: Pos) -> Result<(), ParseError> {
        let (count, count_pos) = self.polygon_count("the polygon vertex count")?;
        self.cursor
            .ensure_input("polygon vertex count", count, 3, count_pos)?;
        let mut vertices = Vec::with_capacity(count);
        for _ in 0..count {
            vertices.push(self.cursor.vec3("a polygon vertex")?);
        }
        self.push_object(Primitive::Polygon { vertices }, pos)
    }

    /// `pp n` and n times `x y z nx ny nz`.
    pub(super) fn patch(&mut self, pos: Pos) -> Result<(), ParseError> {
        let (count, count_pos) = self.polygon_count("the patch vertex count")?;
        self.cursor
            .ensure_input("patch vertex count", count, 6, count_pos)?;
        let mut vertices = Vec::with_capacity(count);
        let mut normals = Vec::with_capacity(count);
        for _ in 0..count {
            vertices.push(self.cursor.vec3("a patch vertex")?);
            normals.push(self.cursor.vec3("a patch vertex normal")?);
        }
        self.push_object(Primitive::Patch { vertices, normals }, pos)
    }

    fn polygon_count(&mut self, expected: &'static str) -> Result<(usize, Pos), ParseError> {
        let (count, pos) = self
            .cursor
            .count(expected, self.limits.max_polygon_vertices)?;
        if count < 3 {
            let what = expected.strip_prefix("the ").unwrap_or(expected);
            let why = format!("a polygon needs at least 3 vertices, found {count}");
            return Err(self.invalid(pos, what, why));
        }
        Ok((count, pos))
    }

    /// `c bx by bz br ax ay az ar`: an open cone. Both radii negative means
    /// inside-only in NFF; the absolute values are kept and the flag
    /// dropped, as [`Primitive::Cone`] has no use for it.
    pub(super) fn cone(&mut self, pos: Pos) -> Result<(), ParseError> {
        let base = self.cursor.vec3("the cone base centre")?;
        let base_pos = self.cursor.here();
        let base_radius = self.cursor.number("the cone base radius")?;
        let apex = self.cursor.vec3("the cone apex centre")?;
        let apex_pos = self.cursor.here();
        let apex_radius = self.cursor.number("the cone apex radius")?;
        // A lone negative radius is reported at itself, both zero at the
        // apex's.
        let radii_pos = if base_radius < 0.0 && apex_radius >= 0.0 {
            base_pos
        } else {
            apex_pos
        };
        self.rule(radii_pos, rules::cone_radii(base_radius, apex_radius))?;
        self.rule(pos, rules::cone_axis(base, apex))?;
        let cone = Primitive::Cone {
            base,
            base_radius: base_radius.abs(),
            apex,
            apex_radius: apex_radius.abs(),
        };
        self.push_object(cone, pos)
    }

    /// `box minx miny minz maxx maxy maxz`. The corners may come in any
    /// order (the component-wise min and max are taken); a box flat along
    /// any axis is an error.
    pub(super) fn aabox(&mut self, pos: Pos) -> Result<(), ParseError> {
        let a = self.cursor.vec3("the box minimum corner")?;
        let b = self.cursor.vec3("the box maximum corner")?;
        let (min, max) = (a.min(b), a.max(b));
        self.rule(pos, rules::aabox(min, max))?;
        self.push_object(Primitive::Box { min, max }, pos)
    }

    /// `mesh nv nt`, nv vertices, nt index triples: 1-based, or negative to
    /// count back from the last vertex (-1 = last). Stored zero-based.
    pub(super) fn mesh(&mut self, pos: Pos) -> Result<(), ParseError> {
        let limits = self.limits;
        let (vertex_count, nv_pos) = self
            .cursor
            .count("the mesh vertex count", limits.max_mesh_vertices)?;
        let (triangle_count, nt_pos) = self
            .cursor
            .count("the mesh triangle count", limits.max_mesh_triangles)?;
        if vertex_count < 3 {
            let why = format!("a mesh needs at least 3 vertices, found {vertex_count}");
            return Err(self.invalid(nv_pos, "mesh vertex count", why));
        }
        if triangle_count == 0 {
            return Err(self.invalid(nt_pos, "mesh triangle count", "a mesh needs a triangle"));
        }
        self.check_primitives(triangle_count, nt_pos)?;
        self.cursor
            .ensure_input("mesh vertex count", vertex_count, 3, nv_pos)?;
        let mut vertices = Vec::with_capacity(vertex_count);
        for _ in 0..vertex_count {
            vertices.push(self.cursor.vec3("a mesh vertex")?);
        }
        self.cursor
            .ensure_input("mesh triangle count", triangle_count, 3, nt_pos)?;
        let mut triangles = Vec::with_capacity(triangle_count);
        for _ in 0..triangle_count {
            triangles.push([
                self.mesh_index(vertex_count)?,
                self.mesh_index(vertex_count)?,
                self.mesh_index(vertex_count)?,
            ]);
        }
        self.push_object(
            Primitive::Mesh {
                vertices,
                triangles,
            },
            pos,
        )
    }

    /// One index, resolved to zero-based and range-checked.
    fn mesh_index(&mut self, vertex_count: usize) -> Result<u32, ParseError> {
        let (index, token) = self.cursor.integer("a mesh vertex index")?;
        let count = i128::try_from(vertex_count).unwrap_or(i128::MAX);
        let zero_based = match index {
            _ if index > 0 && index <= count => index - 1,
            _ if index < 0 && -index <= count => count + index,
            _ => {
                let why = if index == 0 {
                    "indices start at 1 (or -1 for the last vertex), found 0".to_string()
                } else {
                    format!("{} is out of range for {count} vertices", token.text)
                };
                return Err(self.invalid(token.pos, "mesh index", why));
            }
        };
        u32::try_from(zero_based)
            .map_err(|_| self.invalid(token.pos, "mesh index", "does not fit in 32 bits"))
    }
}
