//! Scattering functions (BSDFs): Lambert, GGX conductor (Schlick from a colour, or a
//! measured metal's complex index), smooth/rough dielectric, thin dielectric and the glTF
//! metallic-roughness mix. A closed enum, no trait objects.
//!
//! A lobe is one module ([`lambert`], [`conductor`], [`dielectric`], [`thin`], [`pbr`]):
//! each answers every question of [`lobe::Lobe`] — sample, eval, pdf, its Mueller matrix,
//! what a photon does at it, the denoiser's albedo, whether it is delta, diffuse-like or
//! an interface whose η follows the wavelength — and [`Bsdf`] forwards each question through
//! one exhaustive match. Code outside this module asks the [`Bsdf`], never its variants
//! (the materials build them, [`crate::material`]). Adding a lobe: its module, its variant,
//! its arm of the match, its example in `lobe_tests`.
//!
//! Frame: every direction is in the **local shading frame**, z = the surface's OUTWARD
//! normal (outside of the object is z > 0); unit vectors point AWAY from the surface.
//! `eta` = n_inside / n_outside; `wo.z < 0` means the path is inside the object (pbrt-v4
//! `DielectricBxDF` convention). `f` is per steradian, pdfs are per unit solid angle; delta
//! lobes have `eval = pdf = 0` and are only reachable through [`Bsdf::sample`], whose
//! `f`/`pdf` then carry the delta's weight (f·|cos θi|/pdf is the throughput factor).

mod albedo_table;
pub mod anisotropic;
mod conductor;
pub(crate) mod dielectric;
mod energy;
#[cfg(test)]
mod energy_tests;
mod ggx_reflect;
mod gltf_brdf;
pub mod interference;
pub mod iridescence;
mod lambert;
mod layers;
#[cfg(test)]
mod layers_tests;
mod lobe;
#[cfg(test)]
mod lobe_tests;
pub mod microfacet;
mod pbr;
pub mod sheen;
#[cfg(test)]
mod tests;
mod thin;

use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
pub use iridescence::{Iridescence, LobeExtensions};
pub use lambert::cosine_direction;
pub use layers::{coat_fresnel, Layers};
use lobe::Lobe;
pub use lobe::{RouletteLobes, GLOSSY_ALPHA};

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

/// Binds `$l` to the lobe of `$bsdf` (its module's struct, [`lobe::Lobe`]) and evaluates
/// `$body`: the one match over the variants, without a wildcard, so a new variant must name
/// its lobe here and that lobe must answer every question of [`lobe::Lobe`].
macro_rules! with_lobe {
    ($bsdf:expr, |$l:ident| $body:expr) => {
        match *$bsdf {
            Bsdf::Lambert { albedo } => {
                let $l = lambert::Lambert { albedo };
                $body
            }
            Bsdf::Conductor { f0, alpha } => {
                let $l = conductor::Conductor { f0, alpha };
                $body
            }
            Bsdf::ComplexConductor {
                eta,
                k,
                alpha,
                extensions,
            } => {
                let $l = conductor::ComplexConductor {
                    eta,
                    k,
                    alpha,
                    extensions,
                };
                $body
            }
            Bsdf::Dielectric { eta, alpha, tint } => {
                let $l = dielectric::Dielectric { eta, alpha, tint };
                $body
            }
            Bsdf::ThinDielectric { eta, tint } => {
                let $l = thin::ThinDielectric { eta, tint };
                $body
            }
            Bsdf::GltfPbr {
                base,
                metallic,
                alpha,
                ior,
                specular,
                specular_color,
                layers,
                extensions,
            } => {
                let $l = pbr::GltfPbr {
                    base,
                    metallic,
                    alpha,
                    ior,
                    specular,
                    specular_color,
                    layers,
                    extensions,
                };
                $body
            }
        }
    };
}

impl<C: Carrier> Bsdf<C> {
    /// The same lobe in its simplest form: a glTF BRDF with no specular part at all
    /// (metallic 0, `specular` 0, so F0 = F90 = 0; no layer, no film) is the Lambert lobe
    /// it then equals, f = base/π, which skips the GGX terms weighed by zero; any other
    /// lobe is itself.
    pub fn reduced(self) -> Self {
        match self {
            Bsdf::GltfPbr {
                base,
                metallic,
                specular,
                ref layers,
                ref extensions,
                ..
            } if metallic == 0.0
                && specular == 0.0
                && extensions.iridescence.is_none()
                && layers.is_none() =>
            {
                Bsdf::Lambert { albedo: base }
            }
            other => other,
        }
    }

    /// Whether every lobe is a delta (eval and pdf are then always 0).
    pub fn is_delta(&self) -> bool {
        with_lobe!(self, |l| l.is_delta())
    }

    /// Whether [`Bsdf::sample`] reads its 2D number `u`: not for the smooth and thin
    /// dielectrics, which choose reflection or transmission with `uc` alone (the path
    /// tracer then skips that number).
    pub fn samples_direction(&self) -> bool {
        with_lobe!(self, |l| l.samples_direction())
    }

    /// f(wo, wi); 0 for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        if self.is_delta() {
            return C::ZERO;
        }
        with_lobe!(self, |l| l.eval(wo, wi, mode))
    }

    /// Solid-angle pdf of [`Bsdf::sample`] producing `wi`; 0 for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> f32 {
        if self.is_delta() {
            return 0.0;
        }
        with_lobe!(self, |l| l.pdf(wo, wi))
    }

    /// Samples wi given wo; `uc` picks a lobe, `u` the direction (all in [0,1)).
    /// `None` when no valid direction results (e.g. a microfacet reflection below the
    /// horizon, or grazing `wo`).
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        with_lobe!(self, |l| l.sample(wo, uc, u, mode))
    }

    /// The normalized Mueller matrix N = M / M₀₀ of the light the BSDF scatters from −`wi`
    /// to `wo` (its scalar value already carries M₀₀) and the local normal (surface or
    /// microfacet) its s/p bases refer to ([`crate::shading::polarized::s_basis`]); `None`
    /// for a depolarizing BSDF ([`Bsdf::depolarizes`]) or a degenerate pair.
    pub fn mueller(&self, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
        let (m, normal) = with_lobe!(self, |l| l.mueller(wo, wi))?;
        let d = m[0][0];
        (d > 0.0 && d.is_finite()).then(|| (m.map(|row| row.map(|v| v / d)), normal))
    }

    /// Whether the BSDF depolarizes whatever the directions (Lambert, the glTF PBR mix):
    /// the light it scatters is read as unpolarized, [`Bsdf::mueller`] is `None`.
    pub fn depolarizes(&self) -> bool {
        with_lobe!(self, |l| l.depolarizes())
    }

    /// Whether the BSDF's polarization depends on the wavelength beyond what the shared
    /// step already reduces to the hero (a measured conductor, whose complex index is taken
    /// at the hero in [`Bsdf::mueller`]). One Stokes vector or analyzer serves all the lanes
    /// of a path until a crystal or such a surface; then the hero alone.
    pub fn hero_polarizes(&self) -> bool {
        with_lobe!(self, |l| l.hero_polarizes())
    }

    /// Whether photons should be gathered at the BSDF rather than continuing the camera
    /// path: anything with a diffuse lobe, or a glossy lobe at least [`GLOSSY_ALPHA`] rough.
    pub fn is_diffuse_like(&self) -> bool {
        with_lobe!(self, |l| l.is_diffuse_like())
    }

    /// The colours a photon chooses among under lobe roulette ([`RouletteLobes`]).
    pub fn roulette_lobes(&self) -> RouletteLobes<C> {
        with_lobe!(self, |l| l.roulette_lobes())
    }

    /// The direction a photon takes from `wo` when lobe roulette chooses transmission: the
    /// refraction about the normal at a dielectric interface, straight through elsewhere.
    pub fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        with_lobe!(self, |l| l.roulette_transmission(wo))
    }

    /// The reflectance of the denoiser's albedo feature ([`crate::denoise`]): the diffuse
    /// colour for the glTF model, the normal-incidence reflectance of a conductor, the
    /// transmission tint of a dielectric.
    pub fn albedo(&self) -> C {
        with_lobe!(self, |l| l.albedo())
    }

    /// The η (n_inside / n_outside) of a dielectric interface, which bends light by an index
    /// the path's wavelengths may change; `None` for the other BSDFs (the thin wall does
    /// not bend light).
    pub fn interface_eta(&self) -> Option<f32> {
        with_lobe!(self, |l| l.interface_eta())
    }

    /// The BSDF as lane `k` of a spectral path sees it: the interface η replaced by `eta`,
    /// the colours' lanes rotated by `k` ([`Carrier::rotated`]); `None` for a BSDF without
    /// an interface η ([`Bsdf::interface_eta`]).
    pub fn with_lane(&self, eta: f32, k: usize) -> Option<Bsdf<C>> {
        with_lobe!(self, |l| l.with_lane(eta, k))
    }
}
