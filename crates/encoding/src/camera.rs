//! Cameras: a 2D orthographic camera for planar scenes and a 3D perspective orbit camera.
//!
//! Pure `f64` math (no GPU types): the renderer turns [`Camera::clip_from_world`] into an
//! `f32` uniform, the viewer drives [`Camera::pan`], [`Camera::zoom_at`] and
//! [`Camera::orbit`], tests use [`Camera::pixel_from_world`].
//!
//! Pixel coordinates have their origin at the top-left corner of the viewport, `x` to the
//! right and `y` down; a pixel's centre is at `(i + 0.5, j + 0.5)`. World `y` points up.

use glam::{DMat4, DVec2, DVec3, DVec4};

use splinescope_core::geom::Aabb;

/// An orthographic camera looking down `−z` at the plane `z = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera2d {
    /// The world point at the centre of the viewport.
    pub center: DVec2,
    /// Zoom: how many pixels one world unit spans (> 0).
    pub pixels_per_unit: f64,
}

/// A perspective camera orbiting a target point (world `y` up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera3d {
    /// The point looked at and orbited.
    pub target: DVec3,
    /// Distance from the eye to the target (> 0).
    pub distance: f64,
    /// Rotation about the world `y` axis, radians (0 looks down `−z`).
    pub yaw: f64,
    /// Elevation above the `xz` plane, radians, kept inside `(−π/2, π/2)`.
    pub pitch: f64,
    /// Vertical field of view, radians.
    pub fov_y: f64,
}

/// The camera of a view: 2D for planar scenes, 3D otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Camera {
    /// Orthographic, for planar scenes.
    Ortho2d(Camera2d),
    /// Perspective orbit, for 3D scenes.
    Orbit3d(Camera3d),
}

/// The fraction of the viewport a fitted scene fills.
pub const FIT_FILL: f64 = 0.9;
/// The default vertical field of view of the 3D camera, in degrees.
pub const DEFAULT_FOV_DEG: f64 = 45.0;
const PITCH_LIMIT: f64 = 1.55;

impl Camera3d {
    /// The eye position.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + self.distance * DVec3::new(cp * sy, sp, cp * cy)
    }
}

impl Camera {
    /// A camera showing all of `bbox` in a `viewport` (pixels), 2D or 3D as asked.
    ///
    /// An empty box gives a camera on the origin; a box of zero size gets one world unit.
    #[must_use]
    pub fn fit(bbox: Aabb, viewport: DVec2, three_d: bool) -> Camera {
        let (center, size) = if bbox.is_empty() {
            (DVec3::ZERO, DVec3::ONE)
        } else {
            (bbox.center(), bbox.max - bbox.min)
        };
        if three_d {
            let radius = (0.5 * size.length()).max(1e-9);
            let fov_y = DEFAULT_FOV_DEG.to_radians();
            let aspect = (viewport.x / viewport.y.max(1.0)).max(1e-6);
            // The tighter of the vertical and horizontal half-angles bounds the sphere.
            let half = (0.5 * fov_y).min((aspect * (0.5 * fov_y).tan()).atan());
            Camera::Orbit3d(Camera3d {
                target: center,
                distance: radius / (half.sin() * FIT_FILL),
                yaw: 0.5,
                pitch: 0.35,
                fov_y,
            })
        } else {
            let w = if size.x > 0.0 { size.x } else { size.y };
            let h = if size.y > 0.0 { size.y } else { size.x };
            let (w, h) = if w > 0.0 { (w, h) } else { (1.0, 1.0) };
            let ppu = FIT_FILL * (viewport.x / w).min(viewport.y / h);
            Camera::Ortho2d(Camera2d {
                center: center.truncate(),
                pixels_per_unit: ppu,
            })
        }
    }

    /// The matrix taking world points to wgpu clip space (`x, y ∈ [−1, 1]` up-right,
    /// depth in `[0, 1]`) for a `viewport` in pixels.
    #[must_use]
    pub fn clip_from_world(&self, viewport: DVec2) -> DMat4 {
        let viewport = viewport.max(DVec2::ONE);
        match self {
            Camera::Ortho2d(c) => {
                let sx = 2.0 * c.pixels_per_unit / viewport.x;
                let sy = 2.0 * c.pixels_per_unit / viewport.y;
                DMat4::from_cols(
                    DVec4::new(sx, 0.0, 0.0, 0.0),
                    DVec4::new(0.0, sy, 0.0, 0.0),
                    DVec4::new(0.0, 0.0, 0.0, 0.0),
                    DVec4::new(-sx * c.center.x, -sy * c.center.y, 0.5, 1.0),
                )
            }
            Camera::Orbit3d(c) => {
                let view = glam::dcamera::rh::view::look_at_mat4(c.eye(), c.target, DVec3::Y);
                let aspect = viewport.x / viewport.y;
                let near = (c.distance * 1e-3).max(1e-9);
                let far = c.distance * 1e3 + 1.0;
                glam::dcamera::rh::proj::directx::perspective(c.fov_y, aspect, near, far) * view
            }
        }
    }

    /// The pixel position of a world point, or `None` behind a 3D camera.
    #[must_use]
    pub fn pixel_from_world(&self, p: DVec3, viewport: DVec2) -> Option<DVec2> {
        let clip = self.clip_from_world(viewport) * p.extend(1.0);
        if clip.w <= 0.0 {
            return None;
        }
        let ndc = clip.truncate().truncate() / clip.w;
        Some(DVec2::new(
            (ndc.x * 0.5 + 0.5) * viewport.x,
            (0.5 - ndc.y * 0.5) * viewport.y,
        ))
    }

    /// The world point under a pixel (2D), or on the plane through the target facing the
    /// eye (3D).
    #[must_use]
    pub fn world_from_pixel(&self, pixel: DVec2, viewport: DVec2) -> DVec3 {
        match self {
            Camera::Ortho2d(c) => {
                let d = (pixel - 0.5 * viewport) / c.pixels_per_unit;
                DVec3::new(c.center.x + d.x, c.center.y - d.y, 0.0)
            }
            Camera::Orbit3d(c) => {
                let (right, up) = orbit_basis(c);
                let scale = 2.0 * c.distance * (0.5 * c.fov_y).tan() / viewport.y.max(1.0);
                let d = (pixel - 0.5 * viewport) * scale;
                c.target + right * d.x - up * d.y
            }
        }
    }

    /// The world point under `pixel` on the plane through `anchor` that faces the viewer
    /// (2D: the plane `z = anchor.z`). Dragging a point keeps it at its depth.
    #[must_use]
    pub fn drag_point(&self, pixel: DVec2, viewport: DVec2, anchor: DVec3) -> DVec3 {
        match self {
            Camera::Ortho2d(_) => {
                let p = self.world_from_pixel(pixel, viewport);
                DVec3::new(p.x, p.y, anchor.z)
            }
            Camera::Orbit3d(c) => {
                let inverse = self.clip_from_world(viewport).inverse();
                let ndc = DVec2::new(
                    pixel.x / viewport.x.max(1.0) * 2.0 - 1.0,
                    1.0 - pixel.y / viewport.y.max(1.0) * 2.0,
                );
                let unproject = |z: f64| {
                    let h = inverse * DVec4::new(ndc.x, ndc.y, z, 1.0);
                    h.truncate() / h.w
                };
                let (near, far) = (unproject(0.0), unproject(1.0));
                let dir = (far - near).normalize_or(DVec3::NEG_Z);
                let normal = (c.target - c.eye()).normalize_or(DVec3::NEG_Z);
                let denom = dir.dot(normal);
                if denom.abs() < 1e-12 {
                    return anchor;
                }
                near + dir * ((anchor - near).dot(normal) / denom)
            }
        }
    }

    /// Moves the view so that the content follows the pointer by `delta_px`.
    pub fn pan(&mut self, delta_px: DVec2, viewport: DVec2) {
        match self {
            Camera::Ortho2d(c) => {
                c.center.x -= delta_px.x / c.pixels_per_unit;
                c.center.y += delta_px.y / c.pixels_per_unit;
            }
            Camera::Orbit3d(c) => {
                let (right, up) = orbit_basis(c);
                let scale = 2.0 * c.distance * (0.5 * c.fov_y).tan() / viewport.y.max(1.0);
                c.target += (-right * delta_px.x + up * delta_px.y) * scale;
            }
        }
    }

    /// Zooms by `factor` (> 1 zooms in), keeping the world point under `pixel` fixed in 2D
    /// and moving the eye towards the target in 3D.
    pub fn zoom_at(&mut self, factor: f64, pixel: DVec2, viewport: DVec2) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        match self {
            Camera::Ortho2d(c) => {
                let before = Camera::Ortho2d(*c).world_from_pixel(pixel, viewport);
                c.pixels_per_unit = (c.pixels_per_unit * factor).clamp(1e-9, 1e15);
                let after = Camera::Ortho2d(*c).world_from_pixel(pixel, viewport);
                c.center += (before - after).truncate();
            }
            Camera::Orbit3d(c) => {
                c.distance = (c.distance / factor).clamp(1e-9, 1e15);
            }
        }
    }

    /// Orbits a 3D camera by a pointer drag of `delta_px` (no effect in 2D).
    pub fn orbit(&mut self, delta_px: DVec2) {
        if let Camera::Orbit3d(c) = self {
            c.yaw -= delta_px.x * 0.01;
            c.pitch = (c.pitch + delta_px.y * 0.01).clamp(-PITCH_LIMIT, PITCH_LIMIT);
        }
    }

    /// The height, in world units, of what a `viewport` shows (in 3D, at the target's
    /// distance).
    #[must_use]
    pub fn view_height(&self, viewport: DVec2) -> f64 {
        match self {
            Camera::Ortho2d(c) => viewport.y / c.pixels_per_unit,
            Camera::Orbit3d(c) => 2.0 * c.distance * (0.5 * c.fov_y).tan(),
        }
    }

    /// Whether this is the 3D camera.
    #[must_use]
    pub fn is_3d(&self) -> bool {
        matches!(self, Camera::Orbit3d(_))
    }
}

/// The camera's right and up unit vectors.
fn orbit_basis(c: &Camera3d) -> (DVec3, DVec3) {
    let forward = (c.target - c.eye()).normalize_or(DVec3::NEG_Z);
    let right = forward.cross(DVec3::Y).normalize_or(DVec3::X);
    let up = right.cross(forward);
    (right, up)
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEW: DVec2 = DVec2::new(800.0, 600.0);

    #[test]
    fn fitted_2d_box_fills_the_viewport_and_is_centred() {
        let bbox = Aabb::from_points(&[DVec3::new(-1.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 0.0)]);
        let cam = Camera::fit(bbox, VIEW, false);
        let lo = cam.pixel_from_world(bbox.min, VIEW).unwrap();
        let hi = cam.pixel_from_world(bbox.max, VIEW).unwrap();
        // The box is wider than tall: its width is FIT_FILL of the viewport.
        assert!(((hi.x - lo.x) - FIT_FILL * VIEW.x).abs() < 1e-9);
        assert!(((lo.x + hi.x) * 0.5 - VIEW.x * 0.5).abs() < 1e-9);
        // World y up is pixel y down.
        assert!(hi.y < lo.y);
    }

    #[test]
    fn pixel_and_world_round_trip_in_2d() {
        let cam = Camera::Ortho2d(Camera2d {
            center: DVec2::new(2.0, -1.0),
            pixels_per_unit: 37.0,
        });
        let p = DVec3::new(3.5, 0.25, 0.0);
        let px = cam.pixel_from_world(p, VIEW).unwrap();
        assert!((cam.world_from_pixel(px, VIEW) - p).length() < 1e-12);
    }

    #[test]
    fn zoom_keeps_the_point_under_the_cursor() {
        let mut cam = Camera::Ortho2d(Camera2d {
            center: DVec2::ZERO,
            pixels_per_unit: 10.0,
        });
        let cursor = DVec2::new(100.0, 450.0);
        let before = cam.world_from_pixel(cursor, VIEW);
        cam.zoom_at(1.7, cursor, VIEW);
        assert!((cam.world_from_pixel(cursor, VIEW) - before).length() < 1e-12);
    }

    #[test]
    fn pan_moves_content_with_the_pointer() {
        let mut cam = Camera::Ortho2d(Camera2d {
            center: DVec2::ZERO,
            pixels_per_unit: 10.0,
        });
        let p = DVec3::new(1.0, 1.0, 0.0);
        let before = cam.pixel_from_world(p, VIEW).unwrap();
        cam.pan(DVec2::new(15.0, -4.0), VIEW);
        let after = cam.pixel_from_world(p, VIEW).unwrap();
        assert!((after - before - DVec2::new(15.0, -4.0)).length() < 1e-9);
    }

    #[test]
    fn dragged_points_land_under_the_pointer_at_their_depth() {
        let bbox = Aabb::from_points(&[DVec3::new(-1.0, -2.0, -3.0), DVec3::new(4.0, 1.0, 2.0)]);
        for three_d in [false, true] {
            let cam = Camera::fit(bbox, VIEW, three_d);
            let anchor = DVec3::new(1.0, 0.5, if three_d { 1.0 } else { 0.0 });
            let pixel = DVec2::new(300.0, 250.0);
            let p = cam.drag_point(pixel, VIEW, anchor);
            let back = cam.pixel_from_world(p, VIEW).unwrap();
            assert!((back - pixel).length() < 1e-6, "{three_d}: {back}");
            if let Camera::Orbit3d(c) = cam {
                let normal = (c.target - c.eye()).normalize();
                assert!((p - anchor).dot(normal).abs() < 1e-9);
            } else {
                assert_eq!(p.z, anchor.z);
            }
        }
    }

    #[test]
    fn fitted_3d_camera_sees_every_corner_of_the_box() {
        let bbox = Aabb::from_points(&[DVec3::new(-1.0, -2.0, -3.0), DVec3::new(4.0, 1.0, 2.0)]);
        let cam = Camera::fit(bbox, VIEW, true);
        for i in 0..8 {
            let corner = DVec3::new(
                if i & 1 == 0 { bbox.min.x } else { bbox.max.x },
                if i & 2 == 0 { bbox.min.y } else { bbox.max.y },
                if i & 4 == 0 { bbox.min.z } else { bbox.max.z },
            );
            let px = cam
                .pixel_from_world(corner, VIEW)
                .expect("in front of the eye");
            assert!(
                px.x >= 0.0 && px.x <= VIEW.x && px.y >= 0.0 && px.y <= VIEW.y,
                "{px}"
            );
        }
    }
}
