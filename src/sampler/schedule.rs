//! The fixed dimension schedule of a camera path: which sampler dimension each
//! random decision draws, so a decision at bounce `b` always reads the same dimension
//! whatever earlier bounces drew (a bounce that skips a decision leaves its dimensions
//! unused rather than shifting later ones).
//!
//! Layout: `PIXEL` (2D film position), `LENS` (2D aperture), `WAVELENGTH` (2D hero
//! wavelength), then [`BOUNCE_STRIDE`] dimensions per bounce starting at [`FIRST_BOUNCE`]:
//! light choice (1D: the light group), light member (1D: the triangle within the emissive
//! group), light position (2D), material layer (1D: which layer of a layered material the
//! hit scatters from), BSDF lobe (1D), BSDF direction (2D), Russian roulette (1D). With
//! [`super::zsobol::ZSobol`] dimensions are unbounded (each only keys hashes), so paths of
//! any length get their own dimensions.
//!
//! Bounce `b` counts every scattering vertex of the camera path (delta ones included), so
//! no two vertices of one path share a dimension. Decisions outside the schedule (BLEND
//! coverage, the photon map's final gather, Whitted's per-branch roulette) draw from the
//! sample's independent stream ([`crate::math::Rng`]).

/// Film position within the pixel (2D).
pub const PIXEL: u32 = 0;
/// Lens aperture position (2D).
pub const LENS: u32 = 2;
/// Wavelength sample (2D: the set's offset and the hero member,
/// [`crate::spectrum::hero_number`]).
pub const WAVELENGTH: u32 = 4;
/// First dimension of bounce 0.
pub const FIRST_BOUNCE: u32 = 6;
/// Dimensions per bounce.
pub const BOUNCE_STRIDE: u32 = 9;

/// One random decision within a bounce.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BounceDim {
    /// Which light group to sample (1D).
    LightChoice,
    /// Which member of the group (the emissive triangle, 1D).
    LightMember,
    /// Position on the chosen light (2D).
    LightPosition,
    /// Which layer of the material scatters (1D).
    Layer,
    /// Which BSDF lobe (reflect/transmit, 1D).
    BsdfLobe,
    /// BSDF direction within the lobe (2D).
    BsdfDirection,
    /// Russian roulette (1D).
    Roulette,
}

impl BounceDim {
    /// Offset of this decision within a bounce's dimensions.
    pub const fn offset(self) -> u32 {
        match self {
            BounceDim::LightChoice => 0,
            BounceDim::LightMember => 1,
            BounceDim::LightPosition => 2,
            BounceDim::Layer => 4,
            BounceDim::BsdfLobe => 5,
            BounceDim::BsdfDirection => 6,
            BounceDim::Roulette => 8,
        }
    }
}

/// The dimension of decision `what` at bounce `bounce` (0 = the camera ray's first hit).
pub const fn bounce_dimension(bounce: u32, what: BounceDim) -> u32 {
    FIRST_BOUNCE + bounce * BOUNCE_STRIDE + what.offset()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedule_slots_do_not_overlap() {
        let mut used = std::collections::HashSet::new();
        let mut claim = |d: u32, n: u32| (d..d + n).all(|k| used.insert(k));
        assert!(claim(PIXEL, 2) && claim(LENS, 2) && claim(WAVELENGTH, 2));
        for b in 0..20 {
            assert!(claim(bounce_dimension(b, BounceDim::LightChoice), 1));
            assert!(claim(bounce_dimension(b, BounceDim::LightMember), 1));
            assert!(claim(bounce_dimension(b, BounceDim::LightPosition), 2));
            assert!(claim(bounce_dimension(b, BounceDim::Layer), 1));
            assert!(claim(bounce_dimension(b, BounceDim::BsdfLobe), 1));
            assert!(claim(bounce_dimension(b, BounceDim::BsdfDirection), 2));
            assert!(claim(bounce_dimension(b, BounceDim::Roulette), 1));
        }
        assert_eq!(used.len() as u32, FIRST_BOUNCE + 20 * BOUNCE_STRIDE);
    }
}
