//! Cameras: glTF perspective and orthographic projections. Automatic framing for files
//! without a camera is [`crate::framing`].
//! Camera space is glTF's: looking down −Z, +Y up. Raster coordinates have (0,0) at the top-left
//! corner of the image, x right, y down, in pixels.

use crate::math::Ray;
use crate::scene::desc::{CameraDesc, Projection};
use glam::{Mat4, Vec2, Vec3};

/// A camera ready to generate rays for one image size.
#[derive(Debug, Clone)]
pub struct Camera {
    world_from_camera: Mat4,
    projection: Projection,
    /// tan(yfov/2) for perspective; ymag for orthographic.
    half_height: f32,
    /// half_height × aspect.
    half_width: f32,
    width: u32,
    height: u32,
    /// Inverse of `world_from_camera` (for projecting world points, [`Camera::project`]).
    camera_from_world: Mat4,
}

/// A world point seen by a perspective camera ([`Camera::project`]).
#[derive(Debug, Clone, Copy)]
pub struct Projected {
    /// Raster position (pixels, (0,0) top-left), inside the image.
    pub raster: Vec2,
    /// The camera's position (the pinhole), world space.
    pub eye: Vec3,
    /// cos θ between the camera's viewing axis and the direction to the point.
    pub cos_theta: f32,
    /// Area of one pixel on the image plane at unit distance from the pinhole (camera
    /// space units²): (2 tan(xfov/2) / width) · (2 tan(yfov/2) / height).
    pub pixel_area: f32,
}

impl Camera {
    /// The image's right and up directions (world, unit): the camera frame's x and y.
    pub fn basis(&self) -> (Vec3, Vec3) {
        let right = self.world_from_camera.x_axis.truncate().normalize_or_zero();
        let up = self.world_from_camera.y_axis.truncate().normalize_or_zero();
        (right, up)
    }

    /// The projection (perspective or orthographic) the camera was built from.
    pub fn projection(&self) -> &Projection {
        &self.projection
    }

    /// Builds the camera for a `width × height` image. The image aspect wins over the
    /// file's aspect ratio; the vertical extent (yfov or ymag) is kept.
    pub fn new(desc: &CameraDesc, width: u32, height: u32) -> Self {
        let aspect = width as f32 / height.max(1) as f32;
        let half_height = match desc.projection {
            Projection::Perspective { yfov, .. } => (0.5 * yfov).tan(),
            Projection::Orthographic { ymag, .. } => ymag.abs(),
        };
        Camera {
            world_from_camera: desc.world_from_camera,
            projection: desc.projection,
            half_height,
            half_width: half_height * aspect,
            width,
            height,
            camera_from_world: desc.world_from_camera.inverse(),
        }
    }

    /// Whether rays leave from one point (a pinhole): only then can a light path be
    /// connected to the camera ([`Camera::project`]).
    pub fn is_perspective(&self) -> bool {
        matches!(self.projection, Projection::Perspective { .. })
    }

    /// Where the world point `p` lands on the image of a perspective camera (the inverse of
    /// [`Camera::generate_ray`]): `None` for an orthographic camera (no ray through a
    /// given point reaches a pinhole), a point behind the camera or outside the image.
    pub fn project(&self, p: Vec3) -> Option<Projected> {
        if !self.is_perspective() {
            return None;
        }
        let q = self.camera_from_world.transform_point3(p);
        if q.z >= 0.0 || q.z.is_nan() {
            return None;
        }
        let (ndc_x, ndc_y) = (q.x / -q.z, q.y / -q.z);
        let (w, h) = (self.width as f32, self.height as f32);
        let raster = Vec2::new(
            (ndc_x / self.half_width + 1.0) * 0.5 * w,
            (1.0 - ndc_y / self.half_height) * 0.5 * h,
        );
        if !(raster.x >= 0.0 && raster.y >= 0.0 && raster.x < w && raster.y < h) {
            return None;
        }
        Some(Projected {
            raster,
            eye: self.world_from_camera.transform_point3(Vec3::ZERO),
            cos_theta: -q.z / q.length(),
            pixel_area: (2.0 * self.half_width / w) * (2.0 * self.half_height / h),
        })
    }

    /// The ray through raster position `px` (pixels, fractional).
    pub fn generate_ray(&self, px: Vec2) -> Ray {
        let ndc_x = (2.0 * px.x / self.width as f32 - 1.0) * self.half_width;
        let ndc_y = (1.0 - 2.0 * px.y / self.height as f32) * self.half_height;
        match self.projection {
            Projection::Perspective { .. } => {
                let d = Vec3::new(ndc_x, ndc_y, -1.0).normalize();
                Ray::new(
                    self.world_from_camera.transform_point3(Vec3::ZERO),
                    self.world_from_camera.transform_vector3(d).normalize(),
                )
            }
            Projection::Orthographic { .. } => Ray::new(
                self.world_from_camera
                    .transform_point3(Vec3::new(ndc_x, ndc_y, 0.0)),
                self.world_from_camera
                    .transform_vector3(Vec3::NEG_Z)
                    .normalize(),
            ),
        }
    }
}

/// World-from-camera matrix of a camera at `eye` looking at `target` (camera −Z forward;
/// −Z itself when they coincide). The view direction is the f64 difference normalised
/// safely ([`crate::math::unit_direction`]), so eyes and targets 1e-30 or 1e38 apart
/// look the right way.
pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    let f = crate::math::unit_direction(target.as_dvec3() - eye.as_dvec3()).unwrap_or(Vec3::NEG_Z);
    let right = f
        .cross(up)
        .try_normalize()
        .unwrap_or_else(|| f.any_orthonormal_vector());
    let y = right.cross(f);
    Mat4::from_cols(
        right.extend(0.0),
        y.extend(0.0),
        (-f).extend(0.0),
        eye.extend(1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tilted(width: u32, height: u32) -> Camera {
        let desc = CameraDesc {
            name: "cam".into(),
            projection: Projection::Perspective {
                yfov: 0.9,
                aspect: None,
            },
            world_from_camera: look_at(
                Vec3::new(0.3, 1.1, 2.0),
                Vec3::new(-0.2, 0.0, -0.4),
                Vec3::Y,
            ),
        };
        Camera::new(&desc, width, height)
    }

    /// A point on the ray through raster position `px` projects back to `px`, so a light
    /// path's splat lands in the pixel whose camera rays reach its vertex — also a hair
    /// inside a pixel's edge, where a half-pixel convention slip would change the pixel.
    #[test]
    fn project_inverts_generate_ray_up_to_the_pixel_edges() {
        let cam = tilted(48, 36);
        for (x, y) in [(0, 0), (7, 30), (23, 17), (47, 35), (40, 2)] {
            for (fx, fy) in [(1e-3, 1e-3), (0.5, 0.5), (0.999, 0.001), (0.001, 0.999)] {
                let px = Vec2::new(x as f32 + fx, y as f32 + fy);
                let ray = cam.generate_ray(px);
                let pr = cam.project(ray.origin + ray.dir * 2.7).expect("in view");
                assert!(
                    (pr.raster - px).abs().max_element() < 2e-4,
                    "{px} -> {}",
                    pr.raster
                );
                assert_eq!((pr.raster.x as u32, pr.raster.y as u32), (x, y));
                assert!((pr.eye - ray.origin).length() < 1e-5);
            }
        }
    }

    /// Solid angle of the triangle of unit directions a, b, c (Van Oosterom & Strackee
    /// 1983, IEEE Trans. Biomed. Eng. 30(2)).
    fn triangle_solid_angle(a: Vec3, b: Vec3, c: Vec3) -> f64 {
        let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
        let num = a.dot(b.cross(c)).abs();
        let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
        2.0 * num.atan2(den)
    }

    /// The pinhole importance's pixel factor: a pixel subtends `pixel_area · cos³θ`
    /// steradians (pbrt-v4 `PerspectiveCamera::PDF_We`: the image-plane area element at
    /// unit distance is dω / cos³θ), checked against the exact solid angle of the pixel's
    /// four corner rays, at the centre and in a corner of the image.
    #[test]
    fn pixel_area_times_cos_cubed_is_the_pixel_solid_angle() {
        let cam = tilted(48, 36);
        for (x, y) in [(24, 18), (0, 0), (47, 30)] {
            let corner = |dx: f32, dy: f32| {
                cam.generate_ray(Vec2::new(x as f32 + dx, y as f32 + dy))
                    .dir
            };
            let (a, b, c, d) = (
                corner(0., 0.),
                corner(1., 0.),
                corner(1., 1.),
                corner(0., 1.),
            );
            let exact = triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, d);
            let mid = cam.generate_ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            let pr = cam.project(mid.origin + mid.dir).expect("in view");
            let approx = f64::from(pr.pixel_area) * f64::from(pr.cos_theta).powi(3);
            assert!(
                (approx / exact - 1.0).abs() < 2e-3,
                "pixel ({x}, {y}): {approx:e} sr vs exact {exact:e} sr"
            );
        }
    }
}
