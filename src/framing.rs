//! Automatic framing for files without a camera: a perspective camera that looks at the
//! model from a named [`View`] and fits the **projected vertices** (not the bounding
//! sphere), so thin, flat and elongated models fill the frame as well as compact ones.
//!
//! Frames and units: world space is glTF's (+Y up, +Z the model's front, metres; any scale
//! works, 1e-4 to 1e4 m are tested). Camera space looks down −Z with +Y up
//! ([`crate::camera`]). Fill is measured in normalised image coordinates: a point projects
//! to `(x/(−z)/tan(hfov_x), y/(−z)/tan(hfov_y))` ∈ [−1, 1]² inside the image.
//!
//! Fit (invariant): every vertex projects inside the central `FILL` fraction of the image
//! in both directions, and the extremes touch that bound in at least one direction, so the
//! projected bounding box spans `FILL` (80 %) of the image in its limiting direction
//! (width or height). Found in closed form per vertex: for a camera at distance `D` along
//! the view axis from the aim point, a vertex at lateral offset `a` and depth `z` (towards
//! the camera) projects to `a / (D − z)`; `|a| / (D − z) ≤ FILL·tan(half fov)` gives
//! `D ≥ z + |a| / (FILL·tan(half fov))`, and `D` is the largest such bound. The aim point
//! is then re-centred on the projected box (perspective makes near parts look larger), and
//! the fit is repeated a few times.

use crate::camera::look_at;
use crate::scene::desc::{CameraDesc, Projection};
use glam::{DVec3, Mat4, Vec3};

/// Vertical field of view of the automatic camera: 28°, a moderate telephoto that keeps
/// gem facets from looking distorted (a "portrait lens" look; 25–30° is common for product
/// shots).
pub const AUTO_YFOV_DEG: f32 = 28.0;
/// Fraction of the image the model's projected bounding box spans in its limiting
/// direction.
pub const FILL: f64 = 0.8;
/// Elevation of the three-quarter view above the horizon: 35°, enough to see a gem's
/// table and crown facets and the floor around it.
pub const THREEQUARTER_ELEVATION_DEG: f64 = 35.0;
/// Azimuth of the three-quarter view, from the front (+Z) towards the right (+X).
pub const THREEQUARTER_AZIMUTH_DEG: f64 = 30.0;

/// Where the automatic camera looks from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum View {
    /// From the front-right and above (35° elevation, 30° azimuth): the default.
    #[default]
    ThreeQuarter,
    /// From the front (+Z), level.
    Front,
    /// From the right (+X), level.
    Side,
    /// From above (+Y), the model's front at the bottom of the image.
    Top,
}

/// All views, in CLI order.
pub const VIEWS: [View; 4] = [View::Front, View::Top, View::Side, View::ThreeQuarter];

impl View {
    /// The CLI name (`--view`).
    pub fn name(self) -> &'static str {
        match self {
            View::ThreeQuarter => "threequarter",
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
        }
    }

    /// Parses a CLI name (case-insensitive; `three-quarter` is accepted too).
    pub fn parse(s: &str) -> crate::Result<View> {
        let key = s.trim().to_ascii_lowercase().replace(['-', '_'], "");
        VIEWS.into_iter().find(|v| v.name() == key).ok_or_else(|| {
            let names: Vec<&str> = VIEWS.iter().map(|v| v.name()).collect();
            crate::Error::Usage(format!(
                "--view {s:?}: unknown view (expected one of: {})",
                names.join(", ")
            ))
        })
    }

    /// Unit direction from the model towards the camera, and the world direction that is
    /// up in the image.
    pub fn direction(self) -> (DVec3, DVec3) {
        match self {
            View::Front => (DVec3::Z, DVec3::Y),
            View::Side => (DVec3::X, DVec3::Y),
            // Looking straight down: image up is the model's back (−Z), so its front is at
            // the bottom, as in a plan drawing.
            View::Top => (DVec3::Y, DVec3::NEG_Z),
            View::ThreeQuarter => {
                let (e, a) = (
                    THREEQUARTER_ELEVATION_DEG.to_radians(),
                    THREEQUARTER_AZIMUTH_DEG.to_radians(),
                );
                (
                    DVec3::new(e.cos() * a.sin(), e.sin(), e.cos() * a.cos()),
                    DVec3::Y,
                )
            }
        }
    }
}

/// An orthonormal camera basis: `right`, `up`, and `back` (towards the camera).
struct Basis {
    right: DVec3,
    up: DVec3,
    back: DVec3,
}

impl Basis {
    fn new(view: View) -> Self {
        let (back, up_hint) = view.direction();
        let right = up_hint.cross(back).normalize();
        Basis {
            right,
            up: back.cross(right),
            back,
        }
    }
}

/// A perspective camera (vertical fov [`AUTO_YFOV_DEG`]) that frames `points` from `view`
/// for an image of width/height `aspect` (see the module docs for the fit). Non-finite
/// points are ignored; with no finite point the unit cube around the origin is framed; a
/// model of zero extent (a single point) is framed as a sphere of radius 1e-6 of its
/// distance from the origin (at least 1e-9 m).
pub fn frame_points(points: &[Vec3], view: View, aspect: f32) -> CameraDesc {
    let aspect = if aspect.is_finite() && aspect > 1e-3 {
        f64::from(aspect).min(1e3)
    } else {
        1.0
    };
    let mut pts: Vec<DVec3> = points
        .iter()
        .filter(|p| p.is_finite())
        .map(|p| p.as_dvec3())
        .collect();
    if pts.is_empty() {
        pts = vec![DVec3::splat(-0.5), DVec3::splat(0.5)];
    }
    let basis = Basis::new(view);
    // Coordinates in the camera basis (right, up, back), about the first point.
    let origin = pts[0];
    let local: Vec<DVec3> = pts
        .iter()
        .map(|p| {
            let d = *p - origin;
            DVec3::new(d.dot(basis.right), d.dot(basis.up), d.dot(basis.back))
        })
        .collect();
    let (lo, hi) = local.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let extent = (hi - lo).max_element();
    let floor = (origin.length() * 1e-6).max(1e-9);
    let pad = if extent < floor { floor } else { 0.0 };
    let tan_y = (0.5 * f64::from(AUTO_YFOV_DEG).to_radians()).tan() * FILL;
    let tan_x = tan_y * aspect;
    // The distance that fits every vertex around the aim point `aim` (local coordinates).
    let fit = |aim: DVec3| {
        let d = local
            .iter()
            .map(|p| {
                let d = *p - aim;
                let (ax, ay) = (d.x.abs() + pad, d.y.abs() + pad);
                d.z + (ax / tan_x).max(ay / tan_y)
            })
            .fold(0.0f64, f64::max);
        // Keep the camera outside the model's depth range (never inside it).
        d.max(hi.z - aim.z + pad)
    };
    // Aim at the box centre first, then re-centre on the projected box: its centre in
    // normalised coordinates moves the aim laterally by that much at the aim's depth.
    let mut aim = 0.5 * (lo + hi);
    for _ in 0..8 {
        let dist = fit(aim);
        let (mut pl, mut ph) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in &local {
            let d = *p - aim;
            let depth = (dist - d.z).max(1e-300);
            let (sx, sy) = (d.x / depth, d.y / depth);
            pl = (pl.0.min(sx), pl.1.min(sy));
            ph = (ph.0.max(sx), ph.1.max(sy));
        }
        let shift = (0.5 * (pl.0 + ph.0) * dist, 0.5 * (pl.1 + ph.1) * dist);
        if shift.0.abs().max(shift.1.abs()) <= 1e-9 * dist {
            break;
        }
        aim.x += shift.0;
        aim.y += shift.1;
    }
    let dist = fit(aim);
    let to_world = |l: DVec3| origin + basis.right * l.x + basis.up * l.y + basis.back * l.z;
    let target = to_world(aim);
    let eye = target + basis.back * dist;
    let world_from_camera = Mat4::from_cols(
        basis.right.as_vec3().extend(0.0),
        basis.up.as_vec3().extend(0.0),
        basis.back.as_vec3().extend(0.0),
        eye.as_vec3().extend(1.0),
    );
    debug_assert!(world_from_camera.is_finite());
    CameraDesc {
        name: format!("auto-framed ({})", view.name()),
        projection: Projection::Perspective {
            yfov: AUTO_YFOV_DEG.to_radians(),
            aspect: Some(aspect as f32),
        },
        world_from_camera: if world_from_camera.is_finite() {
            world_from_camera
        } else {
            look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y)
        },
    }
}

/// The projected bounding box of `points` seen by the perspective camera `desc` in an
/// image of width/height `aspect`, in normalised image coordinates (`[−1, 1]²` is the
/// image; x right, y up): `(min, max)`, or `None` for a non-perspective camera, no points,
/// or a point behind the camera.
pub fn projected_box(points: &[Vec3], desc: &CameraDesc, aspect: f32) -> Option<(DVec3, DVec3)> {
    let Projection::Perspective { yfov, .. } = desc.projection else {
        return None;
    };
    let tan_y = (0.5 * f64::from(yfov)).tan();
    let tan_x = tan_y * f64::from(aspect);
    let camera_from_world = desc.world_from_camera.as_dmat4().inverse();
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in points.iter().filter(|p| p.is_finite()) {
        let c = camera_from_world.transform_point3(p.as_dvec3());
        if c.z >= 0.0 {
            return None;
        }
        let s = DVec3::new(c.x / -c.z / tan_x, c.y / -c.z / tan_y, 0.0);
        lo = lo.min(s);
        hi = hi.max(s);
    }
    lo.is_finite().then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxed(size: Vec3, centre: Vec3) -> Vec<Vec3> {
        (0..8)
            .map(|i| {
                let s = Vec3::new(
                    if i & 1 == 0 { -0.5 } else { 0.5 },
                    if i & 2 == 0 { -0.5 } else { 0.5 },
                    if i & 4 == 0 { -0.5 } else { 0.5 },
                );
                centre + s * size
            })
            .collect()
    }

    #[test]
    fn every_view_fills_the_frame_for_odd_shapes_and_scales() {
        let shapes = [
            Vec3::ONE,
            Vec3::new(1.0, 0.01, 1.0),  // flat plate
            Vec3::new(10.0, 0.1, 0.1),  // long rod along X
            Vec3::new(0.1, 0.1, 10.0),  // long rod along Z (end-on from the front)
            Vec3::new(0.05, 3.0, 0.05), // pole
        ];
        for scale in [1e-4f32, 1.0, 1e4] {
            for shape in shapes {
                let pts = boxed(shape * scale, Vec3::new(3.0, -2.0, 1.0) * scale);
                for view in VIEWS {
                    for aspect in [4.0 / 3.0, 0.5, 2.5] {
                        let cam = frame_points(&pts, view, aspect);
                        let (lo, hi) = projected_box(&pts, &cam, aspect).expect("in front");
                        let span = (hi - lo).max_element() * 0.5;
                        // The closed-form fit is exact up to f32 rounding of the matrix;
                        // 1e-3 covers it at every scale.
                        assert!(
                            (span - FILL).abs() < 1e-3,
                            "{view:?} {shape} ×{scale} aspect {aspect}: span {span}"
                        );
                        let centre = 0.5 * (lo + hi);
                        assert!(centre.abs().max_element() < 2e-3, "off centre {centre}");
                        assert!(lo.min_element() >= -1.0 && hi.max_element() <= 1.0);
                    }
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_give_a_finite_camera() {
        for pts in [
            vec![],
            vec![Vec3::new(1.0, 2.0, 3.0)],
            vec![Vec3::NAN, Vec3::ZERO, Vec3::INFINITY],
        ] {
            let cam = frame_points(&pts, View::ThreeQuarter, 1.5);
            assert!(cam.world_from_camera.is_finite());
        }
    }

    #[test]
    fn views_parse_and_look_from_where_they_say() {
        assert_eq!(View::parse("Three-Quarter").unwrap(), View::ThreeQuarter);
        assert_eq!(View::parse("top").unwrap(), View::Top);
        assert!(View::parse("bottom").is_err());
        let pts = boxed(Vec3::ONE, Vec3::ZERO);
        let eye = |v| {
            frame_points(&pts, v, 1.0)
                .world_from_camera
                .transform_point3(Vec3::ZERO)
        };
        assert!(eye(View::Front).z > 1.0 && eye(View::Front).x.abs() < 1e-4);
        assert!(eye(View::Side).x > 1.0 && eye(View::Side).z.abs() < 1e-4);
        assert!(eye(View::Top).y > 1.0);
        // The view direction (camera +Z, towards the camera), not the eye position: the aim
        // point is re-centred on the projected box, off the box centre.
        let e = frame_points(&pts, View::ThreeQuarter, 1.0)
            .world_from_camera
            .transform_vector3(Vec3::Z);
        let elevation = (e.y / e.length()).asin().to_degrees();
        assert!((elevation - 35.0).abs() < 0.1, "elevation {elevation}");
        assert!(e.x > 0.0 && e.z > e.x);
    }
}
