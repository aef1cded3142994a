//! Depth of field in the image, against the thin-lens model of
//! `camera.rs`: the focal plane stays as sharp as a pinhole's, and a square
//! off it spreads by a circle of confusion of diameter `A |1 / F - d / z|`
//! pixels (aperture A in pixels, focal ratio F, view distance d, depth z).

use glam::{Vec2, Vec3A};

use super::{index, world};
use crate::accel::AccelKind;
use crate::render::{Encoding, Film, LensOverride, RenderSettings, render};
use crate::scene::Lens;

/// The camera of every scene here: 10 units above the origin looking down
/// -z, 64 x 64 pixels, 30 degrees between the top and bottom row centres.
const CAMERA: &str = "v from 0 0 10 at 0 0 0 up 0 1 0 angle 30 hither 0 resolution 64 64\n";
const SIDE: u32 = 64;
const VIEW_DISTANCE: f32 = 10.0;

/// World size of a pixel at the view distance.
fn pixel_size() -> f32 {
    2.0 * VIEW_DISTANCE * 15f32.to_radians().tan() / (SIDE - 1) as f32
}

fn lit_by_ambient(lens: Option<(f32, f32)>, n: u32) -> RenderSettings {
    RenderSettings {
        width: SIDE,
        height: SIDE,
        ambient: 1.0,
        depth_of_field: lens.is_some(),
        lens_override: lens.map_or_else(LensOverride::default, |(aperture, focal)| {
            LensOverride::all(Lens { aperture, focal })
        }),
        samples: n,
        ..RenderSettings::default()
    }
}

fn film(text: &str, settings: RenderSettings) -> Film {
    let w = world(text);
    render(w.clone(), index(&w, AccelKind::Bvh), settings, Some(2))
        .unwrap()
        .0
}

/// A 12 x 12 checkerboard of half-unit squares on the plane z = 0, blue and
/// white, lit by ambient light alone: every pixel is the colour of the
/// square its rays meet. The board is shifted off the pixel grid: a ray
/// exactly on the diagonal that splits a square into two triangles can
/// miss both (the triangle test is not watertight), and without the
/// shift the pixel centres on the image diagonal lie on those lines.
fn checkerboard() -> String {
    let mut text = format!("bclr 0 0 0\n{CAMERA}");
    for i in -6..6 {
        for j in -6..6 {
            let colour = if (i + j) % 2 == 0 {
                "1 1 1"
            } else {
                "0.2 0.4 0.9"
            };
            let (x, y) = (i as f32 * 0.5 + 0.0123, j as f32 * 0.5 + 0.0371);
            let (x1, y1) = (x + 0.5, y + 0.5);
            text.push_str(&format!(
                "f {colour} 1 0 0 0 0 1 0 1\np 4 {x} {y} 0 {x1} {y} 0 {x1} {y1} 0 {x} {y1} 0\n"
            ));
        }
    }
    text
}

/// The largest channel difference between two renders, in 8-bit levels.
fn max_levels(a: &Film, b: &Film) -> u8 {
    let (a, b) = (a.to_image(Encoding::Linear), b.to_image(Encoding::Linear));
    a.pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c])))
        .max()
        .unwrap_or(0)
}

#[test]
fn the_focal_plane_is_as_sharp_as_a_pinhole_image() {
    let text = checkerboard();
    let pinhole = film(&text, lit_by_ambient(None, 4));
    // Focal ratio 1: the plane z = 0 is the focal plane. Every lens ray of
    // a pixel meets the others there, so it sees the same square.
    let focused = film(&text, lit_by_ambient(Some((30.0, 1.0)), 4));
    let levels = max_levels(&pinhole, &focused);
    assert!(levels <= 1, "in focus, a pixel is {levels} levels off");
    // The same lens focused a fifth further blurs the squares' edges.
    let blurred = film(&text, lit_by_ambient(Some((30.0, 1.2)), 4));
    let levels = max_levels(&pinhole, &blurred);
    assert!(levels > 64, "out of focus, only {levels} levels off");
}

/// A white square of half-side `half` pixels (as the pinhole sees it) at
/// depth `depth`, facing the camera on its axis, on black.
fn square_at(depth: f32, half: f32) -> String {
    let a = half * pixel_size() * depth / VIEW_DISTANCE;
    let z = VIEW_DISTANCE - depth;
    format!(
        "bclr 0 0 0\n{CAMERA}f 1 1 1 1 0 0 0 0 1 0 1\n\
         p 4 {} {} {z} {a} {} {z} {a} {a} {z} {} {a} {z}\n",
        -a, -a, -a, -a
    )
}

/// The mean squared distance of the image's light from the image centre,
/// in pixels squared: the pixel values weight their centres.
fn second_moment(film: &Film) -> f64 {
    let centre = Vec2::splat(SIDE as f32 / 2.0);
    let (mut weight, mut moment) = (0.0f64, 0.0f64);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let v = f64::from(film.pixel(x, y).unwrap().dot(Vec3A::ONE) / 3.0);
            let r = (Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - centre).length_squared();
            weight += v;
            moment += v * f64::from(r);
        }
    }
    moment / weight
}

#[test]
fn a_square_off_the_focal_plane_spreads_by_the_circle_of_confusion() {
    // Blurring by a uniform disc of radius R adds R^2 / 2 to the second
    // moment; a square of half-side a has a^2 * 2/3 of its own. Sixteen by
    // sixteen stratified lens samples per pixel.
    let half = 3.0f32;
    for (aperture, focal, depth) in [
        (24.0f32, 1.0f32, 5.0f32),
        (12.0, 1.5, 5.0),
        (30.0, 1.0, 25.0),
    ] {
        let diameter = aperture * (1.0 / focal - VIEW_DISTANCE / depth).abs();
        let expected = 0.5 * diameter;
        let image = film(
            &square_at(depth, half),
            lit_by_ambient(Some((aperture, focal)), 16),
        );
        let own = 2.0 / 3.0 * f64::from(half * half);
        let radius = (2.0 * (second_moment(&image) - own)).sqrt() as f32;
        assert!(
            (radius / expected - 1.0).abs() < 0.005,
            "A {aperture}, F {focal}, depth {depth}: blur radius {radius} px, \
             the thin lens gives {expected}"
        );
    }
}
