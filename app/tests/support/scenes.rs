//! The small scenes the end-to-end tests render: written out in full, so a
//! failing test shows what it rendered.

/// A red sphere at the origin resting on a grey box top (z = 0), one
/// light, the blue sky behind: two primitives, 48 x 32 pixels. The
/// top-left pixel sees the sky; pixel (24, 11) the sphere; (40, 30) the lit
/// floor in front of it and (20, 19) its shadow behind it.
pub const RED_SPHERE_ON_A_BOX: &str = "\
bclr 0.1 0.2 0.4
v from 0 -6 2 at 0 0 0.5 up 0 0 1 angle 40 hither 0.01 resolution 48 32
l 3 -3 6 1 1 1
f 0.6 0.6 0.6 1 1 1 1 0 10 0 1
box -5 -5 -0.2 5 5 0
f 0.9 0.1 0.1 0.8 1 1 1 0.3 40 0 1
s 0 0 1 1
";

/// A matte red sphere and a glass one (T 0.8, ior 1.5) on a mirroring
/// floor under a point light, `width` x `height` pixels, with `view` added
/// to the camera block (`aperture 3`, say) and `extra` after the objects:
/// every kind of ray in a few milliseconds.
pub fn spheres_on_a_floor(width: u32, height: u32, view: &str, extra: &str) -> String {
    format!(
        "\
bclr 0.2 0.3 0.5
v
from 0 -7 2.5
at 0 0 0.8
up 0 0 1
angle 40
hither 0.01
resolution {width} {height}
{view}
l 4 -3 6 1 1 1
f 0.7 0.7 0.7 1 1 1 1 0.1 10 0 1
p 4
-6 -6 0  6 -6 0  6 6 0  -6 6 0
f 0.9 0.2 0.1 0.8 1 1 1 0.3 40 0 1
s -1 1 1 1
f 1 1 1 0.1 1 1 1 0.2 100 0.8 1.5
s 1.2 -1 0.8 0.8
{extra}
"
    )
}
