//! Pinhole camera with analytic ray differentials (Igehy 1999).

use crate::scene::{Hit, Lod, Ray};
use glam::Vec3;

/// A pinhole camera looking from `eye` at `target`, image `width x height` pixels.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: Vec3,
    /// Change of the unnormalised ray direction per pixel step in x and y.
    step_x: Vec3,
    step_y: Vec3,
    /// Unnormalised direction through the image corner (0, 0).
    corner: Vec3,
}

/// A primary ray and the derivatives of its unit direction per pixel step.
#[derive(Clone, Copy, Debug)]
pub struct DiffRay {
    pub ray: Ray,
    pub d_dir_dx: Vec3,
    pub d_dir_dy: Vec3,
}

impl Camera {
    pub fn new(eye: Vec3, target: Vec3, vfov_deg: f32, width: usize, height: usize) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let half_h = (0.5 * vfov_deg.to_radians()).tan();
        let half_w = half_h * width as f32 / height as f32;
        let step_x = right * (2.0 * half_w / width as f32);
        let step_y = -up * (2.0 * half_h / height as f32);
        let corner = forward - right * half_w + up * half_h;
        Self {
            eye,
            step_x,
            step_y,
            corner,
        }
    }

    /// The ray through the continuous image point `(x, y)` (pixel centres at `i + 0.5`), with
    /// Igehy's direction differentials `dD/dx = (d.d s - (d.s) d) / |d|^3`.
    pub fn ray(&self, x: f32, y: f32) -> DiffRay {
        let d = self.corner + x * self.step_x + y * self.step_y;
        let len = d.length();
        let dir = d / len;
        let diff = |s: Vec3| (s - dir * dir.dot(s)) / len;
        DiffRay {
            ray: Ray {
                origin: self.eye,
                dir,
            },
            d_dir_dx: diff(self.step_x),
            d_dir_dy: diff(self.step_y),
        }
    }

    /// The angle one pixel subtends at the image centre (radians).
    pub fn pixel_angle(&self) -> f32 {
        self.step_y.length()
    }

    /// The water's level of detail for this view.
    pub fn lod(&self) -> Lod {
        Lod {
            eye: self.eye,
            pixel_angle: self.pixel_angle(),
        }
    }
}

/// What the GPU demonstration (`highlights_gpu`) needs of the camera: its rays as
/// a linear function of the pixel, and the projection of world points (for scissor rects).
#[allow(dead_code)] // the CPU demonstration traces `Camera::ray` instead
impl Camera {
    /// The unnormalised direction through the image corner `(0, 0)` and its change per pixel
    /// step in x and y: the ray through `(x, y)` is `corner + x step_x + y step_y`.
    pub fn basis(&self) -> [Vec3; 3] {
        [self.corner, self.step_x, self.step_y]
    }

    /// The continuous image point of the world point `p`, if it lies at least `near` in
    /// front of the eye (along the view axis).
    pub fn project(&self, p: Vec3, near: f32) -> Option<(f32, f32)> {
        // The view axis `forward` is the direction through the image centre; `corner` and
        // the steps differ from it by vectors orthogonal to it, so `corner . forward = 1`.
        let forward = self.forward();
        let v = p - self.eye;
        let depth = v.dot(forward);
        if depth < near {
            return None;
        }
        let d = v / depth - self.corner;
        Some((
            d.dot(self.step_x) / self.step_x.length_squared(),
            d.dot(self.step_y) / self.step_y.length_squared(),
        ))
    }

    /// The unit view axis.
    fn forward(&self) -> Vec3 {
        let right = self.step_x.normalize();
        let down = self.step_y.normalize();
        (self.corner - right * self.corner.dot(right) - down * self.corner.dot(down)).normalize()
    }
}

/// The camera of frame `k` of the temporal test (frame 0 is the still image), shared by the
/// CPU and GPU demonstrations: a slow sideways and forward dolly, a fraction of a pixel's
/// footprint on the far water per frame.
pub fn camera_at(frame: usize, width: usize, height: usize) -> Camera {
    let k = frame as f32;
    let eye = Vec3::new(0.004 * k, 1.6, 4.0 - 0.01 * k);
    Camera::new(eye, eye + Vec3::new(0.0, -0.14, -1.0), 38.0, width, height)
}

impl DiffRay {
    /// Igehy's transfer to the hit's tangent plane: `dP = t dD + dt D` with
    /// `dt = -(t dD . n) / (D . n)` (the origin differential is zero for a pinhole).
    /// Returns `(dx_u, dx_v)`, the world offsets per pixel step in x and y.
    #[allow(dead_code)]
    pub fn footprint_on_plane(&self, hit: &Hit) -> (Vec3, Vec3) {
        let dn = self.ray.dir.dot(hit.normal);
        let transfer = |dd: Vec3| {
            let dp = hit.t * dd;
            let dt = if dn.abs() > 1e-6 {
                -dp.dot(hit.normal) / dn
            } else {
                0.0
            };
            dp + dt * self.ray.dir
        };
        (transfer(self.d_dir_dx), transfer(self.d_dir_dy))
    }
}
