//! A structure-of-arrays path kernel (issue 51): the camera paths of `--method path`, and
//! of `--method hybrid` with `--caustics map` unpolarized ([`rules`]: what the method asks
//! of them), in RGB or spectral transport on scenes lit by punctual lights, emissive
//! triangles and an environment ([`features`] decides; the plan's `lanes` stage says why
//! not), the default ([`Kernel::Soa`]; `IRIS_KERNEL=scalar` or [`Kernel::Scalar`] picks
//! the scalar path vertex). Any other method, or a scene outside the class, renders with
//! the scalar vertex, unchanged. A lane that meets a material the kernel does not shade
//! (or a vertex where the hybrid gathers its caustic map) has that vertex shaded by the
//! scalar vertex and comes back ([`handoff`]).
//!
//! Design: 16 camera paths (8 with `IRIS_LANES=8`) run through one bounce loop
//! ([`paths::run`]) with their whole state in structure-of-arrays form, lane `i` at index
//! `i` of each array: the next rays, throughput and radiance in `M` channels (3 RGB, or
//! 4 wavelengths with the hero in channel 0: [`colour`]), η scale, bounce counts, job,
//! sample stream, wavelengths and alive mask. Rays go to the backend as one
//! [`crate::accel::packet::RayPacket`] and the hits come back as one
//! [`crate::accel::packet::HitPacket`]; the hit records are built over the lanes
//! ([`hits`]), with only the triangle's vertices, vertex normals and material gathered per
//! lane. Beer–Lambert absorption inside glass ([`volumes`]) and the light a path meets
//! (emission, the environment on escape, MIS-weighted: [`emitters`]) come first; shading
//! runs over all lanes with masks per material group ([`shade`]): next-event estimation at
//! Lambert and glossy lanes toward one light chosen as the scalar path tracer chooses it
//! ([`emitters`]), the cosine-sampled bounce and Russian roulette, the glossy lanes'
//! glTF BRDF or rough glass sampled and evaluated per lane by the scalar BSDF
//! ([`glossy`]); the smooth dielectric's Fresnel-weighted reflection or refraction. Shadow rays go out as one packet. A lane whose
//! path ends writes its job's radiance and takes the next job (refill), so glass paths do
//! not leave the packet empty. In spectral transport a sample meeting a dispersive glass
//! splits there into its 4 wavelengths as the scalar path tracer splits it, the waiting
//! sub-paths taking the lane in turn before the next job ([`branches`]). A lane takes its
//! job with the first hit known: the batch's
//! camera rays are traced `N` at a time in job order as coherent packets of their own
//! ([`camera`]), so the bounce packets carry bounce rays only. The film receives the
//! estimates in job order, as the scalar path's ([`crate::render::render_batches`]).
//!
//! SIMD: the per-lane arithmetic is plain loops over fixed-size arrays that LLVM
//! vectorises; the whole loop is compiled for AVX-512, AVX2 and scalar x86-64 and chosen at
//! run time by `pulp` ([`estimate`]), which holds the only `unsafe` (its
//! `#[target_feature]` calls). On the pure-Rust BVH the packets are answered lane by lane.
//!
//! Random numbers: each camera sample's own stream, the scalar path tracer's: the render's
//! sampler (Z-order Sobol' by default) restarted for the job ([`crate::render::Starts`]),
//! the camera ray made from it as the scalar path makes it, and each vertex's decisions
//! read from the scalar path's dimension schedule in its order ([`numbers`]). Deterministic
//! for a scene, seed, backend and packet width: a job's estimate depends on the job alone,
//! so the image is the same whatever the threads, rounds or shards (another width or
//! backend may differ where a ray meets two triangles exactly on their shared edge); a sample's
//! estimate equals the scalar path tracer's up to float rounding (the kernel's arithmetic
//! is its own: the sine and cosine of the bounce direction, the hit record, the order of
//! products), which can flip a decision taken on a threshold (a roulette, a Fresnel
//! choice, an edge between triangles) on a few samples, so the images agree pixel by pixel
//! on most pixels and in expectation everywhere.

#[cfg(test)]
mod asset_tests;
mod branches;
mod camera;
mod class;
mod colour;
mod emitters;
mod features;
mod glossy;
mod handing;
mod handoff;
mod hits;
mod numbers;
mod paths;
mod rules;
mod shade;
mod state;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_glossy;
#[cfg(test)]
mod tests_handoff;
#[cfg(test)]
mod tests_hybrid;
#[cfg(test)]
mod tests_lights;
#[cfg(test)]
mod tests_spectral;
mod volumes;

pub use features::{qualify, Tables};
pub use handoff::{OnScalar, Vertex};
pub use rules::{Carried, Rules};

use super::Dispersion;
use crate::accel::packet::{Lanes, PacketWidth};
use crate::camera::Camera;
use crate::render::{render_batches, Film, Job, Kernel, Observer, Prepass, RenderSettings};
use crate::render::{RenderStats, Starts};
use crate::scene::Scene;
use class::{Class, Full, Plain};
use glam::Vec3;
use std::marker::PhantomData;

/// The kernel's tables for `scene` seen by `camera` when `settings` ask for the kernel
/// ([`Kernel::Soa`], the default) and the scene qualifies ([`qualify`]); otherwise `None`
/// (the scalar path vertex renders). An invalid `IRIS_KERNEL` is an error.
pub fn choose(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
) -> crate::error::Result<Option<Tables>> {
    if settings.kernel.resolve()? != Kernel::Soa {
        return Ok(None);
    }
    Ok(qualify(scene, camera.is_perspective(), settings.spectral).ok())
}

/// Whether the environment asks for the kernel (`IRIS_KERNEL` unset, empty or `soa`).
pub fn requested() -> bool {
    Kernel::FromEnv.resolve().ok() == Some(Kernel::Soa)
}

/// What the render plan says of the kernel for `scene` when it is asked for: which
/// kernel renders the camera paths, and why (`Ok`: the kernel, with its width; `Err`: the
/// reason it does not take the scene); `gathers`: the method gathers another estimator
/// along them (the hybrid), which takes the full loop.
pub fn plan_text(
    scene: &Scene,
    (perspective, spectral): (bool, bool),
    gathers: bool,
) -> Result<String, String> {
    qualify(scene, perspective, spectral).map(|tables| {
        let handed = if tables.scalar.is_empty() {
            String::new()
        } else {
            format!(
                "; a lane meeting a material the kernel does not shade has that vertex \
                 shaded by the scalar vertex ({})",
                tables.scalar.join("; ")
            )
        };
        let class = if tables.plain() && !gathers {
            "the loop for Lambert surfaces and clear glass under punctual lights (no \
             emitter, environment, absorption, glossy or hand-over code)"
        } else {
            "the full loop (emitters and environments with MIS, absorbing glass, glossy \
             lobes and rough glass by the scalar BSDF per lane, hand-over)"
        };
        let carrier = if tables.spectral {
            "4 wavelengths a lane (a sample splits into its wavelengths at its first \
             dispersive glass, the sub-paths taking the lane in turn)"
        } else {
            "linear RGB"
        };
        format!(
            "structure-of-arrays kernel: {} camera paths with their whole \
             state in arrays, carrying {carrier}, hit records and shading across the lanes \
             (AVX-512, AVX2 or scalar code chosen at run time), {class}, each camera sample with its own \
             random stream (the single-ray path's numbers): the image equals the \
             single-ray image up to float rounding on most pixels and in expectation \
             everywhere{handed}",
            width()
        )
    })
}

/// Paths per packet: 16, or 8 when `IRIS_LANES=8`.
fn width() -> usize {
    match std::env::var("IRIS_LANES").ok().as_deref() {
        Some("8") => 8,
        _ => 16,
    }
}

/// The path tracer's render (`max_depth` non-delta bounces, `dispersion`) through the
/// kernel with `tables`, of the units `range` (all: `None`), as
/// [`crate::integrator::Integrator::render_units`] renders it on the scalar vertex.
pub fn render(
    tables: &Tables,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    (range, observer): (Option<std::ops::Range<u64>>, Option<Observer>),
    (max_depth, dispersion): (u32, Dispersion),
) -> crate::error::Result<(Film, RenderStats)> {
    let vertex = OnScalar {
        max_depth,
        strategy: dispersion,
    };
    let rules = if settings.spectral {
        Rules::Spectral(&vertex, None)
    } else {
        Rules::Rgb(&vertex)
    };
    let estimate =
        |s: &Starts, j: &[Job], o: &mut [Vec3]| estimate(tables, scene, (s, j), &rules, o);
    render_batches(camera, settings, range, Prepass::now(), observer, estimate)
}

/// The kernel's estimate of `jobs` (begun by `starts`) under the method's `rules`: job
/// `i`'s linear RGB radiance into `out[i]`. Returns the rays traced. The loop runs
/// compiled for the widest vector instructions this CPU has (`pulp`'s run-time dispatch).
pub fn estimate(
    tables: &Tables,
    scene: &Scene,
    (starts, jobs): (&Starts, &[Job]),
    rules: &Rules,
    out: &mut [Vec3],
) -> u64 {
    estimate_at(width(), tables, scene, (starts, jobs), rules, out)
}

/// [`estimate`] on `width` lanes (8, or 16 for any other value), carrying what `rules`
/// carry, with the loop specialised to the scene's class ([`class`]; a strategy that
/// gathers another estimator takes the full loop, which hands vertices over).
fn estimate_at(
    width: usize,
    tables: &Tables,
    scene: &Scene,
    run: (&Starts, &[Job]),
    rules: &Rules,
    out: &mut [Vec3],
) -> u64 {
    let op = Run {
        tables,
        scene,
        run,
        rules,
        out,
    };
    let plain = tables.plain() && !rules.gathers();
    match (width == 8, rules.spectral(), plain) {
        (true, false, true) => op.dispatch::<8, 3, Plain>(),
        (true, false, false) => op.dispatch::<8, 3, Full>(),
        (true, true, true) => op.dispatch::<8, 4, Plain>(),
        (true, true, false) => op.dispatch::<8, 4, Full>(),
        (false, false, true) => op.dispatch::<16, 3, Plain>(),
        (false, false, false) => op.dispatch::<16, 3, Full>(),
        (false, true, true) => op.dispatch::<16, 4, Plain>(),
        (false, true, false) => op.dispatch::<16, 4, Full>(),
    }
}

/// The bounce loop's inputs.
struct Run<'a> {
    tables: &'a Tables,
    scene: &'a Scene,
    run: (&'a Starts<'a>, &'a [Job]),
    rules: &'a Rules<'a>,
    out: &'a mut [Vec3],
}

impl Run<'_> {
    /// The loop on `N` lanes carrying `M` channels for the class `K`, compiled for the
    /// widest vector instructions this CPU has.
    fn dispatch<const N: usize, const M: usize, K: Class>(self) -> u64
    where
        Lanes<N>: PacketWidth,
    {
        pulp::Arch::new().dispatch(Loop::<N, M, K> {
            run: self,
            class: PhantomData,
        })
    }
}

/// The bounce loop on `N` lanes for the class `K` as `pulp`'s operation:
/// [`pulp::WithSimd::with_simd`] is instantiated per instruction set and inlined, with
/// [`paths::run`] and the lane loops under it (all `#[inline(always)]`), into `pulp`'s
/// `#[target_feature]` function for that set, so LLVM vectorises them for AVX-512 or AVX2.
/// (A closure is not inlined there: its body would be compiled once, for the crate's
/// baseline.)
struct Loop<'a, const N: usize, const M: usize, K> {
    run: Run<'a>,
    class: PhantomData<K>,
}

impl<const N: usize, const M: usize, K: Class> pulp::WithSimd for Loop<'_, N, M, K>
where
    Lanes<N>: PacketWidth,
{
    type Output = u64;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> u64 {
        let r = self.run;
        paths::run::<N, M, K>(r.tables, r.scene, r.run, r.rules, r.out)
    }
}
