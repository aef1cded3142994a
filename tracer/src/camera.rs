//! The pinhole / thin-lens camera of `scene-format.md`: `angle` spans the
//! centres of the top and bottom pixel rows, the view plane lies at
//! `|at - from|`, the aperture is measured in pixels and the focal plane at
//! `focal` times the view-plane distance.

use glam::{Quat, Vec2, Vec3, Vec3A};

use crate::geometry::Ray;
use crate::scene::{Lens, Viewpoint};

/// Why a camera cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    /// A zero width or height (width, height).
    #[error("the image must be at least 1x1 pixels, got {0}x{1}")]
    EmptyImage(u32, u32),
    /// The eye and the point looked at are the same.
    #[error("`from` and `at` coincide, so there is no view direction")]
    NoViewDirection,
    /// `up` gives no sideways direction.
    #[error("`up` is parallel to the view direction")]
    UpParallel,
    /// A field of view outside 0..180 degrees (the angle given).
    #[error("the field of view must be between 0 and 180 degrees, got {0}")]
    BadAngle(f32),
    /// A negative aperture or a focal ratio <= 0 (aperture, focal).
    #[error("the aperture must be >= 0 and the focal ratio > 0, got {0} and {1}")]
    BadLens(f32, f32),
}

/// Where the camera stands and looks: what a viewer changes when the user
/// orbits, pans or dollies. The field of view and lens stay the scene's.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CameraPose {
    /// The eye's position.
    pub from: Vec3,
    /// The point seen at the image's centre.
    pub at: Vec3,
    /// Which way is up in the image; not parallel to `at - from`.
    pub up: Vec3,
}

/// Closest a pitch may bring the view direction to `up`, in radians, so
/// the camera never becomes degenerate.
const POLE_MARGIN: f32 = 0.02;

impl CameraPose {
    /// The pose of a scene's view.
    pub fn of(view: &Viewpoint) -> Self {
        Self {
            from: view.from,
            at: view.at,
            up: view.up,
        }
    }

    /// Puts this pose into `view`.
    pub fn apply(&self, view: &mut Viewpoint) {
        view.from = self.from;
        view.at = self.at;
        view.up = self.up;
    }

    /// Turns `from` around `at`: `yaw` radians about `up`, `pitch` radians
    /// towards `up` (stopping short of it, or of its opposite).
    pub fn orbit(&self, yaw: f32, pitch: f32) -> Self {
        let up = self.up.normalize_or(Vec3::Z);
        let offset = self.from - self.at;
        let distance = offset.length();
        if distance == 0.0 {
            return *self;
        }
        let offset = Quat::from_axis_angle(up, yaw) * offset;
        let elevation = (offset.dot(up) / distance).clamp(-1.0, 1.0).asin();
        let limit = std::f32::consts::FRAC_PI_2 - POLE_MARGIN;
        let pitch = (elevation + pitch).clamp(-limit, limit) - elevation;
        let right = offset.cross(up).normalize_or(Vec3::X);
        let offset = Quat::from_axis_angle(right, pitch) * offset;
        Self {
            from: self.at + offset,
            ..*self
        }
    }

    /// Slides `from` and `at` together across the view: `dx` to the right
    /// and `dy` up, both as fractions of the distance to `at`.
    pub fn pan(&self, dx: f32, dy: f32) -> Self {
        let forward = self.at - self.from;
        let distance = forward.length();
        let right = forward.cross(self.up).normalize_or_zero();
        let up = right.cross(forward).normalize_or_zero();
        let shift = (right * dx + up * dy) * distance;
        Self {
            from: self.from + shift,
            at: self.at + shift,
            up: self.up,
        }
    }

    /// Moves `from` towards `at` (factor < 1) or away (factor > 1).
    pub fn dolly(&self, factor: f32) -> Self {
        let factor = if factor.is_finite() {
            factor.clamp(1e-3, 1e3)
        } else {
            1.0
        };
        Self {
            from: self.at + (self.from - self.at) * factor,
            ..*self
        }
    }
}

/// A camera ready to generate eye rays for an image of a given size.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    eye: Vec3A,
    /// Unit vectors: image right, image up, view direction.
    right: Vec3A,
    up: Vec3A,
    forward: Vec3A,
    /// Distance from the eye to the view plane.
    view_distance: f32,
    /// World size of one pixel on the view plane.
    pixel_size: f32,
    width: u32,
    height: u32,
    /// Lens radius in world units (0: pinhole).
    lens_radius: f32,
    focal_ratio: f32,
    hither: f32,
}

impl Camera {
    /// A camera for `view` rendering `width` x `height` pixels with the given
    /// lens (`aperture` in pixels, `focal` as a ratio of the view distance).
    pub fn new(
        view: &Viewpoint,
        width: u32,
        height: u32,
        aperture: f32,
        focal: f32,
    ) -> Result<Self, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage(width, height));
        }
        if !(view.angle > 0.0 && view.angle < 180.0) {
            return Err(CameraError::BadAngle(view.angle));
        }
        if !(aperture >= 0.0 && focal > 0.0 && aperture.is_finite() && focal.is_finite()) {
            return Err(CameraError::BadLens(aperture, focal));
        }
        let eye = Vec3A::from(view.from);
        let to_at = Vec3A::from(view.at) - eye;
        let view_distance = to_at.length();
        if !(view_distance > 0.0 && view_distance.is_finite()) {
            return Err(CameraError::NoViewDirection);
        }
        let forward = to_at / view_distance;
        let right = forward.cross(Vec3A::from(view.up));
        if right.length_squared() <= 1e-12 * Vec3A::from(view.up).length_squared() {
            return Err(CameraError::UpParallel);
        }
        let right = right.normalize();
        let up = right.cross(forward);
        let plane_height = 2.0 * view_distance * (view.angle.to_radians() * 0.5).tan();
        let pixel_size = plane_height / (height.max(2) - 1) as f32;
        Ok(Self {
            eye,
            right,
            up,
            forward,
            view_distance,
            pixel_size,
            width,
            height,
            lens_radius: 0.5 * aperture * pixel_size,
            focal_ratio: focal,
            hither: view.hither.max(0.0),
        })
    }

    /// A camera for `view` moved to `pose` (when the user moved it), with
    /// `lens` (`None`: a pinhole). [`RenderSettings::render_camera`] says
    /// which pose and lens a render takes.
    ///
    /// [`RenderSettings::render_camera`]: crate::render::RenderSettings::render_camera
    pub(crate) fn posed(
        view: &Viewpoint,
        pose: Option<&CameraPose>,
        lens: Option<Lens>,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        let lens = lens.unwrap_or(Lens::PINHOLE);
        let mut view = view.clone();
        if let Some(pose) = pose {
            pose.apply(&mut view);
        }
        Self::new(&view, width, height, lens.aperture, lens.focal)
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Eye rays must not report hits nearer than this (`hither`).
    pub fn hither(&self) -> f32 {
        self.hither
    }

    /// True when the lens has a size, so depth of field is visible.
    pub(crate) fn has_lens(&self) -> bool {
        self.lens_radius > 0.0
    }

    /// The point on the view plane at continuous image coordinates `(x, y)`,
    /// in pixels from the top-left corner: pixel `(i, j)` spans
    /// `[i, i + 1) x [j, j + 1)` and its centre is at `(i + 0.5, j + 0.5)`.
    pub fn view_plane_point(&self, x: f32, y: f32) -> Vec3A {
        let u = (x - 0.5 * self.width as f32) * self.pixel_size;
        let v = (0.5 * self.height as f32 - y) * self.pixel_size;
        self.eye + self.forward * self.view_distance + self.right * u + self.up * v
    }

    /// The eye ray through image point `(x, y)` from the lens point `lens`
    /// (a point of the unit disk; ignored by a pinhole camera). Every lens
    /// point's ray meets the others on the focal plane, so it stays sharp.
    pub fn ray(&self, x: f32, y: f32, lens: Vec2) -> Ray {
        let target = self.view_plane_point(x, y);
        if self.lens_radius == 0.0 {
            return Ray::new(self.eye, target - self.eye);
        }
        let focus = self.eye + (target - self.eye) * self.focal_ratio;
        let origin = self.eye + (self.right * lens.x + self.up * lens.y) * self.lens_radius;
        Ray::new(origin, focus - origin)
    }

    /// Where the eye is: the pinhole, or the lens centre.
    pub fn eye(&self) -> Vec3A {
        self.eye
    }

    /// The image's right and up and the view direction, unit vectors: the
    /// frame a figure draws the camera in.
    pub fn basis(&self) -> [Vec3A; 3] {
        [self.right, self.up, self.forward]
    }

    /// The lens radius in scene units (0: a pinhole).
    pub fn lens_radius(&self) -> f32 {
        self.lens_radius
    }

    /// How far the sharp plane is, as a multiple of the view-plane
    /// distance: points at `eye + (view_plane_point - eye) * focal_ratio`
    /// are in focus.
    pub fn focal_ratio(&self) -> f32 {
        self.focal_ratio
    }

    /// How far in front of the eye `point` is, along the view direction
    /// (negative behind it): what clipping at the eye compares.
    pub fn depth(&self, point: Vec3A) -> f32 {
        (point - self.eye).dot(self.forward)
    }

    /// The continuous image coordinates where the pinhole projection of
    /// `point` lands, or `None` behind the eye. The inverse of [`Camera::ray`]
    /// for a pinhole, used by tests and the GUI's picking.
    pub fn project(&self, point: Vec3A) -> Option<Vec2> {
        let d = point - self.eye;
        let depth = d.dot(self.forward);
        if depth <= 0.0 {
            return None;
        }
        let on_plane = d * (self.view_distance / depth);
        let u = on_plane.dot(self.right) / self.pixel_size;
        let v = on_plane.dot(self.up) / self.pixel_size;
        Some(Vec2::new(
            u + 0.5 * self.width as f32,
            0.5 * self.height as f32 - v,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn view(width: u32, height: u32) -> Viewpoint {
        Viewpoint {
            from: Vec3::new(1.0, 2.0, 3.0),
            at: Vec3::new(-2.0, 0.5, -1.0),
            up: Vec3::new(0.2, 1.0, 0.1),
            angle: 40.0,
            hither: 0.0,
            width,
            height,
            aperture: 0.0,
            focal: 1.0,
        }
    }

    #[test]
    fn centre_ray_of_odd_image_goes_through_at() {
        let v = view(101, 51);
        let cam = Camera::new(&v, v.width, v.height, 0.0, 1.0).unwrap();
        let ray = cam.ray(50.5, 25.5, Vec2::ZERO);
        let to_at = (Vec3A::from(v.at) - Vec3A::from(v.from)).normalize();
        assert!(ray.dir.dot(to_at) > 1.0 - 1e-6, "{:?}", ray.dir);
    }

    #[test]
    fn top_and_bottom_row_centres_span_the_angle() {
        let v = view(64, 33);
        let cam = Camera::new(&v, v.width, v.height, 0.0, 1.0).unwrap();
        let top = cam.ray(32.0, 0.5, Vec2::ZERO).dir;
        let bottom = cam.ray(32.0, 32.5, Vec2::ZERO).dir;
        let angle = top.dot(bottom).clamp(-1.0, 1.0).acos().to_degrees();
        assert!((angle - 40.0).abs() < 1e-3, "{angle}");
    }

    #[test]
    fn corner_rays_make_the_stated_angle_and_width_widens_the_field() {
        // Square pixels: on a 2:1 image the horizontal span of pixel centres
        // is twice the vertical one on the view plane.
        let v = view(65, 33);
        let cam = Camera::new(&v, v.width, v.height, 0.0, 1.0).unwrap();
        let centre = cam.view_plane_point(32.5, 16.5);
        let top_left = cam.view_plane_point(0.5, 0.5);
        let bottom_left = cam.view_plane_point(0.5, 32.5);
        let top_right = cam.view_plane_point(64.5, 0.5);
        let vertical = (top_left - bottom_left).length();
        let horizontal = (top_right - top_left).length();
        assert!((horizontal / vertical - 2.0).abs() < 1e-4);
        // The corner ray's angle to the view direction: its offsets on the
        // view plane are d tan(20 deg) vertically and twice that sideways.
        let eye = Vec3A::from(v.from);
        let forward = (Vec3A::from(v.at) - eye).normalize();
        let corner = (top_left - eye).normalize().dot(forward).acos();
        let expected = (20f32.to_radians().tan() * 5f32.sqrt()).atan();
        assert!((corner - expected).abs() < 1e-4, "{corner} vs {expected}");
        assert!((centre - Vec3A::from(v.at)).length() < 1e-4);
    }

    #[test]
    fn right_is_view_cross_up() {
        let v = Viewpoint {
            from: Vec3::new(0.0, 0.0, 5.0),
            at: Vec3::ZERO,
            up: Vec3::Y,
            ..Viewpoint::default()
        };
        let cam = Camera::new(&v, 11, 11, 0.0, 1.0).unwrap();
        // Looking down -z with y up, image right is +x.
        let right_pixel = cam.ray(10.5, 5.5, Vec2::ZERO).dir;
        assert!(right_pixel.x > 0.0 && right_pixel.y.abs() < 1e-6);
        let top_pixel = cam.ray(5.5, 0.5, Vec2::ZERO).dir;
        assert!(top_pixel.y > 0.0);
    }

    #[test]
    fn project_inverts_pinhole_ray() {
        let v = view(80, 60);
        let cam = Camera::new(&v, v.width, v.height, 0.0, 1.0).unwrap();
        let ray = cam.ray(12.25, 40.75, Vec2::ZERO);
        let p = cam.project(ray.at(7.0)).unwrap();
        assert!((p - Vec2::new(12.25, 40.75)).length() < 1e-3, "{p}");
    }

    #[test]
    fn focal_plane_points_are_sharp_and_others_are_not() {
        let v = view(64, 64);
        let cam = Camera::new(&v, 64, 64, 20.0, 1.5).unwrap();
        let d = (Vec3A::from(v.at) - Vec3A::from(v.from)).length();
        let lenses = [
            Vec2::new(0.9, 0.0),
            Vec2::new(-0.5, 0.5),
            Vec2::new(0.0, -0.95),
        ];
        for lens in lenses {
            let ray = cam.ray(20.5, 30.5, lens);
            // Where the ray crosses the focal plane (distance 1.5 d along
            // the view direction), every lens sample agrees.
            let t = (1.5 * d - (ray.origin - cam.eye).dot(cam.forward)) / ray.dir.dot(cam.forward);
            let p = cam.project(ray.at(t)).unwrap();
            assert!((p - Vec2::new(20.5, 30.5)).length() < 1e-2, "{p}");
            // On the view plane (nearer than focus) they disagree.
            let t = (d - (ray.origin - cam.eye).dot(cam.forward)) / ray.dir.dot(cam.forward);
            let q = cam.project(ray.at(t)).unwrap();
            assert!((q - Vec2::new(20.5, 30.5)).length() > 0.5, "{q}");
        }
    }

    /// The thin-lens model of the module doc, worked on paper: a lens point
    /// `l` (in the unit disk) sits `l * A / 2` pixels off the axis, and its
    /// ray meets the pinhole ray of the same image point on the focal plane
    /// (depth `F d`). At depth `z` the two are apart by `l * A / 2 * (1 - z /
    /// (F d))` pixels of the view plane scaled to that depth, so seen
    /// through the pinhole the point lands `|l| * A / 2 * |d / z - 1 / F|`
    /// pixels away: the circle of confusion has the diameter
    /// `A * |1 / F - d / z|`.
    #[test]
    fn circle_of_confusion_matches_the_thin_lens_model() {
        let v = view(96, 64);
        let d = (v.at - v.from).length();
        for (aperture, focal) in [(20.0f32, 1.5f32), (7.0, 0.6), (33.0, 1.0)] {
            let cam = Camera::new(&v, v.width, v.height, aperture, focal).unwrap();
            for z in [0.3 * d, 0.8 * d, 1.9 * d, 4.0 * d] {
                let diameter = aperture * (1.0 / focal - d / z).abs();
                for (x, y) in [(48.0, 32.0), (10.25, 55.5), (90.5, 3.75)] {
                    for angle in [0.0f32, 1.0, 2.5, 4.0, 5.5] {
                        for radius in [1.0f32, 0.5] {
                            let lens = Vec2::from_angle(angle) * radius;
                            let ray = cam.ray(x, y, lens);
                            // Where the ray reaches depth z along the view.
                            let t = (z - (ray.origin - cam.eye).dot(cam.forward))
                                / ray.dir.dot(cam.forward);
                            let seen = cam.project(ray.at(t)).unwrap();
                            let spread = (seen - Vec2::new(x, y)).length();
                            let expected = 0.5 * diameter * radius;
                            assert!(
                                (spread - expected).abs() < 1e-3,
                                "A {aperture} F {focal} z {z}: {spread} px, expected {expected}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn orbit_keeps_the_distance_and_stops_short_of_the_pole() {
        let pose = CameraPose::of(&view(8, 8));
        let distance = (pose.from - pose.at).length();
        let turned = pose.orbit(0.7, 0.3);
        assert!(((turned.from - turned.at).length() - distance).abs() < 1e-4);
        assert_eq!(turned.at, pose.at);
        let top = pose.orbit(0.0, 10.0);
        let dir = (top.from - top.at).normalize();
        let up = pose.up.normalize();
        assert!(dir.dot(up) < 1.0 - 1e-5 && dir.dot(up) > 0.99);
        let mut v = view(8, 8);
        top.apply(&mut v);
        assert!(Camera::new(&v, 8, 8, 0.0, 1.0).is_ok());
        // A full turn of yaw comes back.
        let round = pose.orbit(std::f32::consts::TAU, 0.0);
        assert!((round.from - pose.from).length() < 1e-4);
    }

    #[test]
    fn pan_moves_both_points_and_dolly_changes_the_distance() {
        let pose = CameraPose::of(&view(8, 8));
        let panned = pose.pan(0.1, -0.2);
        assert!(((panned.from - pose.from) - (panned.at - pose.at)).length() < 1e-6);
        assert!((panned.from - pose.from).length() > 0.0);
        let closer = pose.dolly(0.5);
        let d0 = (pose.from - pose.at).length();
        assert!(((closer.from - closer.at).length() - 0.5 * d0).abs() < 1e-4);
        // Halfway, on the eye's side of `at`.
        assert!((closer.from - (pose.from + pose.at) * 0.5).length() < 1e-5);
    }

    #[test]
    fn pan_slides_along_the_image_axes() {
        let v = view(8, 8);
        let pose = CameraPose::of(&v);
        let [right, up, _] = Camera::new(&v, 8, 8, 0.0, 1.0).unwrap().basis();
        let shift = Vec3::from((right * 0.1 - up * 0.2) * (pose.at - pose.from).length());
        let panned = pose.pan(0.1, -0.2);
        assert!(
            (panned.from - pose.from - shift).length() < 1e-5,
            "{panned:?}"
        );
        assert!((panned.at - pose.at - shift).length() < 1e-5, "{panned:?}");
        assert_eq!(panned.up, pose.up);
    }

    /// The eye's elevation above the plane across `up`, and its direction
    /// in that plane (unit), seen from `at`.
    fn elevation_and_heading(pose: &CameraPose) -> (f32, Vec3) {
        let up = pose.up.normalize();
        let offset = (pose.from - pose.at).normalize();
        let heading = (offset - up * offset.dot(up)).normalize();
        (offset.dot(up).asin(), heading)
    }

    #[test]
    fn orbit_pitches_by_the_angle_and_stops_at_the_margin_on_its_side() {
        let pose = CameraPose::of(&view(8, 8));
        let (start, heading) = elevation_and_heading(&pose);
        let limit = std::f32::consts::FRAC_PI_2 - POLE_MARGIN;
        for (pitch, expected) in [
            (0.3, start + 0.3),
            (-0.4, start - 0.4),
            (10.0, limit),
            (-10.0, -limit),
        ] {
            let (elevation, turned) = elevation_and_heading(&pose.orbit(0.0, pitch));
            assert!(
                (elevation - expected).abs() < 1e-4,
                "pitch {pitch}: {elevation} vs {expected}"
            );
            // Never over the pole: the eye stays on its side of `up`.
            assert!(turned.dot(heading) > 1.0 - 1e-4, "pitch {pitch}: {turned}");
        }
    }

    #[test]
    fn accessors_give_the_frame_lens_and_depths() {
        let v = Viewpoint {
            from: Vec3::new(0.0, 0.0, 5.0),
            at: Vec3::ZERO,
            up: Vec3::Y,
            angle: 90.0,
            hither: 0.25,
            ..Viewpoint::default()
        };
        // 11 rows span 10 units at distance 5 (tan 45 deg = 1): a unit a
        // pixel, so an aperture of 3 pixels is a radius of 1.5 units.
        let cam = Camera::new(&v, 11, 11, 3.0, 2.0).unwrap();
        assert_eq!(cam.eye(), Vec3A::new(0.0, 0.0, 5.0));
        assert_eq!(cam.basis(), [Vec3A::X, Vec3A::Y, Vec3A::NEG_Z]);
        assert!(
            (cam.lens_radius() - 1.5).abs() < 1e-5,
            "{}",
            cam.lens_radius()
        );
        assert_eq!(cam.focal_ratio(), 2.0);
        assert_eq!(cam.hither(), 0.25);
        assert_eq!(cam.depth(Vec3A::new(3.0, -2.0, 1.0)), 4.0);
        assert_eq!(cam.depth(Vec3A::new(0.0, 0.0, 6.0)), -1.0);
        assert!(cam.has_lens());
        // A lens point's ray starts that far across the lens, right and up.
        let origin = cam.ray(5.5, 5.5, Vec2::new(0.6, 0.8)).origin;
        assert!(
            (origin - Vec3A::new(0.9, 1.2, 5.0)).length() < 1e-5,
            "{origin}"
        );
        assert!(!Camera::new(&v, 11, 11, 0.0, 2.0).unwrap().has_lens());
        let wide = Camera::new(&v, 16, 9, 0.0, 1.0).unwrap();
        assert_eq!((wide.width(), wide.height()), (16, 9));
    }

    #[test]
    fn degenerate_cameras_are_errors() {
        let mut v = view(8, 8);
        v.up = (v.at - v.from) * 2.0;
        assert_eq!(
            Camera::new(&v, 8, 8, 0.0, 1.0),
            Err(CameraError::UpParallel)
        );
        let mut v = view(8, 8);
        v.at = v.from;
        assert_eq!(
            Camera::new(&v, 8, 8, 0.0, 1.0),
            Err(CameraError::NoViewDirection)
        );
        assert!(Camera::new(&view(8, 8), 0, 8, 0.0, 1.0).is_err());
        assert!(Camera::new(&view(8, 8), 8, 8, -1.0, 1.0).is_err());
    }
}
