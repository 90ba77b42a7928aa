//! `--camera-look-at EX,EY,EZ:TX,TY,TZ:FOV`: a perspective camera at the eye E looking at
//! the target T, with a vertical field of view of FOV degrees and +Y up (the live view's
//! orbit camera, [`crate::view`], written so that a shell command reproduces it).
//!
//! Scene units and world space, as the file's. The text round-trips exactly: [`LookAt`]'s
//! `Display` writes each `f32` with the fewest digits that parse back to the same value,
//! so a camera printed by the view and parsed by `iris render` is the same bits.
//!
//! When the view direction is within 10⁻³ rad of ±Y (looking straight down or up), "up"
//! is −Z (looking down) or +Z (looking up) instead: the image's up is then the direction
//! the camera would tilt towards.

use crate::scene::desc::{CameraDesc, Projection};
use glam::Vec3;

/// Smallest and largest vertical field of view, degrees.
pub const FOV_RANGE: (f32, f32) = (0.1, 170.0);

/// A look-at camera (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LookAt {
    /// Eye position, world space.
    pub eye: Vec3,
    /// The point looked at, world space (not the eye).
    pub target: Vec3,
    /// Vertical field of view, degrees, within [`FOV_RANGE`].
    pub fov_deg: f32,
}

impl LookAt {
    /// Parses `EX,EY,EZ:TX,TY,TZ:FOV`; the error says what is wrong.
    pub fn parse(text: &str) -> Result<LookAt, String> {
        let parts: Vec<&str> = text.split(':').map(str::trim).collect();
        let [eye, target, fov] = parts[..] else {
            return Err(format!(
                "expected EX,EY,EZ:TX,TY,TZ:FOV (eye, target, vertical field of view in \
                 degrees), got {text:?}"
            ));
        };
        let point = |what: &str, s: &str| -> Result<Vec3, String> {
            let v: Vec<f32> = s
                .split(',')
                .map(|c| c.trim().parse::<f32>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("the {what} {s:?} is not three numbers"))?;
            match v[..] {
                [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(Vec3::new(x, y, z)),
                _ => Err(format!("the {what} {s:?} is not three finite numbers")),
            }
        };
        let look = LookAt {
            eye: point("eye", eye)?,
            target: point("target", target)?,
            fov_deg: fov
                .parse::<f32>()
                .map_err(|_| format!("the field of view {fov:?} is not a number"))?,
        };
        look.check()?;
        Ok(look)
    }

    /// The invariants of the module docs.
    pub fn check(&self) -> Result<(), String> {
        let (lo, hi) = FOV_RANGE;
        if !(self.fov_deg >= lo && self.fov_deg <= hi) {
            return Err(format!(
                "the field of view {} is outside {lo} to {hi} degrees",
                self.fov_deg
            ));
        }
        if !self.eye.is_finite() || !self.target.is_finite() {
            return Err("the eye and the target must be finite".into());
        }
        if self.forward().is_none() {
            return Err("the eye and the target are the same point".into());
        }
        Ok(())
    }

    /// The unit view direction, from the eye to the target, taken in f64 and normalised
    /// safely ([`crate::math::unit_direction`]: any two distinct finite points give one);
    /// `None` when they are the same point.
    fn forward(&self) -> Option<Vec3> {
        crate::math::unit_direction(self.target.as_dvec3() - self.eye.as_dvec3()).ok()
    }

    /// The camera: perspective, looking down its local −Z (glTF), the aspect from the image.
    pub fn camera(&self) -> CameraDesc {
        let forward = self.forward().unwrap_or(Vec3::NEG_Z);
        let up = if forward.y.abs() > (1.0f32 - 5e-7) {
            Vec3::new(0.0, 0.0, forward.y.signum())
        } else {
            Vec3::Y
        };
        CameraDesc {
            name: "look-at".into(),
            projection: Projection::Perspective {
                yfov: self.fov_deg.to_radians(),
                aspect: None,
            },
            world_from_camera: crate::camera::look_at(self.eye, self.target, up),
        }
    }
}

impl std::fmt::Display for LookAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (e, t) = (self.eye, self.target);
        write!(
            f,
            "{},{},{}:{},{},{}:{}",
            e.x, e.y, e.z, t.x, t.y, t.z, self.fov_deg
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_bit_for_bit() {
        let look = LookAt {
            eye: Vec3::new(0.1 + 0.2, -1.0e-7, 3.456_789),
            target: Vec3::new(1.0 / 3.0, 0.0, -2.5),
            fov_deg: 39.597_75,
        };
        let back = LookAt::parse(&look.to_string()).unwrap();
        assert_eq!(
            back.eye.to_array().map(f32::to_bits),
            look.eye.to_array().map(f32::to_bits)
        );
        assert_eq!(back.target, look.target);
        assert_eq!(back.fov_deg.to_bits(), look.fov_deg.to_bits());
    }

    #[test]
    fn camera_looks_at_the_target_with_y_up() {
        let look = LookAt::parse("0,1,5:0,1,0:40").unwrap();
        let cam = look.camera();
        let m = cam.world_from_camera;
        assert!((m.transform_vector3(-Vec3::Z) - -Vec3::Z).length() < 1e-6);
        assert!((m.transform_vector3(Vec3::Y) - Vec3::Y).length() < 1e-6);
        assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(0.0, 1.0, 5.0)).length() < 1e-6);
        // Straight down: up is −Z, the frame stays orthonormal.
        let down = LookAt::parse("0,5,0:0,0,0:30")
            .unwrap()
            .camera()
            .world_from_camera;
        let (r, u, b) = (
            down.x_axis.truncate(),
            down.y_axis.truncate(),
            down.z_axis.truncate(),
        );
        assert!(r.dot(u).abs() < 1e-6 && u.dot(b).abs() < 1e-6 && r.is_normalized());
        assert!((u - -Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn bad_text_is_refused_with_the_reason() {
        for (text, says) in [
            ("1,2,3:4,5,6", "expected EX,EY,EZ"),
            ("1,2:4,5,6:40", "eye"),
            ("1,2,3:4,x,6:40", "target"),
            ("1,2,3:1,2,3:40", "same point"),
            ("1,2,3:4,5,6:0", "field of view"),
            ("1,2,3:4,5,6:nan", "field of view"),
            ("1,2,inf:4,5,6:40", "eye"),
        ] {
            let e = LookAt::parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
        }
    }

    /// Eyes and targets whose f32 difference would overflow or underflow when squared
    /// still look from the eye to the target.
    #[test]
    fn far_and_near_targets_look_the_right_way() {
        let diagonal = Vec3::new(1.0, 1.0, 0.0) / 2f32.sqrt();
        for (text, forward) in [
            ("0,0,0:3e38,3e38,0:40", diagonal),
            ("-3e38,-3e38,0:3e38,3e38,0:40", diagonal),
            ("0,0,0:1e-30,1e-30,0:40", diagonal),
            ("0,0,0:1e-45,0,0:40", Vec3::X),
        ] {
            let look = LookAt::parse(text).unwrap();
            let m = look.camera().world_from_camera;
            let f = -m.z_axis.truncate();
            assert!((f - forward).length() < 1e-6, "{text}: {f}");
            assert!(m.is_finite(), "{text}: {m}");
        }
    }
}
