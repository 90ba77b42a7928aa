//! Scattering functions (BSDFs) for path tracing: Lambert, GGX conductor (Schlick from a
//! colour, or a measured metal's complex index), smooth/rough dielectric, thin dielectric
//! and the glTF metallic-roughness mix. A closed enum, no trait objects.
//!
//! Frame: every direction is in the **local shading frame**, z = the surface's OUTWARD
//! normal (outside of the object is z > 0); unit vectors point AWAY from the surface.
//! `eta` = n_inside / n_outside; `wo.z < 0` means the path is inside the object (pbrt-v4
//! `DielectricBxDF` convention). `f` is per steradian, pdfs are per unit solid angle; delta
//! lobes have `eval = pdf = 0` and are only reachable through [`Bsdf::sample`], whose
//! `f`/`pdf` then carry the delta's weight (f·|cos θi|/pdf is the throughput factor).

mod albedo_table;
pub mod anisotropic;
pub(crate) mod dielectric;
mod energy;
#[cfg(test)]
mod energy_tests;
pub mod interference;
pub mod iridescence;
mod layers;
#[cfg(test)]
mod layers_tests;
pub mod microfacet;
mod pbr;
pub mod sheen;
#[cfg(test)]
mod tests;

use crate::spectrum::Carrier;
use anisotropic::Microfacet;
use glam::{Vec2, Vec3};
pub use iridescence::{Iridescence, LobeExtensions};
pub use layers::{coat_fresnel, Layers};
use pbr::ConductorFresnel;

/// GGX α below which a lobe is treated as perfectly smooth (delta).
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// Which quantity a path carries (pbrt-v4 §9.5.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TransportMode {
    /// Camera paths: refraction scales f by 1/η'² (radiance compression).
    Radiance,
    /// Light paths (adjoint BSDF): no η'² factor, f_imp(wo, wi) = f_rad(wi, wo).
    Importance,
}

/// Result of [`Bsdf::sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BsdfSample<C = Vec3> {
    /// Sampled incident direction (local frame, unit).
    pub wi: Vec3,
    /// f(wo, wi) (for delta lobes: the delta's coefficient).
    pub f: C,
    /// Solid-angle pdf (for delta lobes: the discrete lobe probability).
    pub pdf: f32,
    /// Whether the sample is from a delta lobe.
    pub delta: bool,
    /// Whether `wi` is on the other side of the surface from `wo`.
    pub transmission: bool,
}

impl<C> BsdfSample<C> {
    /// A sample of a delta lobe: `f` is the delta's coefficient, `pdf` the probability of
    /// choosing the lobe.
    #[inline]
    pub(crate) fn delta(wi: Vec3, f: C, pdf: f32, transmission: bool) -> Self {
        BsdfSample {
            wi,
            f,
            pdf,
            delta: true,
            transmission,
        }
    }

    /// A sample of a non-delta lobe: the direction `wi` drawn with solid-angle density `pdf`,
    /// and `f(wo, wi)` from `f` (evaluated only for a usable sample). `None` when `pdf` is
    /// not positive and finite.
    #[inline]
    pub(crate) fn lobe(
        wi: Vec3,
        pdf: f32,
        transmission: bool,
        f: impl FnOnce() -> C,
    ) -> Option<Self> {
        (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
            wi,
            f: f(),
            pdf,
            delta: false,
            transmission,
        })
    }
}

/// The specular reflection of `w` about the shading normal (local frame: z).
#[inline]
pub(crate) fn reflect_z(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// A BSDF at one shading point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bsdf<C = Vec3> {
    /// Lambertian reflection, f = albedo/π (two-sided).
    Lambert {
        /// Diffuse reflectance.
        albedo: C,
    },
    /// GGX microfacet conductor with Schlick Fresnel from f0 (glTF metals: f0 = base colour);
    /// `alpha < SMOOTH_ALPHA` ⇒ a delta mirror.
    Conductor {
        /// Normal-incidence reflectance.
        f0: C,
        /// GGX α.
        alpha: f32,
    },
    /// GGX microfacet conductor with the exact Fresnel reflectance of a complex index
    /// η + ik per channel or wavelength ([`crate::optics::fresnel_conductor`]): a measured
    /// metal ([`crate::spectrum::Metal`]), whose colour is its k(λ) and n(λ), not a tint.
    /// `alpha < SMOOTH_ALPHA` ⇒ a delta mirror.
    ComplexConductor {
        /// Real part n of the metal's index, relative to the outside.
        eta: C,
        /// Extinction coefficient k (≥ 0).
        k: C,
        /// GGX α.
        alpha: f32,
        /// KHR_materials_iridescence / KHR_materials_anisotropy ([`iridescence`]).
        extensions: LobeExtensions,
    },
    /// Smooth (alpha < 1e-3 ⇒ delta lobes) or rough GGX dielectric (Walter 2007, with
    /// Turquin 2019 multiple-scattering compensation: energy-conserving, not reciprocal), with
    /// reflection and transmission; `tint` multiplies transmission (glTF base colour), `eta`
    /// may be < 1 (bubble) and may be +∞ (glTF ior 0: pure mirror). η = 1 is always delta
    /// (straight through).
    Dielectric {
        /// n_inside / n_outside.
        eta: f32,
        /// GGX α.
        alpha: f32,
        /// Transmission tint.
        tint: C,
    },
    /// Thin-walled dielectric (KHR_materials_transmission without volume): straight-through
    /// transmission, no bending.
    ThinDielectric {
        /// Index of the slab relative to its surroundings.
        eta: f32,
        /// Transmission tint.
        tint: C,
    },
    /// glTF metallic-roughness: Lambert diffuse + GGX specular with KHR_materials_specular
    /// (f0 = min(((ior−1)/(ior+1))²·specular_color, 1)·specular, f90 = specular), mixed with
    /// the metal lobe by `metallic`; sample picks a lobe by an estimate of its weight.
    /// `alpha` (= roughness²) is floored at 1e-2 (no delta lobe).
    GltfPbr {
        /// Base colour (linear).
        base: C,
        /// Metalness in [0, 1].
        metallic: f32,
        /// GGX α.
        alpha: f32,
        /// Index of refraction (∞ allowed).
        ior: f32,
        /// KHR_materials_specular factor.
        specular: f32,
        /// KHR_materials_specular colour.
        specular_color: C,
        /// KHR_materials_clearcoat, _sheen and _diffuse_transmission ([`layers`]).
        layers: Layers<C>,
        /// KHR_materials_iridescence / KHR_materials_anisotropy ([`iridescence`]).
        extensions: LobeExtensions,
    },
}

/// Both directions on the same side of the surface.
#[inline]
pub(crate) fn same_hemisphere(a: Vec3, b: Vec3) -> bool {
    a.z * b.z > 0.0
}

impl<C: Carrier> Bsdf<C> {
    fn gltf(&self) -> Option<pbr::Gltf<C>> {
        pbr::Gltf::of(self)
    }

    /// The conductor lobe of [`Bsdf::Conductor`] and [`Bsdf::ComplexConductor`].
    fn conductor(&self) -> Option<pbr::Conductor<C>> {
        let (fresnel, alpha, anisotropy) = match *self {
            Bsdf::Conductor { f0, alpha } => (ConductorFresnel::Schlick(f0), alpha, 0.0),
            Bsdf::ComplexConductor {
                eta,
                k,
                alpha,
                extensions,
            } => (
                ConductorFresnel::Complex { eta, k, extensions },
                alpha,
                extensions.anisotropy,
            ),
            _ => return None,
        };
        Some(pbr::Conductor {
            fresnel,
            ggx: Microfacet::khr(alpha, anisotropy),
            smooth: self.is_delta(),
        })
    }

    /// The layered glTF BSDF when any KHR layer is present (`None` otherwise: the plain
    /// glTF BRDF, unchanged).
    fn layered(&self) -> Option<layers::Layered<C>> {
        match self {
            Bsdf::GltfPbr { layers, .. } if !layers.is_none() => {
                Some(layers::Layered::new(self.gltf()?, layers))
            }
            _ => None,
        }
    }

    /// Whether every lobe is a delta (eval and pdf are then always 0).
    pub fn is_delta(&self) -> bool {
        match *self {
            Bsdf::Lambert { .. } | Bsdf::GltfPbr { .. } => false,
            Bsdf::Conductor { alpha, .. } => alpha < SMOOTH_ALPHA,
            // Anisotropy widens the lobe along x (α_x = mix(α, 1, s²)): never a delta.
            Bsdf::ComplexConductor {
                alpha, extensions, ..
            } => alpha < SMOOTH_ALPHA && extensions.anisotropy <= 0.0,
            Bsdf::Dielectric { eta, alpha, .. } => alpha < SMOOTH_ALPHA || eta == 1.0,
            Bsdf::ThinDielectric { .. } => true,
        }
    }

    /// Whether [`Bsdf::sample`] reads its 2D number `u`: not for the smooth and thin
    /// dielectrics, which choose reflection or transmission with `uc` alone (the path
    /// tracer then skips that number).
    pub fn samples_direction(&self) -> bool {
        match *self {
            Bsdf::Dielectric { .. } => !self.is_delta(),
            Bsdf::ThinDielectric { .. } => false,
            _ => true,
        }
    }

    /// f(wo, wi); 0 for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        if self.is_delta() {
            return C::ZERO;
        }
        match *self {
            Bsdf::Lambert { albedo } => pbr::lambert_eval(albedo, wo, wi),
            Bsdf::Conductor { .. } | Bsdf::ComplexConductor { .. } => {
                self.conductor().map_or(C::ZERO, |c| c.eval(wo, wi))
            }
            Bsdf::Dielectric { eta, alpha, tint } => {
                dielectric::Rough { eta, alpha, tint }.eval(wo, wi, mode)
            }
            Bsdf::ThinDielectric { .. } => C::ZERO,
            Bsdf::GltfPbr { .. } => match self.layered() {
                Some(l) => l.eval(wo, wi, mode),
                None => self.gltf().map_or(C::ZERO, |g| g.eval(wo, wi)),
            },
        }
    }

    /// Solid-angle pdf of [`Bsdf::sample`] producing `wi`; 0 for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> f32 {
        if self.is_delta() {
            return 0.0;
        }
        match *self {
            Bsdf::Lambert { .. } => pbr::lambert_pdf(wo, wi),
            Bsdf::Conductor { .. } | Bsdf::ComplexConductor { .. } => {
                self.conductor().map_or(0.0, |c| c.pdf(wo, wi))
            }
            Bsdf::Dielectric { eta, alpha, tint } => {
                dielectric::Rough { eta, alpha, tint }.pdf(wo, wi)
            }
            Bsdf::ThinDielectric { .. } => 0.0,
            Bsdf::GltfPbr { .. } => match self.layered() {
                Some(l) => l.pdf(wo, wi),
                None => self.gltf().map_or(0.0, |g| g.pdf(wo, wi)),
            },
        }
    }

    /// Samples wi given wo; `uc` picks a lobe, `u` the direction (all in [0,1)).
    /// `None` when no valid direction results (e.g. a microfacet reflection below the
    /// horizon, or grazing `wo`).
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        match *self {
            Bsdf::Lambert { albedo } => pbr::lambert_sample(albedo, wo, u),
            Bsdf::Conductor { .. } | Bsdf::ComplexConductor { .. } => {
                self.conductor()?.sample(wo, u)
            }
            Bsdf::Dielectric { eta, alpha, tint } => {
                if alpha < SMOOTH_ALPHA || eta == 1.0 {
                    dielectric::smooth_sample(eta, tint, wo, uc, mode)
                } else {
                    dielectric::Rough { eta, alpha, tint }.sample(wo, uc, u, mode)
                }
            }
            Bsdf::ThinDielectric { eta, tint } => dielectric::thin_sample(eta, tint, wo, uc),
            Bsdf::GltfPbr { .. } => match self.layered() {
                Some(l) => l.sample(wo, uc, u, mode),
                None => self.gltf()?.sample(wo, uc, u),
            },
        }
    }
}
