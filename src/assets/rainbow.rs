//! `scenes/fig5_3_1_rainbow.glb`: the prism rainbow (Fig. 5.3.1) of Cropp & Zhang, "Light
//! Refraction with Dispersion", as a caustic of a delta light: a horizontal sun through a slit and an N-BK7 prism onto a white
//! screen, for the photon mapper (the path tracer cannot reach a directional light
//! through glass, so it shows the screen dark).
//!
//! Units are metres, +Y up, lux. Every mesh is in world space (no node translation);
//! geometry is computed in `f64` and rounded to `f32` once (bit-identical files).
//!
//! Geometry (top view; everything happens in the horizontal plane y = [`RAINBOW_Y`]):
//! - prism: [`upright_prism`] of side [`PRISM_SIDE`] (apex towards +Z, centroid on the Y
//!   axis), 0.1 m tall, 1 mm above a white (0.8) floor; material `extras.iris_glass:
//!   "N-BK7"`, fallback `KHR_materials_ior` 1.5168, transmission 1, volume 0.1;
//! - sun: a narrow spot light ([`SUN_CONE_DEG`] half-angle) [`SUN_DISTANCE`] upstream of the
//!   slit, giving [`SUN_LUX`] lx there, `extras.iris_spectrum: "sun"`, pointing
//!   horizontally along `dir_in` = (cos 19.32°, 0, sin 19.32°): the incidence of minimum
//!   deviation on the prism's −X face for n_d = 1.5168 (sin θ₁ = n_d sin 30°, θ₁ =
//!   49.323°, deviation D = 2θ₁ − 60° = 38.647°; Born & Wolf, "Principles of Optics",
//!   §4.7.2). Horizontal, it gives the floor no direct light;
//! - baffle: an opaque black (0.02) plate perpendicular to `dir_in`, 0.25 m before the
//!   entry point (−side/3, y, 0), from y = 0 to 0.4 and from 0.2 m to one side to 1.05 m
//!   to the other of the axis, so its shadow covers the prism and the screen; a slit of
//!   [`SLIT_WIDTH`] × [`SLIT_HEIGHT`] centred on the axis lets a parallel beam through to
//!   the middle of the −X face;
//! - screen: white (0.85) 0.4 × 0.25 m, standing on the floor, perpendicular to the
//!   587.56 nm exit ray (`dir_out` = (cos 19.32°, 0, −sin 19.32°)), facing back along it,
//!   its centre [`RAINBOW_SCREEN_DISTANCE`] = 1.2 m along it from the exit point
//!   (side/3, y, 0);
//! - fill: a directional light of [`FILL_LUX`] lx from above, so the set is visible;
//! - camera: 0.5 m up and 1.3 m along −`dispersion` from the point 0.6 m down the beam
//!   from the exit, looking at that point (at y = 0.02), so the prism is on the left and the
//!   screen on the right (yfov 40°, 16:9).
//!
//! Expected path (the axis ray; N-BK7 Sellmeier from [`crate::spectrum::IorModel`]): at
//! n_d the ray runs inside along +X and hits the screen at its centre. Deviation and
//! landing point along [`RainbowLayout::dispersion`] (from the screen centre):
//!
//! | λ (nm) | n | deviation | along `dispersion` |
//! |---|---|---|---|
//! | 430 (violet) | 1.52729 | 39.576° | +19.7 mm |
//! | 486.13 (F) | 1.52238 | 39.139° | +10.4 mm |
//! | 587.56 (d) | 1.51680 | 38.647° | 0 |
//! | 656.27 (C, red) | 1.51432 | 38.429° | −4.6 mm |
//!
//! so violet lands 24.3 mm beyond red along `dispersion` = `Y × dir_out` (horizontal, in
//! the screen plane, towards −Z): more deviation turns the beam further about +Y. Each
//! colour's band is the slit's width (3 mm) wide. The exit points differ by < 0.4 mm.
//!
//! Photon budget: the sun is a distant spot rather than a directional light so that its
//! photons are aimed at the slit: its cone covers a disc of radius ≈ 2.8 cm at the slit,
//! of which the slit (1.2·10⁻⁴ m²) passes ≈ 5 % (a directional light's photons start on
//! the scene's bounding disc, ≈ 4 m², and ≈ 3·10⁻⁵ of them would pass). Its rays diverge
//! by at most the slit's size over 4 m (< 0.6 mrad, less than the real sun's 9 mrad).

use super::parts::{add_mesh, camera};
use super::spectral::{upright_prism, BeamLayout, N_D_BK7};
use crate::authoring::shapes::TriMesh;
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::SceneDesc;
use crate::spectrum::EmissionSpectrum;
use glam::{DVec3, Vec3};

/// Side of the prism's equilateral cross-section, metres.
pub const PRISM_SIDE: f64 = 0.1;
/// Height of the beam plane (the prism's mid-height), metres.
pub const RAINBOW_Y: f64 = 0.051;
/// Full width of the slit, metres.
pub const SLIT_WIDTH: f64 = 0.003;
/// Full height of the slit, metres.
pub const SLIT_HEIGHT: f64 = 0.04;
/// Distance from the slit to the prism's entry point along the beam, metres.
pub const SLIT_DISTANCE: f64 = 0.25;
/// Distance from the exit point to the screen centre along the 587.56 nm exit ray, metres.
pub const RAINBOW_SCREEN_DISTANCE: f64 = 1.2;
/// Illuminance of the sun at the slit, lux.
pub const SUN_LUX: f32 = 20.0;
/// Distance of the sun (a spot light) upstream of the slit, metres.
pub const SUN_DISTANCE: f64 = 4.0;
/// Outer cone half-angle of the sun spot, degrees (inner: 7/8 of it).
pub const SUN_CONE_DEG: f32 = 0.4;
/// Illuminance of the dim fill from above, lux.
pub const FILL_LUX: f32 = 0.02;
/// The red of the module doc (C line), nm.
pub const LAMBDA_RED: f64 = 656.27;
/// The violet of the module doc, nm.
pub const LAMBDA_VIOLET: f64 = 430.0;

/// Where the beam goes in [`fig5_3_1_rainbow`] (all in world space).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RainbowLayout {
    /// Centre of the slit.
    pub slit: DVec3,
    /// Where the axis meets the prism's −X face.
    pub entry: DVec3,
    /// Where the axis leaves the +X face at n_d (430–656 nm: within 0.4 mm).
    pub exit: DVec3,
    /// Direction the sun's light travels (unit, horizontal).
    pub dir_in: DVec3,
    /// Exit direction at n_d (unit, horizontal).
    pub dir_out: DVec3,
    /// Screen centre: a point of the screen plane.
    pub screen_centre: DVec3,
    /// The screen's unit normal (facing the prism, = −`dir_out`).
    pub screen_normal: DVec3,
    /// Unit vector in the screen plane along which shorter wavelengths (more deviation)
    /// land further: `Y × dir_out`.
    pub dispersion: DVec3,
}

/// Outward unit normals of the prism's −X and +X faces, and a point of the +X face.
fn faces() -> (DVec3, DVec3, DVec3) {
    let c30 = 3.0f64.sqrt() / 2.0;
    let h = PRISM_SIDE * c30;
    (
        DVec3::new(-c30, 0.0, 0.5),
        DVec3::new(c30, 0.0, 0.5),
        DVec3::new(PRISM_SIDE / 2.0, RAINBOW_Y, -h / 3.0),
    )
}

/// The layout of [`fig5_3_1_rainbow`].
pub fn rainbow_layout() -> RainbowLayout {
    let b = BeamLayout::minimum_deviation();
    let at_y = |p: DVec3| DVec3::new(p.x, RAINBOW_Y, p.z);
    let (entry, exit) = (at_y(b.entry), at_y(b.exit));
    RainbowLayout {
        slit: entry - SLIT_DISTANCE * b.dir_in,
        entry,
        exit,
        dir_in: b.dir_in,
        dir_out: b.dir_out,
        screen_centre: exit + RAINBOW_SCREEN_DISTANCE * b.dir_out,
        screen_normal: -b.dir_out,
        dispersion: DVec3::Y.cross(b.dir_out).normalize(),
    }
}

/// Refracts unit `d` at a surface with unit normal `n` facing against `d`, `eta` =
/// n_incident / n_transmitted (vector Snell's law, pbrt-v4 §9.3); `None` on total internal
/// reflection.
fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    (sin2_t < 1.0).then(|| eta * d + (eta * cos_i - (1.0 - sin2_t).sqrt()) * n)
}

/// The beam axis through the prism for glass index `n`: (exit point, exit direction,
/// landing point on the screen plane); `None` on total internal reflection or if `n` is
/// not finite and > 1.
pub fn rainbow_landing(n: f64) -> Option<(DVec3, DVec3, DVec3)> {
    if !n.is_finite() || n <= 1.0 {
        return None;
    }
    let l = rainbow_layout();
    let (n_in, n_out, on_out) = faces();
    let inside = refract(l.dir_in, n_in, 1.0 / n)?;
    let exit = l.entry + (on_out - l.entry).dot(n_out) / inside.dot(n_out) * inside;
    let out = refract(inside, -n_out, n)?;
    let s = (l.screen_centre - exit).dot(l.screen_normal) / out.dot(l.screen_normal);
    Some((exit, out, exit + s * out))
}

/// Pushes the rectangle `c ± a ± b` facing `a × b`, with its flat normal.
fn rect(mesh: &mut TriMesh, c: DVec3, a: DVec3, b: DVec3) {
    let n = a.cross(b).normalize().as_vec3();
    let base = mesh.positions.len() as u32;
    for p in [c - a - b, c + a - b, c + a + b, c - a + b] {
        mesh.positions.push(p.as_vec3());
        mesh.normals.push(n);
    }
    mesh.indices.push([base, base + 1, base + 2]);
    mesh.indices.push([base, base + 2, base + 3]);
}

/// Fig. 5.3.1 as a caustic: a horizontal sun through a slit and an N-BK7 prism throws a
/// rainbow on a white screen 1.2 m away.
pub fn fig5_3_1_rainbow() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Fig. 5.3.1: sunlight through a slit and a prism, rainbow on a screen".into(),
        ..SceneDesc::default()
    };
    let l = rainbow_layout();
    let mut floor = TriMesh::default();
    let (fc, fx, fz) = (DVec3::new(0.475, 0.0, -0.45), 0.875, 0.7);
    rect(&mut floor, fc, fz * DVec3::Z, fx * DVec3::X);
    let floor_material = MaterialDesc::diffuse("Floor", Vec3::splat(0.8));
    add_mesh(&mut s, "Floor", floor, floor_material, None);

    let glass = MaterialDesc::named_glass("Prism N-BK7", "N-BK7", N_D_BK7 as f32, 0.1);
    let prism = upright_prism(PRISM_SIDE, RAINBOW_Y - 0.05, 0.1);
    add_mesh(&mut s, "Prism", prism, glass, None);

    // Baffle facing the sun (Y × u = −dir_in with u = Y × dir_in), made of four strips
    // around the slit: u from −0.2 to 1.05 m, y from 0 to 0.4 m.
    let u = DVec3::Y.cross(l.dir_in);
    let (w, h) = (SLIT_WIDTH / 2.0, SLIT_HEIGHT / 2.0);
    let (u0, u1, top) = (-0.2, 1.05, 0.4);
    let at = |du: f64, y: f64| DVec3::new(l.slit.x, y, l.slit.z) + du * u;
    let mut baffle = TriMesh::default();
    let strips = [
        (u0, -w, 0.0, top),
        (w, u1, 0.0, top),
        (-w, w, 0.0, RAINBOW_Y - h),
        (-w, w, RAINBOW_Y + h, top),
    ];
    for (a, b, y0, y1) in strips {
        let c = at((a + b) / 2.0, (y0 + y1) / 2.0);
        rect(
            &mut baffle,
            c,
            (y1 - y0) / 2.0 * DVec3::Y,
            (b - a) / 2.0 * u,
        );
    }
    let black = MaterialDesc::diffuse("Baffle", Vec3::splat(0.02));
    add_mesh(&mut s, "Slit baffle", baffle, black, None);

    // Screen facing −dir_out: Y × (Y × dir_out) = −dir_out (dir_out is horizontal).
    let mut screen = TriMesh::default();
    let c = DVec3::new(l.screen_centre.x, 0.125, l.screen_centre.z);
    rect(&mut screen, c, 0.125 * DVec3::Y, 0.2 * l.dispersion);
    let white = MaterialDesc::diffuse("Screen", Vec3::splat(0.85));
    add_mesh(&mut s, "Screen", screen, white, None);

    s.lights.push(LightDesc::Spot {
        name: "Sun".into(),
        position: (l.slit - SUN_DISTANCE * l.dir_in).as_vec3(),
        direction: l.dir_in.as_vec3(),
        color: Vec3::ONE,
        // E = I / d² at the slit.
        intensity: SUN_LUX * (SUN_DISTANCE * SUN_DISTANCE) as f32,
        inner_cone: (SUN_CONE_DEG * 0.875).to_radians(),
        outer_cone: SUN_CONE_DEG.to_radians(),
        range: None,
        spectrum: Some(EmissionSpectrum::Sun),
    });
    s.lights.push(LightDesc::Directional {
        name: "Fill".into(),
        direction: Vec3::new(0.3, -1.0, 0.2),
        color: Vec3::ONE,
        intensity: FILL_LUX,
        spectrum: None,
    });

    // From the side opposite the dispersion, across from the middle of the beam's path.
    let middle = l.exit + 0.6 * l.dir_out;
    let eye = middle - 1.3 * l.dispersion + DVec3::new(0.0, 0.5, 0.0);
    let target = DVec3::new(middle.x, 0.02, middle.z);
    s.cameras
        .push(camera(eye.as_vec3(), target.as_vec3(), 40.0, 16.0 / 9.0));
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::IorModel;

    #[test]
    fn violet_lands_beyond_red_along_the_dispersion_direction() {
        let glass = IorModel::named("N-BK7").expect("known");
        let l = rainbow_layout();
        let land = |nm: f64| rainbow_landing(f64::from(glass.ior(nm as f32))).expect("passes");
        // At n_d the axis ray meets the screen centre (1e-5 m: the Sellmeier n_d differs
        // from 1.5168 by 1e-7, moving the landing point by ≈ 2e-7 m).
        let (exit_d, _, mid) = land(587.56);
        assert!((mid - l.screen_centre).length() < 1e-5, "{mid}");
        assert!((exit_d - l.exit).length() < 1e-5, "{exit_d}");
        // The doc's table, to 0.1 mm.
        let along = |nm: f64| (land(nm).2 - l.screen_centre).dot(l.dispersion);
        let (violet, red) = (along(LAMBDA_VIOLET), along(LAMBDA_RED));
        assert!((violet - 0.0197).abs() < 1e-4, "violet {violet}");
        assert!((red + 0.0046).abs() < 1e-4, "red {red}");
        assert!((along(486.13) - 0.0104).abs() < 1e-4);
        // Exit points differ by 0.37 mm (violet vs red); the dispersion direction lies in
        // the screen plane.
        assert!((land(LAMBDA_VIOLET).0 - land(LAMBDA_RED).0).length() < 4e-4);
        assert!(l.dispersion.dot(l.screen_normal).abs() < 1e-12);
        assert!(l.dispersion.z < 0.0);
    }

    #[test]
    fn screen_faces_the_prism_and_baffle_faces_the_sun() {
        let s = fig5_3_1_rainbow();
        crate::authoring::scene::validate(&s).expect("valid");
        let l = rainbow_layout();
        let normal = |name: &str| {
            let m = s.meshes.iter().find(|m| m.name == name).expect(name);
            let g = m;
            let [a, b, c] = g.indices[0].map(|i| g.positions[i as usize].as_dvec3());
            (b - a).cross(c - a).normalize()
        };
        assert!(normal("Screen").dot(l.screen_normal) > 1.0 - 1e-9);
        assert!(normal("Slit baffle").dot(-l.dir_in) > 1.0 - 1e-9);
        assert!(rainbow_landing(0.5).is_none() && rainbow_landing(f64::NAN).is_none());
    }
}
