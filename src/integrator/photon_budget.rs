//! How many caustic photons a hybrid pass traces when `--photons` does not say: the count
//! that makes the image's relative error fall fastest per unit of work, chosen once per
//! render by a pilot at the render's own resolution, seed and wavelengths.
//!
//! One pass of the hybrid ([`super::hybrid`]) costs the camera paths' work `t_P` plus `n`
//! photons at `c` each, and leaves in a pixel the variance `v_P + v_C·N/n`: the camera
//! paths' own (with the map's expected value), and the map's, which at a fixed radius falls
//! as 1/n (the gather averages n independent photons; the radius sequence depends on the
//! pass index only, [`super::caustic::CausticMap::end_pass`]). The error after a given work
//! is proportional to `(v_P + v_C·N/n)(t_P + n·c)`, least at
//!
//! `n* = N·√((V_C / V_P)·(R_P / R_C))`,
//!
//! Neyman's allocation with costs between two independent estimators (Cochran, *Sampling
//! Techniques*, 3rd ed. 1977, §5.5), with N the pixels (one photon per pixel is the count
//! without a pilot), V_C the map's variance at N photons a pass and V_P the camera side's,
//! each summed over the pilot's pixels and channels with the relative MSE's weight
//! 1/(m² + ε) ([`REL_EPS`], m the pilot's pixel mean), and R_P, R_C the rays per camera path
//! and per photon. Work is counted in rays, not seconds, so the choice is a pure function of
//! the scene, seed and size: every shard of a render makes the same one. R_C counts a
//! photon's full walk ([`super::caustic::Walk::Full`]), though the render's passes end a
//! photon once nothing more of it can be stored.
//!
//! The map's variance grows as its radius shrinks (as 1/r² for a kernel estimate), so the
//! optimum grows with the pass: pass i traces `n*(r₀)·r₀/rᵢ` photons ([`PhotonBudget::per_pass`]),
//! a count that never falls from one pass to the next (so pass i's photon numbers,
//! `i·nᵢ + j`, never overlap an earlier pass's).
//!
//! The pilot: pass 0's wavelengths; two independent maps A and B of N/2 photons each (the
//! photons of indices 0..N of pass 0's numbers, as two passes), which also give the first
//! radius; two camera samples of a separate sampler stream at every `stride`-th pixel
//! (about [`PILOT_PIXELS`] pixels), each traced twice, gathering A and then B. The two
//! traces of a sample take the same path (the gather does not steer it), so `X_A − X_B` is
//! the maps' difference alone: `v_C(N) = E[(X_A − X_B)²]/4`, and the camera side's variance
//! is that of `(X_A + X_B)/2` between the two samples. The two samples share pass 0's
//! wavelengths, so in spectral renders V_P leaves out the colour noise between passes and
//! the pilot errs toward more photons.
//!
//! The count is clamped to [`MIN_FACTOR`]·N … [`MAX_FACTOR`]·N (at most [`MAX_PHOTONS`]
//! and, above N, at most [`MAX_RAISED`]); the pilot's own photons and rays count in the
//! render's figures. Units: radiance as linear RGB, work as rays, radii in scene units.

use super::caustic::CausticMap;
use super::hybrid::split::{CausticPaths, CausticSplit, Gather};
use super::path;
use super::photon_pass::{first_radius, pass_lambda};
use super::{Context, MAX_PHOTONS};
use crate::camera::Camera;
use crate::error::Result;
use crate::image::metrics::REL_EPS;
use crate::photon::emit::PhotonEmitter;
use crate::render::{primary_ray, RenderSettings};
use crate::sampler::PixelSampler;
use crate::scene::Scene;
use crate::shading::Surface;
use crate::spectrum::Carrier;
use glam::DVec3;
use rayon::prelude::*;

/// Pixels the pilot samples, about (a regular sub-grid of the image).
pub const PILOT_PIXELS: u64 = 16_384;
/// Fewest photons a pass, as a fraction of one per pixel.
pub const MIN_FACTOR: f64 = 1.0 / 64.0;
/// Most photons a pass, as a multiple of one per pixel.
pub const MAX_FACTOR: f64 = 4.0;
/// Above one photon per pixel, at most this many a pass (the store budget,
/// [`super::MAX_STORED_PHOTONS`], holds several stored vertices per photon).
pub const MAX_RAISED: u64 = 1 << 22;
/// Stream key of the pilot's camera samples (distinct from the render's).
const PILOT_KEY: u64 = 0x9170_7B0D;

/// The pilot's choice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonBudget {
    /// n*/N at the first radius, before the clamp ([`factor`]).
    pub factor: f64,
    /// The first radius (the one given, or chosen from the pilot's photons).
    pub first_radius: f32,
    /// Rays the pilot traced (photons and camera paths).
    pub rays: u64,
    /// Photons the pilot emitted.
    pub photons: u64,
}

impl PhotonBudget {
    /// Photons of a pass whose radius is `r`, at `pixels` pixels: N·factor·r₀/r within the
    /// bounds ([`photons_for`]).
    pub fn per_pass(&self, pixels: u64, r: f32) -> u64 {
        let grow = if r > 0.0 && self.first_radius > 0.0 {
            f64::from(self.first_radius) / f64::from(r)
        } else {
            1.0
        };
        photons_for(self.factor * grow.max(1.0), pixels)
    }
}

/// What the pilot measured: summed weighted variances and rays per path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PilotFigures {
    /// Σ w·v_C at one photon per pixel, at the first radius.
    pub map: f64,
    /// Σ w·v_P.
    pub camera: f64,
    /// Rays per camera path.
    pub rays_per_path: f64,
    /// Rays per photon.
    pub rays_per_photon: f64,
}

/// n*/N for the pilot's figures, unclamped. No map variance: [`MIN_FACTOR`]; no camera
/// variance (or no camera work) but some map variance: [`MAX_FACTOR`].
pub fn factor(f: &PilotFigures) -> f64 {
    let map = f.map;
    if map.is_nan() || map <= 0.0 || !f.rays_per_photon.is_finite() {
        return MIN_FACTOR;
    }
    if !(f.camera > 0.0 && f.rays_per_path > 0.0 && f.rays_per_photon > 0.0) {
        return MAX_FACTOR;
    }
    let k = ((map / f.camera) * (f.rays_per_path / f.rays_per_photon)).sqrt();
    if k.is_finite() {
        k
    } else {
        MAX_FACTOR
    }
}

/// Photons a pass for `factor` at `pixels` (one per pixel being factor 1), within the
/// bounds in the module docs.
pub fn photons_for(factor: f64, pixels: u64) -> u64 {
    let factor = factor.clamp(MIN_FACTOR, MAX_FACTOR);
    let n = (pixels as f64 * factor).round() as u64;
    let cap = if factor > 1.0 {
        MAX_PHOTONS.min(pixels.max(MAX_RAISED))
    } else {
        MAX_PHOTONS
    };
    n.clamp(1, cap)
}

/// Runs the pilot for a hybrid render (map mode, `--photons` not given) and returns the
/// budget; `radius`: the `--radius` given, if any; `dispersion`: what the render's camera
/// paths keep of their wavelengths, so the pilot's camera paths are the render's.
#[allow(clippy::too_many_arguments)]
pub fn choose<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    (max_depth, dispersion): (u32, path::Dispersion),
    emitter: &PhotonEmitter,
    (radius, alpha): (Option<f32>, f32),
) -> Result<PhotonBudget> {
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let half = (pixels.clamp(1, MAX_PHOTONS) / 2).max(1);
    let lambda = pass_lambda::<C>(0, settings.seed);
    let (mut a, mut b) = (
        CausticMap::new(radius, alpha).full_walks(),
        CausticMap::new(radius, alpha).full_walks(),
    );
    let mut rays = 0;
    for (pass, map) in [(0, &mut a), (1, &mut b)] {
        let traced = map.trace_pass::<C>(
            scene,
            emitter,
            settings.seed,
            pass,
            half,
            lambda,
            max_depth,
            None,
        )?;
        rays += traced.0;
    }
    let r0 = radius.unwrap_or_else(|| {
        let points = a.photons.iter().chain(&b.photons).map(|p| p.position());
        first_radius(scene, camera, settings, points)
    });
    let r0 = a.begin_gather(|_| r0);
    b.begin_gather(|_| r0);
    let (mut fig, camera_rays) = measure::<C>(
        scene,
        camera,
        settings,
        (max_depth, dispersion),
        lambda,
        [&a, &b],
    );
    fig.rays_per_photon = rays as f64 / (2 * half) as f64;
    Ok(PhotonBudget {
        factor: factor(&fig),
        first_radius: r0,
        rays: rays + camera_rays,
        photons: 2 * half,
    })
}

/// The pilot's camera side: the weighted variances and rays per camera path (rays per
/// photon left 0 for the caller), and the rays traced.
fn measure<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    (max_depth, dispersion): (u32, path::Dispersion),
    lambda: C::Lambda,
    maps: [&CausticMap; 2],
) -> (PilotFigures, u64) {
    let (w, h) = (settings.width, settings.height);
    let stride = ((u64::from(w) * u64::from(h)) as f64 / PILOT_PIXELS as f64)
        .sqrt()
        .ceil()
        .max(1.0) as u32;
    let sampler = PixelSampler::new(settings.sampler, 2, (w, h), settings.seed ^ PILOT_KEY);
    let at: Vec<(u32, u32)> = (stride / 2..h)
        .step_by(stride as usize)
        .flat_map(|y| {
            (stride / 2..w)
                .step_by(stride as usize)
                .map(move |x| (x, y))
        })
        .collect();
    let gathers: [Gather<'_, C>; 2] = [
        &|s: &Surface<C>, l: &C::Lambda| maps[0].density(s, l, false),
        &|s: &Surface<C>, l: &C::Lambda| maps[1].density(s, l, false),
    ];
    // Per pixel, in pixel order (a fixed sum order: the same figures whatever the threads).
    let per_pixel: Vec<(f64, f64, u64)> = at
        .par_iter()
        .map(|&(x, y)| {
            let mut rays = 0;
            let mut xs = [[DVec3::ZERO; 2]; 2];
            for (k, row) in xs.iter_mut().enumerate() {
                for (g, out) in row.iter_mut().enumerate() {
                    let mut ctx = Context {
                        sample: sampler.start(x, y, k as u64),
                        rays: 0,
                    };
                    let ray = primary_ray(camera, x, y, false, &mut ctx.sample);
                    let split = CausticPaths {
                        split: CausticSplit::Map(gathers[g]),
                        dispersion,
                    };
                    let (l, _) = path::camera_path::<C, _>(
                        scene,
                        &ray,
                        (max_depth, &split),
                        lambda,
                        &mut ctx,
                    );
                    *out = l.to_rgb(&lambda).as_dvec3();
                    rays += ctx.rays;
                }
            }
            let (map, cam) = pixel_variances(xs);
            (map, cam, rays)
        })
        .collect();
    let (mut map, mut cam, mut rays) = (0.0, 0.0, 0);
    for (m, c, r) in per_pixel {
        (map, cam, rays) = (map + m, cam + c, rays + r);
    }
    let paths = (at.len() * 4).max(1) as f64;
    let fig = PilotFigures {
        map,
        camera: cam,
        rays_per_path: rays as f64 / paths,
        rays_per_photon: 0.0,
    };
    (fig, rays)
}

/// One pilot pixel's weighted map and camera variances from `xs[sample][map]` (the two
/// samples, each gathered from map A and map B): see the module docs. A pixel with a
/// non-finite value counts nothing.
pub fn pixel_variances(xs: [[DVec3; 2]; 2]) -> (f64, f64) {
    if !xs.iter().flatten().all(|v| v.is_finite()) {
        return (0.0, 0.0);
    }
    let y = [0.5 * (xs[0][0] + xs[0][1]), 0.5 * (xs[1][0] + xs[1][1])];
    let d = [xs[0][0] - xs[0][1], xs[1][0] - xs[1][1]];
    let v_map = (d[0] * d[0] + d[1] * d[1]) / 8.0;
    let v_cam = (y[0] - y[1]) * (y[0] - y[1]) / 2.0;
    let m = 0.5 * (y[0] + y[1]);
    let w = (m * m + DVec3::splat(REL_EPS)).recip();
    ((v_map * w).element_sum(), (v_cam * w).element_sum())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig(map: f64, camera: f64, rays_per_path: f64, rays_per_photon: f64) -> PilotFigures {
        PilotFigures {
            map,
            camera,
            rays_per_path,
            rays_per_photon,
        }
    }

    #[test]
    fn factor_is_neymans_allocation() {
        // √((0.04/1)·(8/2)) = √0.16 = 0.4.
        assert!((factor(&fig(0.04, 1.0, 8.0, 2.0)) - 0.4).abs() < 1e-12);
        assert!((factor(&fig(1e-6, 1.0, 1.0, 1.0)) - 1e-3).abs() < 1e-15);
        assert_eq!(factor(&fig(0.0, 1.0, 1.0, 1.0)), MIN_FACTOR);
        assert_eq!(factor(&fig(1.0, 0.0, 1.0, 1.0)), MAX_FACTOR);
    }

    #[test]
    fn photons_for_rounds_and_caps() {
        assert_eq!(photons_for(1.0 / 16.0, 186_624), 11_664);
        assert_eq!(photons_for(1e-3, 186_624), 186_624 / 64);
        assert_eq!(photons_for(MIN_FACTOR, 10), 1);
        assert_eq!(photons_for(4.0, 1000), 4000);
        assert_eq!(photons_for(100.0, 1000), 4000);
        // Above one per pixel a large image keeps one per pixel plus at most MAX_RAISED.
        assert_eq!(photons_for(4.0, 8_000_000), 8_000_000);
        assert_eq!(photons_for(4.0, 2_000_000), MAX_RAISED);
    }

    #[test]
    fn the_count_grows_as_the_radius_shrinks_and_never_falls() {
        let b = PhotonBudget {
            factor: 0.1,
            first_radius: 0.02,
            rays: 0,
            photons: 0,
        };
        assert_eq!(b.per_pass(10_000, 0.02), 1000);
        // r₀/r = 2: twice the photons (the map's variance ∝ 1/r², the optimum ∝ its root).
        assert_eq!(b.per_pass(10_000, 0.01), 2000);
        // Along Knaus and Zwicker's sequence the count never falls.
        let mut r2 = 0.02f64 * 0.02;
        let mut last = 0;
        for i in 1..2000u32 {
            let n = b.per_pass(10_000, r2.sqrt() as f32);
            assert!(n >= last, "pass {i}: {n} < {last}");
            last = n;
            r2 *= crate::integrator::photon_pass::radius2_factor(i, 2.0 / 3.0);
        }
        assert!(last > 3000 && last <= 40_000, "{last}");
    }

    #[test]
    fn pixel_variances_separate_the_maps_from_the_camera() {
        let v = DVec3::splat;
        // Same camera value, maps differ by 0.2 in both samples: all map variance,
        // (0.04 + 0.04)/8 = 0.01 per channel, none for the camera.
        let (m, c) = pixel_variances([[v(1.1), v(0.9)], [v(1.1), v(0.9)]]);
        let w = 1.0 / (1.0 + REL_EPS);
        assert!((m - 3.0 * 0.01 * w).abs() < 1e-12 && c == 0.0, "{m} {c}");
        // Maps agree, samples differ by 0.4 (means 0.8 and 1.2): (0.4²)/2 = 0.08.
        let (m, c) = pixel_variances([[v(0.8), v(0.8)], [v(1.2), v(1.2)]]);
        assert!(m == 0.0 && (c - 3.0 * 0.08 * w).abs() < 1e-12, "{m} {c}");
        assert_eq!(
            pixel_variances([[v(f64::NAN), v(0.8)], [v(1.2), v(1.2)]]),
            (0.0, 0.0)
        );
    }
}
