//! Soft shadows against the geometry of a straight edge: under an S x S
//! light at height H, an occluder edge at height h casts a penumbra S h /
//! (H - h) wide, and a floor point sees the fraction of the light that the
//! edge leaves uncovered. Both shadow modes (N x N stratified light samples
//! per pixel; one light sample per pixel sample with anti-aliasing), for a
//! point light given a size and for an `al` light.

use glam::Vec2;

use super::{index, world};
use crate::accel::AccelKind;
use crate::render::{Film, RenderSettings, render};

/// Light height, occluder height and light side.
const H: f32 = 40.0;
const LOW: f32 = 20.0;
const S: f32 = 2.0;
/// The image: a strip of the floor `SPAN` units wide under the light, one
/// pixel row per `SPAN / WIDTH` units, seen from straight above so floor
/// and image are in proportion.
const WIDTH: u32 = 128;
const HEIGHT: u32 = 5;
const SPAN: f32 = 3.0;
/// How far the ratio of two weighted sums strays from the unweighted
/// fraction: `n . l` varies by less than 0.3% over the light seen from the
/// strip, and a point light's square tilts by at most 2 degrees to face it.
const COSINE_SLACK: f32 = 0.005;

/// A white floor at y = 0 lit by `light` from y = 40; with `occluder`, a
/// black half-plane at y = 20 covers x < 0. The camera looks straight down
/// from y = 10 (under the occluder), image right = +x.
fn scene(light: &str, occluder: bool) -> String {
    let pixel = SPAN / WIDTH as f32;
    // The angle spans the centres of the top and bottom rows, 10 units
    // away, on the floor (the view plane).
    let angle = 2.0
        * (0.5 * pixel * (HEIGHT - 1) as f32 / 10.0)
            .atan()
            .to_degrees();
    let mut text = format!(
        "bclr 0 0 0\n\
         v from 0 10 0 at 0 0 0 up 0 0 -1 angle {angle} hither 0 resolution {WIDTH} {HEIGHT}\n\
         {light}\n\
         f 1 1 1 1 0 0 0 0 1 0 1\n\
         p 4 -30 0 -30  30 0 -30  30 0 30  -30 0 30\n"
    );
    if occluder {
        text.push_str(&format!(
            "f 0 0 0 0 0 0 0 0 1 0 1\np 4 -30 {LOW} -30  0 {LOW} -30  0 {LOW} 30  -30 {LOW} 30\n"
        ));
    }
    text
}

/// The fraction of the light a floor point at `x` sees past the edge: the
/// line from the point over the edge meets the light's plane at
/// `-x (H - h) / h`, and the light spans `[-S/2, S/2]`.
fn visible_fraction(x: f32) -> f32 {
    (0.5 + x * (H - LOW) / (LOW * S)).clamp(0.0, 1.0)
}

fn settings(antialiasing: bool, n: u32) -> RenderSettings {
    RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        ambient: 0.0,
        soft_shadows: true,
        light_size: S,
        antialiasing,
        samples: n,
        ..RenderSettings::default()
    }
}

fn film(text: &str, settings: &RenderSettings) -> Film {
    let w = world(text);
    render(
        w.clone(),
        index(&w, AccelKind::Bvh),
        settings.clone(),
        Some(2),
    )
    .unwrap()
    .0
}

/// Per pixel of the middle row: the floor x under the pixel centre and the
/// shadowed radiance over the unshadowed one (the same samples, so the
/// light's cosine and colour cancel).
fn measured(light: &str, settings: &RenderSettings) -> Vec<(f32, f32)> {
    let shadowed = film(&scene(light, true), settings);
    let open = film(&scene(light, false), settings);
    let w = world(&scene(light, false));
    let camera = settings.render_camera(&w.view).unwrap();
    let row = HEIGHT / 2;
    (0..WIDTH)
        .map(|px| {
            let ray = camera.ray(px as f32 + 0.5, row as f32 + 0.5, Vec2::ZERO);
            let x = ray.at(-ray.origin.y / ray.dir.y).x;
            let lit = open.pixel(px, row).unwrap().x;
            assert!(lit > 0.5, "the open floor is lit: {lit} at x = {x}");
            (x, shadowed.pixel(px, row).unwrap().x / lit)
        })
        .collect()
}

/// The penumbra's width from a least-squares line through the pixels of
/// its middle (where the edge leaves 10% to 90% of the light, chosen by
/// position so the quantised values do not pick themselves): the fraction
/// rises at 1 / width per unit.
fn fitted_width(points: &[(f32, f32)]) -> f32 {
    let inside: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, _)| (0.1..0.9).contains(&visible_fraction(*x)))
        .map(|&(x, f)| (f64::from(x), f64::from(f)))
        .collect();
    let n = inside.len() as f64;
    let (sx, sf) = inside
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, f)| (a + x, b + f));
    let (mx, mf) = (sx / n, sf / n);
    let (sxf, sxx) = inside.iter().fold((0.0, 0.0), |(a, b), (x, f)| {
        (a + (x - mx) * (f - mf), b + (x - mx) * (x - mx))
    });
    (sxx / sxf) as f32
}

const POINT_LIGHT: &str = "l 0 40 0 1 1 1";
const AREA_LIGHT: &str = "al 0 40 0  0 0 0  2 2  1 1 1";

#[test]
fn each_floor_pixel_sees_the_visible_fraction_of_the_light_within_one_sample() {
    let penumbra = S * LOW / (H - LOW);
    for (light, name) in [(POINT_LIGHT, "point light"), (AREA_LIGHT, "al light")] {
        for antialiasing in [false, true] {
            for n in [3, 4, 8] {
                let s = settings(antialiasing, n);
                let mode = if antialiasing {
                    "one light sample per AA sample"
                } else {
                    "stratified"
                };
                // With anti-aliasing the samples spread over the pixel,
                // across which the fraction changes by this much.
                let across_pixel = if antialiasing {
                    (SPAN / WIDTH as f32) / penumbra
                } else {
                    0.0
                };
                let tolerance = 1.0 / (n * n) as f32 + across_pixel + COSINE_SLACK;
                let points = measured(light, &s);
                for &(x, fraction) in &points {
                    let expected = visible_fraction(x);
                    assert!(
                        (fraction - expected).abs() <= tolerance,
                        "{name}, {mode}, N = {n}: at x = {x} the floor sees {fraction} of the \
                         light, the edge leaves {expected} (tolerance {tolerance})"
                    );
                }
                let width = fitted_width(&points);
                assert!(
                    (width / penumbra - 1.0).abs() < 0.03,
                    "{name}, {mode}, N = {n}: penumbra {width} wide, S h / (H - h) = {penumbra}"
                );
            }
        }
    }
}

#[test]
fn hard_shadows_have_no_penumbra() {
    let s = RenderSettings {
        soft_shadows: false,
        ..settings(false, 4)
    };
    for light in [POINT_LIGHT, AREA_LIGHT] {
        let points = measured(light, &s);
        for &(x, fraction) in &points {
            let expected = if x > 0.0 { 1.0 } else { 0.0 };
            assert!((fraction - expected).abs() < 1e-4, "x = {x}: {fraction}");
        }
    }
}

/// Shadows off: no shadow ray is cast or counted, and the floor under the
/// occluder is lit as the open floor is (with shadows on it is dark), for
/// both lights, with hard or soft shadows asked for.
#[test]
fn without_shadows_no_shadow_ray_is_cast_and_the_occluded_floor_is_lit() {
    let pixels = u64::from(WIDTH * HEIGHT);
    for light in [POINT_LIGHT, AREA_LIGHT] {
        let hard = RenderSettings {
            soft_shadows: false,
            ..settings(false, 4)
        };
        let open = film(&scene(light, false), &hard);
        let shadowed = film(&scene(light, true), &hard);
        let row = HEIGHT / 2;
        assert!(
            shadowed.pixel(0, row).unwrap().x < 0.01,
            "with shadows the occluded floor is dark"
        );
        for soft_shadows in [false, true] {
            let off = RenderSettings {
                shadows: false,
                soft_shadows,
                ..hard.clone()
            };
            let w = world(&scene(light, true));
            let (lit, stats) = render(w.clone(), index(&w, AccelKind::Bvh), off, Some(2)).unwrap();
            let c = &stats.counters;
            assert_eq!(c.shadow_rays, 0, "{light}, soft {soft_shadows}");
            assert_eq!(c.total_rays(), pixels, "eye rays only");
            for y in 0..HEIGHT {
                for x in 0..WIDTH {
                    // The occluder moves the ray origins' offset (a
                    // millionth of the scene's size) by a hair.
                    let (a, b) = (lit.pixel(x, y).unwrap(), open.pixel(x, y).unwrap());
                    assert!(
                        (a - b).abs().max_element() < 1e-5,
                        "{light}, soft {soft_shadows}: ({x}, {y}) is {a}, the open floor {b}"
                    );
                }
            }
        }
    }
}
