//! Primitives packed for the traversal's hot loop: spheres and flat
//! triangles (and patches) copied into 48-byte records, in leaf order, half the size of
//! the general [`Shape`] enum (whose cones make it 96 bytes), with the
//! world index inside, so a leaf's primitives are one short run of memory.
//! Every other shape stays a [`Shape`] in the world, reached through the
//! index. Intersections run the primitives' own routines on the copied
//! fields: same arithmetic, same bits as testing the [`Shape`].
//!
//! A leaf's spheres come first, four to a group of records laid out lane
//! by lane and tested four at once with SIMD (the `shells` scene's rays
//! test ~125 spheres each), then its triangles likewise, then one record
//! for each other primitive.

use glam::{BVec4A, Vec3A, Vec4};

use crate::geometry::{
    Aabb, Ray, Shape, Sphere, Triangle, V3, Vector, edges_bounds, intersect_edges,
    intersect_spheres, intersect_triangles,
};

use super::{LeafShape, Nearest, first_occluder, offer_each};

/// What a record holds, stored in `b.w` (see [`tag`]).
const SPHERE: u32 = 0;
const TRIANGLE: u32 = 1;
/// Any other shape: tested through the world's [`Shape`].
const OTHER: u32 = 2;
/// The first record of a group of up to four spheres ([`Spheres`]).
const SPHERES: u32 = 3;
/// The first record of a group of up to four triangles ([`Triangles`]).
const TRIANGLES: u32 = 4;

/// Primitives tested at once: the lanes of a `Vec4`.
pub(super) const LANES: usize = 4;

/// One primitive: a sphere is `a = (centre, radius)`; a triangle is
/// `a = (v0, parallel_eps)`, `b = e1`, `c = e2`; `b.w` is the kind and
/// `c.w` the index in the world's shapes, both as [`tag`]ged float bits.
///
/// The first record of a group is its header: `b` holds the group's size,
/// the spheres and the triangles grouped in its leaf, and the kind; `c` the
/// world indices, a lane each. The group's other records hold its
/// primitives' numbers lane by lane (see [`Group::pack`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub(super) struct PackedShape {
    a: Vec4,
    b: Vec4,
    c: Vec4,
}

impl PackedShape {
    /// A blank record, overwritten by [`pack_leaf`].
    pub(super) const BLANK: Self = Self {
        a: Vec4::ZERO,
        b: Vec4::ZERO,
        c: Vec4::ZERO,
    };

    /// The record of `shape`, which is shape `id` of the world.
    pub(super) fn new(shape: &Shape, id: u32) -> Self {
        let (a, b, c, kind) = match shape {
            Shape::Sphere(s) => (s.centre.extend(s.radius), Vec3A::ZERO, Vec3A::ZERO, SPHERE),
            // Patches intersect like flat triangles (their normals, in the
            // world's shape, only matter for shading): packed too.
            Shape::Triangle(t) => (t.v0.extend(t.parallel_eps()), t.e1, t.e2, TRIANGLE),
            _ => (Vec4::ZERO, Vec3A::ZERO, Vec3A::ZERO, OTHER),
        };
        Self {
            a,
            b: b.extend(tag(kind)),
            c: c.extend(tag(id)),
        }
    }

    /// A record of three numbers a lane, `f` of each of `prims`; NaN in
    /// lanes without a primitive, which no ray hits.
    fn lanes<T>(prims: &[(u32, &T)], f: impl Fn(&T) -> Vec3A) -> Self {
        let mut v = [Vec3A::NAN; LANES];
        for (lane, (_, p)) in v.iter_mut().zip(prims) {
            *lane = f(p);
        }
        Self {
            a: Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x),
            b: Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y),
            c: Vec4::new(v[0].z, v[1].z, v[2].z, v[3].z),
        }
    }

    /// The header of a group of `prims` of kind `kind` in a leaf grouping
    /// `grouped` spheres and triangles; `a` holds `scalar` of each.
    fn header<T>(
        prims: &[(u32, &T)],
        kind: u32,
        grouped: [usize; 2],
        scalar: impl Fn(&T) -> f32,
    ) -> Self {
        let (mut a, mut ids) = ([f32::NAN; LANES], [u32::MAX; LANES]);
        for ((a, id), &(prim_id, p)) in a.iter_mut().zip(&mut ids).zip(prims) {
            (*a, *id) = (scalar(p), prim_id);
        }
        let sizes = [prims.len(), grouped[0], grouped[1]].map(|n| f32::from_bits(n as u32));
        Self {
            a: Vec4::from_array(a),
            b: Vec4::from_array([sizes[0], sizes[1], sizes[2], tag(kind)]),
            c: Vec4::from_array(ids.map(f32::from_bits)),
        }
    }

    /// The record's bits, NaN lanes included, for comparing records.
    #[cfg(test)]
    pub(super) fn bits(&self) -> [u32; 12] {
        let [a, b, c] = [self.a, self.b, self.c].map(|v| v.to_array().map(f32::to_bits));
        std::array::from_fn(|i| [a, b, c][i / 4][i % 4])
    }

    /// The kind of record: [`SPHERE`], [`TRIANGLE`], [`OTHER`], or the
    /// header of a group, [`SPHERES`] or [`TRIANGLES`].
    #[inline(always)]
    fn kind(&self) -> u32 {
        untag(self.b.w)
    }

    /// The bounding box of a packed sphere or triangle, `None` for other
    /// shapes (whose data stays in the world), for validation.
    pub(super) fn bounds(&self) -> Option<Aabb> {
        let a = Vec3A::from_vec4(self.a);
        match self.kind() {
            SPHERE => Some(Sphere::new(a, self.a.w).bounds()),
            TRIANGLE => Some(edges_bounds(
                a,
                Vec3A::from_vec4(self.b),
                Vec3A::from_vec4(self.c),
            )),
            _ => None,
        }
    }
}

impl LeafShape for PackedShape {
    #[inline(always)]
    fn id(&self) -> u32 {
        untag(self.c.w)
    }

    /// The same as `shapes[self.id()].intersect(ray, t_min, t_max)`, bit
    /// for bit.
    #[inline(always)]
    fn intersect(&self, shapes: &[Shape], ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        match self.kind() {
            SPHERE => Sphere::new(Vec3A::from_vec4(self.a), self.a.w).intersect(ray, t_min, t_max),
            TRIANGLE => intersect_edges(
                Vec3A::from_vec4(self.a),
                Vec3A::from_vec4(self.b),
                Vec3A::from_vec4(self.c),
                self.a.w,
                ray,
                t_min,
                t_max,
            ),
            _ => shapes[self.id() as usize].intersect(ray, t_min, t_max),
        }
    }
}

/// Flipped in the bits of a kind or an index kept in a `w` lane.
const TAG: u32 = 1 << 30;

/// `n` as the bits of a float in a `w` lane beside three coordinates: `n`
/// with the exponent's top bit flipped, so that a small `n` is a normal
/// number (at least 2), not a subnormal one. Vector arithmetic on the three
/// coordinates computes the fourth lane too, and on x86 each subnormal
/// operand costs a microcode assist of some hundred cycles: with the raw
/// bits a lone triangle's test took most of the closest-hit time
/// (`docs/PERFORMANCE.md`). Masking the lane at each test does not help:
/// the compiler drops the mask from lanes whose result is not used.
#[inline(always)]
fn tag(n: u32) -> f32 {
    f32::from_bits(n ^ TAG)
}

/// The number [`tag`] stored.
#[inline(always)]
fn untag(lane: f32) -> u32 {
    lane.to_bits() ^ TAG
}

/// A kind of primitive a leaf tests four at once: how a group of them is
/// laid out in records and intersected.
trait Group {
    type Prim;
    /// Records a group takes up, its header included.
    const RECORDS: usize;
    /// Fewest of them in a leaf worth grouping.
    const MIN: usize;
    /// Emits the group's records for up to four `prims` (with their world
    /// indices) in a leaf grouping `grouped` spheres and triangles.
    fn pack(prims: &[(u32, &Self::Prim)], grouped: [usize; 2], emit: &mut dyn FnMut(PackedShape));
    /// The primitive `shape` is, if of this kind.
    fn of(shape: &Shape) -> Option<&Self::Prim>;
    /// The lanes of `group` the ray meets in `(t_min, t_max)` and where,
    /// `None` when no lane can be hit.
    fn intersect(group: &[PackedShape], ray: &RayLanes, t: [Vec4; 2]) -> Option<(BVec4A, Vec4)>;
}

/// Spheres, four to two records: radii in the header, then the centres'
/// x, y and z. A lone sphere keeps a record of its own: a group of one
/// costs more than the scalar test (measured on `balls_medium`, whose
/// leaves are all single spheres).
struct Spheres;

impl Group for Spheres {
    type Prim = Sphere;
    const RECORDS: usize = 2;
    const MIN: usize = 2;

    fn pack(spheres: &[(u32, &Sphere)], grouped: [usize; 2], emit: &mut dyn FnMut(PackedShape)) {
        emit(PackedShape::header(spheres, SPHERES, grouped, |s| s.radius));
        emit(PackedShape::lanes(spheres, |s| s.centre));
    }

    fn of(shape: &Shape) -> Option<&Sphere> {
        match shape {
            Shape::Sphere(s) => Some(s),
            _ => None,
        }
    }

    #[inline(always)]
    fn intersect(group: &[PackedShape], ray: &RayLanes, t: [Vec4; 2]) -> Option<(BVec4A, Vec4)> {
        let [t_min, t_max] = t;
        intersect_spheres(
            lanes(&group[1]),
            group[0].a,
            ray.origin,
            ray.dir,
            t_min,
            t_max,
        )
    }
}

/// Triangles, four to four records: `parallel_eps` in the header, then
/// `v0`, `e1` and `e2`. Only leaves of four or more are grouped: a group
/// of four pays (`mesh_large`, whose leaves all hold four triangles), a
/// half-full one does not (`mount_high`'s leaves of two: more
/// instructions, no faster).
struct Triangles;

impl Group for Triangles {
    type Prim = Triangle;
    const RECORDS: usize = 4;
    const MIN: usize = 4;

    fn pack(
        triangles: &[(u32, &Triangle)],
        grouped: [usize; 2],
        emit: &mut dyn FnMut(PackedShape),
    ) {
        emit(PackedShape::header(
            triangles,
            TRIANGLES,
            grouped,
            Triangle::parallel_eps,
        ));
        emit(PackedShape::lanes(triangles, |t| t.v0));
        emit(PackedShape::lanes(triangles, |t| t.e1));
        emit(PackedShape::lanes(triangles, |t| t.e2));
    }

    fn of(shape: &Shape) -> Option<&Triangle> {
        match shape {
            Shape::Triangle(t) => Some(t),
            _ => None,
        }
    }

    #[inline(always)]
    fn intersect(group: &[PackedShape], ray: &RayLanes, t: [Vec4; 2]) -> Option<(BVec4A, Vec4)> {
        let ([t_min, t_max], edges) = (t, [1, 2, 3].map(|i| lanes(&group[i])));
        intersect_triangles(edges, group[0].a, ray.origin, ray.dir, t_min, t_max)
    }
}

/// The lanes of a group of `G` the ray meets in `(t_min, t_max)`, a bit
/// each, and where.
#[inline(always)]
fn group_hits<G: Group>(
    group: &[PackedShape],
    ray: &RayLanes,
    t_min: f32,
    t_max: f32,
) -> (u32, Vec4) {
    match G::intersect(group, ray, [t_min, t_max].map(Vec4::splat)) {
        Some((hit, t)) => (hit.bitmask(), t),
        None => (0, Vec4::ZERO),
    }
}

/// A ray's origin and direction in all four lanes.
struct RayLanes {
    origin: V3<Vec4>,
    dir: V3<Vec4>,
}

impl RayLanes {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        Self {
            origin: V3::splat(ray.origin),
            dir: V3::splat(ray.dir),
        }
    }
}

/// A record's three numbers a lane as a vector a lane.
#[inline(always)]
fn lanes(record: &PackedShape) -> V3<Vec4> {
    V3 {
        x: record.a,
        y: record.b,
        z: record.c,
    }
}

/// The world index of the primitive in `lane` of a group.
#[inline(always)]
fn group_id(group: &[PackedShape], lane: u32) -> u32 {
    // An array, not `Vec4` indexing, which compiles to a jump table.
    group[0].c.to_array()[lane as usize].to_bits()
}

/// The primitives in a group: its lanes in use.
#[inline(always)]
fn group_size(group: &[PackedShape]) -> u64 {
    group[0].b.x.to_bits() as u64
}

/// The fewest triangles a leaf tests in groups (the BVH build's cost
/// model needs it).
pub(super) const MIN_GROUPED_TRIANGLES: usize = Triangles::MIN;

/// How many of a leaf's spheres and of its triangles go into groups: all
/// of a kind when the leaf has at least [`Group::MIN`] of them, else none.
fn grouping(shapes: &[Shape], ids: &[u32]) -> [usize; 2] {
    let count = |of: fn(&Shape) -> bool| ids.iter().filter(|&&id| of(&shapes[id as usize])).count();
    let spheres = count(|s| Spheres::of(s).is_some());
    let triangles = count(|s| Triangles::of(s).is_some());
    [
        if spheres >= Spheres::MIN { spheres } else { 0 },
        if triangles >= Triangles::MIN {
            triangles
        } else {
            0
        },
    ]
}

/// Set in a leaf's `first` when its records start with groups, so a leaf
/// without any is told without reading its first record: the scalar leaf
/// then costs what it did before groups (`balls_high`, whose leaves are
/// single spheres, spent a measurable share of its instructions reading it).
const GROUPED: usize = 1 << 31;

/// The records a leaf holding the shapes `ids` takes up, and whether it
/// has groups.
pub(super) fn leaf_len(shapes: &[Shape], ids: &[u32]) -> (usize, bool) {
    let [spheres, triangles] = grouping(shapes, ids);
    let len = ids.len() - spheres - triangles
        + Spheres::RECORDS * spheres.div_ceil(LANES)
        + Triangles::RECORDS * triangles.div_ceil(LANES);
    (len, spheres + triangles > 0)
}

/// A leaf slot's `first` for a leaf whose records start at `start`
/// ([`leaf_len`] says whether it is `grouped`).
pub(super) fn leaf_first(start: usize, grouped: bool) -> u32 {
    assert!(
        start < GROUPED,
        "more packed records than a leaf index holds"
    );
    (start | if grouped { GROUPED } else { 0 }) as u32
}

/// Where the records of the leaf whose slot says `first` start.
pub(super) fn leaf_start(first: usize) -> usize {
    first & !GROUPED
}

/// Writes the records of a leaf holding the shapes `ids` into `out`,
/// [`leaf_len`] long: its spheres first, then its triangles, each in
/// groups of four when grouped (see [`grouping`]), then one record per
/// other primitive.
pub(super) fn pack_leaf(shapes: &[Shape], ids: &[u32], out: &mut [PackedShape]) {
    let grouped = grouping(shapes, ids);
    let mut slots = out.iter_mut();
    let mut emit = |record| *slots.next().expect("leaf_len records") = record;
    if grouped[0] > 0 {
        pack_groups::<Spheres>(shapes, ids, grouped, &mut emit);
    }
    if grouped[1] > 0 {
        pack_groups::<Triangles>(shapes, ids, grouped, &mut emit);
    }
    for &id in ids {
        let shape = &shapes[id as usize];
        let in_group = (grouped[0] > 0 && Spheres::of(shape).is_some())
            || (grouped[1] > 0 && Triangles::of(shape).is_some());
        if !in_group {
            emit(PackedShape::new(shape, id));
        }
    }
}

/// Emits the groups of four of the leaf's primitives of kind `G`, in leaf
/// order.
fn pack_groups<G: Group>(
    shapes: &[Shape],
    ids: &[u32],
    grouped: [usize; 2],
    emit: &mut dyn FnMut(PackedShape),
) {
    let mut prims = ids
        .iter()
        .filter_map(|&id| Some((id, G::of(&shapes[id as usize])?)));
    while let Some(first) = prims.next() {
        let mut group = [first; LANES];
        let mut n = 1;
        while n < LANES {
            let Some(prim) = prims.next() else { break };
            group[n] = prim;
            n += 1;
        }
        G::pack(&group[..n], grouped, emit);
    }
}

/// Appends the world indices of the leaf of `count` primitives whose
/// slot says `first` to `ids`, in the order of its records (spheres, then
/// triangles, then the rest: [`pack_leaf`] packs them back in the same
/// order), and returns how many records it takes up; `None` when they run
/// past the end of `prims`.
pub(super) fn leaf_ids(
    prims: &[PackedShape],
    first: usize,
    count: usize,
    ids: &mut Vec<u32>,
) -> Option<usize> {
    let leaf = Leaf::at(prims, first, count)?;
    let mut groups = |records: &[PackedShape], size: usize| {
        for group in records.chunks_exact(size) {
            let lanes = group_size(group) as u32;
            ids.extend((0..lanes).map(|lane| group_id(group, lane)));
        }
    };
    groups(leaf.spheres, Spheres::RECORDS);
    groups(leaf.triangles, Triangles::RECORDS);
    ids.extend(leaf.records.iter().map(LeafShape::id));
    Some(leaf.len())
}

/// Whether the slot of a leaf says its records start with groups.
pub(super) fn leaf_grouped(first: usize) -> bool {
    first & GROUPED != 0
}

/// A leaf's records as its loops read them.
struct Leaf<'a> {
    /// [`Spheres::RECORDS`] records per group of spheres.
    spheres: &'a [PackedShape],
    /// [`Triangles::RECORDS`] records per group of triangles.
    triangles: &'a [PackedShape],
    /// The primitives in the groups (lanes in use).
    grouped: usize,
    /// One record per other primitive.
    records: &'a [PackedShape],
}

impl<'a> Leaf<'a> {
    /// The leaf of `count` primitives whose slot says `first`, or `None`
    /// if it runs past the end of `prims`.
    #[inline(always)]
    fn at(prims: &'a [PackedShape], first: usize, count: usize) -> Option<Self> {
        if first & GROUPED == 0 {
            return Some(Leaf {
                spheres: &[],
                triangles: &[],
                grouped: 0,
                records: prims.get(first..first + count)?,
            });
        }
        let run = prims.get(leaf_start(first)..)?;
        let head = run.first()?;
        let [spheres, triangles] = [head.b.y, head.b.z].map(|n| n.to_bits() as usize);
        let (sphere_groups, run) =
            run.split_at_checked(Spheres::RECORDS * spheres.div_ceil(LANES))?;
        let (triangle_groups, run) =
            run.split_at_checked(Triangles::RECORDS * triangles.div_ceil(LANES))?;
        let grouped = spheres + triangles;
        Some(Leaf {
            spheres: sphere_groups,
            triangles: triangle_groups,
            grouped,
            records: run.get(..count.checked_sub(grouped)?)?,
        })
    }

    /// The records the leaf takes up.
    fn len(&self) -> usize {
        self.spheres.len() + self.triangles.len() + self.records.len()
    }
}

/// The BVH's leaf loop for closest hits ([`offer_each`] for a packed
/// leaf): offers each primitive of the leaf of `count` primitives at
/// `first` that the ray meets to `nearest`, four spheres or triangles at
/// a time, adding one to `tests` per primitive tested (not per group, and
/// not for unused lanes). The lanes of a group are all tested with the
/// limit the group starts with; a lane's hit beyond a nearer lane's is
/// then refused by [`Nearest::offer`], so the nearest hit, ties included,
/// is the one testing them one by one finds.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn offer_leaf(
    prims: &[PackedShape],
    first: usize,
    count: usize,
    shapes: &[Shape],
    ray: &Ray,
    t_min: f32,
    nearest: &mut Nearest,
    tests: &mut u64,
) {
    let leaf = Leaf::at(prims, first, count).expect("a leaf's records are in the tree");
    if leaf.grouped > 0 {
        *tests += leaf.grouped as u64;
        offer_groups::<Spheres>(leaf.spheres, ray, t_min, nearest);
        offer_groups::<Triangles>(leaf.triangles, ray, t_min, nearest);
    }
    offer_each(leaf.records, shapes, ray, t_min, nearest, tests);
}

/// The BVH's leaf loop for any hit ([`first_occluder`] for a packed leaf):
/// the first primitive found on the ray in `(t_min, t_max)`, four spheres
/// or triangles at a time. A group's primitives are tested at once, so all
/// count as tested, even past the one that is hit.
///
/// Out of line: inlined, it left the 8-wide any-hit traversal too few
/// registers, which then kept the ray and its stack's length in memory
/// (shadow rays are faster out of line on mount_high and sombrero).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn leaf_occluder(
    prims: &[PackedShape],
    first: usize,
    count: usize,
    shapes: &[Shape],
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    tests: &mut u64,
) -> Option<u32> {
    let leaf = Leaf::at(prims, first, count).expect("a leaf's records are in the tree");
    if leaf.grouped > 0 {
        let found = groups_occluder::<Spheres>(leaf.spheres, ray, t_min, t_max, tests)
            .or_else(|| groups_occluder::<Triangles>(leaf.triangles, ray, t_min, t_max, tests));
        if found.is_some() {
            return found;
        }
    }
    first_occluder(leaf.records, shapes, ray, t_min, t_max, tests)
}

/// Offers the primitives of `groups` the ray meets to `nearest`, four at
/// a time. Out of line: inlined, the compiler splats the ray's coordinates
/// into lanes on every traversal, groups or not.
#[inline(never)]
fn offer_groups<G: Group>(groups: &[PackedShape], ray: &Ray, t_min: f32, nearest: &mut Nearest) {
    if groups.is_empty() {
        return;
    }
    let lanes = RayLanes::new(ray);
    for group in groups.chunks_exact(G::RECORDS) {
        let (mut hits, t) = group_hits::<G>(group, &lanes, t_min, nearest.limit);
        let t = t.to_array();
        while hits != 0 {
            let lane = hits.trailing_zeros();
            hits &= hits - 1;
            nearest.offer(t[lane as usize], group_id(group, lane));
        }
    }
}

/// The first primitive of `groups` found on the ray in `(t_min, t_max)`,
/// adding to `tests` the primitives of each group tested; out of line like
/// [`offer_groups`].
#[inline(never)]
fn groups_occluder<G: Group>(
    groups: &[PackedShape],
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    tests: &mut u64,
) -> Option<u32> {
    if groups.is_empty() {
        return None;
    }
    let lanes = RayLanes::new(ray);
    for group in groups.chunks_exact(G::RECORDS) {
        *tests += group_size(group);
        let (hits, _) = group_hits::<G>(group, &lanes, t_min, t_max);
        if hits != 0 {
            return Some(group_id(group, hits.trailing_zeros()));
        }
    }
    None
}

/// The records the leaf of `count` primitives at `first` takes up and the
/// bounding box of each of its primitives (`None` for shapes whose data
/// stays in the world), or `None` if the leaf runs past the end of
/// `prims`: for validation.
pub(super) fn leaf_bounds(
    prims: &[PackedShape],
    first: usize,
    count: usize,
) -> Option<(usize, Vec<Option<Aabb>>)> {
    let leaf = Leaf::at(prims, first, count)?;
    let mut bounds = Vec::with_capacity(count);
    let lane = |record: &PackedShape, i: usize| {
        let [x, y, z] = [record.a, record.b, record.c].map(|v| v.to_array()[i]);
        Vec3A::new(x, y, z)
    };
    for group in leaf.spheres.chunks_exact(Spheres::RECORDS) {
        bounds.extend(
            (0..group_size(group) as usize)
                .map(|i| Some(Sphere::new(lane(&group[1], i), group[0].a.to_array()[i]).bounds())),
        );
    }
    for group in leaf.triangles.chunks_exact(Triangles::RECORDS) {
        bounds.extend((0..group_size(group) as usize).map(|i| {
            let [v0, e1, e2] = [1, 2, 3].map(|r| lane(&group[r], i));
            Some(edges_bounds(v0, e1, e2))
        }));
    }
    bounds.extend(leaf.records.iter().map(PackedShape::bounds));
    Some((leaf.len(), bounds))
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;
    use proptest::prelude::*;

    use super::*;
    use crate::geometry::strategies::{config, unit_vector};
    use crate::geometry::{AaBox, Triangle};

    /// One primitive of a test leaf: a sphere (`kind` 0 and 1, so spheres
    /// dominate), a triangle (2) or a box (3), around `centre`; `copy`
    /// repeats the previous shape instead, so rays meet some at exactly
    /// the same distance.
    fn shape(kind: u8, centre: Vec3A, size: f32, copy: bool, previous: Option<&Shape>) -> Shape {
        if let (true, Some(p)) = (copy, previous) {
            return p.clone();
        }
        let corner = centre + Vec3A::splat(size);
        match kind {
            0 | 1 => Shape::Sphere(Sphere::new(centre, size)),
            2 => Triangle::new(centre, corner, centre + Vec3A::new(size, -size, 0.5))
                .map_or(Shape::Sphere(Sphere::new(centre, size)), Shape::Triangle),
            _ => Shape::Box(AaBox::new(centre, corner)),
        }
    }

    fn leaf_shapes() -> impl Strategy<Value = Vec<Shape>> {
        let part = (
            0u8..4,
            (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0),
            0.1f32..1.5,
            0u8..4,
        );
        prop::collection::vec(part, 1..24).prop_map(|parts| {
            let mut shapes: Vec<Shape> = Vec::new();
            for (kind, (x, y, z), size, copy) in parts {
                let s = shape(kind, Vec3A::new(x, y, z), size, copy == 0, shapes.last());
                shapes.push(s);
            }
            shapes
        })
    }

    /// The leaf's records and its slot's `first`.
    fn packed(shapes: &[Shape]) -> (Vec<PackedShape>, usize) {
        let ids: Vec<u32> = (0..shapes.len() as u32).collect();
        let (len, grouped) = leaf_len(shapes, &ids);
        let mut prims = vec![PackedShape::BLANK; len];
        pack_leaf(shapes, &ids, &mut prims);
        (prims, leaf_first(0, grouped) as usize)
    }

    proptest! {
        #![proptest_config(config())]

        /// The packed leaf (spheres four at a time) finds, bit for bit, the
        /// hit testing every shape of the world one by one finds, ties to
        /// the lowest index included, counting one test per primitive; and
        /// an occluder exactly when there is one, really on the ray.
        #[test]
        fn packed_leaves_find_what_the_shapes_one_by_one_find(
            shapes in leaf_shapes(),
            origin in (-6.0f32..6.0, -6.0f32..6.0, -6.0f32..6.0),
            dir in unit_vector(),
            t_min in prop_oneof![Just(0.0f32), 0.0f32..4.0],
        ) {
            let (prims, first) = packed(&shapes);
            let ids: Vec<u32> = (0..shapes.len() as u32).collect();
            let ray = Ray::new(Vec3A::new(origin.0, origin.1, origin.2), dir);
            let (mut packed_best, mut one_by_one) = (Nearest::new(f32::INFINITY), Nearest::new(f32::INFINITY));
            let (mut packed_tests, mut scalar_tests) = (0, 0);
            offer_leaf(&prims, first, shapes.len(), &shapes, &ray, t_min, &mut packed_best, &mut packed_tests);
            offer_each(&ids, &shapes, &ray, t_min, &mut one_by_one, &mut scalar_tests);
            let bits = |n: &Nearest| n.best.map(|h| (h.t.to_bits(), h.shape));
            prop_assert_eq!(bits(&packed_best), bits(&one_by_one));
            prop_assert_eq!(packed_tests, shapes.len() as u64);

            let t_max = one_by_one.best.map_or(8.0, |h| h.t + 0.5);
            let mut tests = 0;
            let found = leaf_occluder(&prims, first, shapes.len(), &shapes, &ray, t_min, t_max, &mut tests);
            let expected = first_occluder(&ids, &shapes, &ray, t_min, t_max, &mut 0);
            prop_assert_eq!(found.is_some(), expected.is_some());
            if let Some(id) = found {
                prop_assert!(shapes[id as usize].intersect(&ray, t_min, t_max).is_some());
            } else {
                prop_assert_eq!(tests, shapes.len() as u64);
            }
            prop_assert!(tests <= shapes.len() as u64);
        }
    }

    #[test]
    fn spheres_come_first_in_groups_of_four_and_a_lone_sphere_keeps_its_record() {
        let sphere = |x: f32| Shape::Sphere(Sphere::new(Vec3A::new(x, 0.0, 0.0), 0.5));
        let tri = Shape::Triangle(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y).unwrap());
        // Five spheres and a triangle: two groups (the second one sphere and
        // three empty lanes), then the triangle's record.
        let shapes = [
            sphere(0.0),
            tri.clone(),
            sphere(1.0),
            sphere(2.0),
            sphere(3.0),
            sphere(4.0),
        ];
        let (prims, first) = packed(&shapes);
        assert_eq!(prims.len(), 2 + 2 + 1);
        let (records, bounds) = leaf_bounds(&prims, first, shapes.len()).unwrap();
        assert_eq!(records, prims.len());
        let expected: Vec<_> = [0, 2, 3, 4, 5, 1].map(|i| shapes[i].bounds()).into();
        assert_eq!(bounds, expected);
        // A ray along x meets all five spheres: the nearest is sphere 0,
        // five spheres and one triangle are counted, not the empty lanes.
        let ray = Ray::new(Vec3A::new(-5.0, 0.0, 0.0), Vec3A::X);
        let mut nearest = Nearest::new(f32::INFINITY);
        let mut tests = 0;
        offer_leaf(
            &prims,
            first,
            shapes.len(),
            &shapes,
            &ray,
            0.0,
            &mut nearest,
            &mut tests,
        );
        assert_eq!(nearest.best.map(|h| (h.t, h.shape)), Some((4.5, 0)));
        assert_eq!(tests, 6);

        let (lone, first) = packed(&[tri.clone(), sphere(0.0)]);
        assert_eq!(first, 0, "no groups");
        assert_eq!(lone.len(), 2);
        assert_eq!(lone[1].kind(), SPHERE);

        // Four triangles make a group of four records, before the sphere's.
        let four = [tri.clone(), tri.clone(), sphere(0.0), tri.clone(), tri];
        let (prims, first) = packed(&four);
        assert_eq!(leaf_start(first), 0);
        assert_eq!(prims[0].kind(), TRIANGLES);
        assert_eq!(prims.len(), 4 + 1);
        assert_eq!(prims[4].kind(), SPHERE);
        let (records, bounds) = leaf_bounds(&prims, first, four.len()).unwrap();
        assert_eq!(records, 5);
        assert_eq!(bounds[0], four[0].bounds());
    }
}
