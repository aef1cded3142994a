//! The acceleration structure drawn over an image: its 3D wireframe
//! projected through the render's camera, as thin lines.

use glam::{Vec2, Vec3A};
use image::{Rgb, RgbImage};
use tracer::accel::Visit;
use tracer::camera::Camera;

use super::projection::Projector;

/// The colour of the wireframe: visible on both the shaded image and the
/// heat maps.
pub(crate) const WIRE: Rgb<u8> = Rgb([80, 255, 120]);

/// Draws each 3D segment of `segments` projected by `camera`, clipped at
/// the eye.
pub(crate) fn draw_wireframe(image: &mut RgbImage, camera: &Camera, segments: &[[Vec3A; 2]]) {
    let projector = Projector::new(camera);
    for &[a, b] in segments {
        if let Some([a, b]) = projector.segment(a, b) {
            draw_line(image, a, b, WIRE);
        }
    }
}

/// The colour of visit `i` of `n` in a traversal: yellow for the first,
/// through orange, to red for the last, so the order of a walk reads off
/// the image. The window's overlay uses it too.
pub(crate) fn visit_colour(i: usize, n: usize) -> [u8; 3] {
    let t = i as f32 / n.saturating_sub(1).max(1) as f32;
    [255, (230.0 - 200.0 * t) as u8, (40.0 * t) as u8]
}

/// Which of one ray's visits are drawn: all of them, or the first `k + 1`
/// while the user steps through the traversal, visit `k` highlighted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) enum VisitStep {
    #[default]
    All,
    At(usize),
}

/// The colour of the visit a step is at: white, apart from the walk's
/// yellow to red and the structure's green.
pub(crate) const CURRENT_VISIT: [u8; 3] = [255, 255, 255];

impl VisitStep {
    /// The visit it is at among `n` (the last one for a step beyond them,
    /// as a new pixel's walk may be shorter), `None` showing all.
    pub(crate) fn current(self, n: usize) -> Option<usize> {
        match self {
            VisitStep::All => None,
            VisitStep::At(k) => n.checked_sub(1).map(|last| k.min(last)),
        }
    }

    /// How many of `n` visits it draws.
    pub(crate) fn drawn(self, n: usize) -> usize {
        self.current(n).map_or(n, |k| k + 1)
    }

    /// One visit on among `n`: from all, the first.
    pub(crate) fn next(self, n: usize) -> VisitStep {
        match self.current(n) {
            None => VisitStep::At(0),
            Some(k) => VisitStep::At((k + 1).min(n.saturating_sub(1))),
        }
    }

    /// One visit back among `n`: from all, the last.
    pub(crate) fn back(self, n: usize) -> VisitStep {
        match self.current(n) {
            None => VisitStep::At(n.saturating_sub(1)),
            Some(k) => VisitStep::At(k.saturating_sub(1)),
        }
    }

    /// The visits of `visits` drawn at this step, each with its colour:
    /// the whole walk's yellow to red, so a visit keeps its colour as the
    /// steps go on, and [`CURRENT_VISIT`] for the step's own.
    pub(crate) fn coloured(self, visits: &[Visit]) -> impl Iterator<Item = (&Visit, Colour)> {
        let n = visits.len();
        let current = self.current(n);
        visits[..self.drawn(n)]
            .iter()
            .enumerate()
            .map(move |(i, v)| {
                let colour = if current == Some(i) {
                    Colour::Current
                } else {
                    Colour::Order(visit_colour(i, n))
                };
                (v, colour)
            })
    }
}

/// How a drawn visit is coloured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum Colour {
    /// Its place in the walk ([`visit_colour`]).
    Order([u8; 3]),
    /// The step's own visit: [`CURRENT_VISIT`], drawn thicker.
    Current,
}

impl Colour {
    pub(crate) fn rgb(self) -> [u8; 3] {
        match self {
            Colour::Order(rgb) => rgb,
            Colour::Current => CURRENT_VISIT,
        }
    }
}

/// Draws the boxes of one ray's `visits` over `image`, coloured by their
/// order ([`visit_colour`]).
pub(crate) fn draw_visits(image: &mut RgbImage, camera: &Camera, visits: &[Visit]) {
    let projector = Projector::new(camera);
    for (i, visit) in visits.iter().enumerate() {
        let colour = Rgb(visit_colour(i, visits.len()));
        for [a, b] in visit.edges() {
            if let Some([a, b]) = projector.segment(a, b) {
                draw_line(image, a, b, colour);
            }
        }
    }
}

/// A one-pixel line from `a` to `b` (image coordinates), clipped to the
/// image first, so a segment reaching far off-screen costs no more than
/// one across it.
pub(crate) fn draw_line(image: &mut RgbImage, a: Vec2, b: Vec2, colour: Rgb<u8>) {
    for (x, y) in line_pixels(a, b, image.width(), image.height()) {
        image.put_pixel(x, y, colour);
    }
}

/// The pixels of a one-pixel line from `a` to `b` inside a `width` x
/// `height` image.
pub(crate) fn line_pixels(a: Vec2, b: Vec2, width: u32, height: u32) -> Vec<(u32, u32)> {
    let size = Vec2::new(width as f32, height as f32);
    let Some((a, b)) = clip(a, b, size) else {
        return Vec::new();
    };
    let steps = (b - a).abs().max_element().ceil().max(1.0);
    (0..=steps as u32)
        .map(|i| a + (b - a) * (i as f32 / steps))
        .filter(|p| p.x >= 0.0 && p.y >= 0.0 && p.x < size.x && p.y < size.y)
        .map(|p| (p.x as u32, p.y as u32))
        .collect()
}

/// The part of segment `a`-`b` inside `[0, size]` (Liang and Barsky);
/// `None` when none is, or for non-finite ends.
fn clip(a: Vec2, b: Vec2, size: Vec2) -> Option<(Vec2, Vec2)> {
    if !a.is_finite() || !b.is_finite() {
        return None;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (p, q) in [
        (-d.x, a.x),
        (d.x, size.x - a.x),
        (-d.y, a.y),
        (d.y, size.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then(|| (a + d * t0, a + d * t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_draws_the_visits_up_to_it_in_the_walks_colours() {
        let visit = |x: u32| Visit::Cell {
            cell: [x, 0, 0],
            bounds: tracer::geometry::Aabb::new(Vec3A::ZERO, Vec3A::ONE),
            tested: 1,
        };
        let visits: Vec<Visit> = (0..4).map(visit).collect();
        let colours =
            |step: VisitStep| -> Vec<Colour> { step.coloured(&visits).map(|(_, c)| c).collect() };
        let order = |i| Colour::Order(visit_colour(i, 4));
        assert_eq!(
            colours(VisitStep::All),
            (0..4).map(order).collect::<Vec<_>>()
        );
        let second = VisitStep::All.next(4).next(4);
        assert_eq!(second, VisitStep::At(1));
        assert_eq!(colours(second), [order(0), Colour::Current]);
        // Beyond a shorter walk: its last visit.
        assert_eq!(VisitStep::At(9).current(4), Some(3));
        assert_eq!(VisitStep::At(3).next(4), VisitStep::At(3));
        assert_eq!(VisitStep::All.back(4), VisitStep::At(3));
        assert_eq!(VisitStep::At(0).back(4), VisitStep::At(0));
        assert_eq!(VisitStep::At(2).drawn(0), 0);
        assert_eq!(VisitStep::All.drawn(4), 4);
    }

    #[test]
    fn lines_are_drawn_and_clipped() {
        let mut image = RgbImage::new(10, 10);
        draw_line(&mut image, Vec2::new(0.5, 5.5), Vec2::new(20.0, 5.5), WIRE);
        assert!((0..10).all(|x| *image.get_pixel(x, 5) == WIRE));
        assert_eq!(*image.get_pixel(5, 4), Rgb([0, 0, 0]));
        draw_line(
            &mut image,
            Vec2::new(2.5, -50.0),
            Vec2::new(2.5, 50.0),
            WIRE,
        );
        assert!((0..10).all(|y| *image.get_pixel(2, y) == WIRE));
        draw_line(&mut image, Vec2::NAN, Vec2::ONE, WIRE);
    }

    #[test]
    fn visits_run_from_yellow_to_red() {
        assert_eq!(visit_colour(0, 5), [255, 230, 0]);
        assert_eq!(visit_colour(4, 5), [255, 30, 40]);
        let greens: Vec<u8> = (0..5).map(|i| visit_colour(i, 5)[1]).collect();
        assert!(greens.windows(2).all(|w| w[0] > w[1]), "{greens:?}");
        assert_eq!(visit_colour(0, 1), [255, 230, 0]);
    }
}
