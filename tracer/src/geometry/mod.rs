//! Ray-primitive geometry: one file per primitive, a closed [`Shape`] enum
//! that dispatches between them without virtual calls in the hot loop.

mod aabb;
mod aabox;
mod cone;
mod lanes;
mod plane;
mod polygon;
mod ray;
mod shape;
mod sphere;
mod triangle;

pub use aabb::Aabb;
pub use aabox::AaBox;
pub use cone::Cone;
pub(crate) use lanes::{V3, Vector};
pub use plane::Plane;
pub(crate) use polygon::triangulate_polygon;
pub use ray::Ray;
#[cfg(test)]
pub(crate) use ray::strategies;
pub use shape::{Shape, SurfaceNormal};
pub use sphere::Sphere;
pub(crate) use sphere::intersect_spheres;
pub use triangle::Triangle;
pub(crate) use triangle::{edges_bounds, intersect_edges, intersect_triangles};
