//! SPPM's and the photon map's camera paths ([`VisiblePoints`]): the path tracer's loop up
//! to the first diffuse-like hit ([`crate::bsdf::Bsdf::is_diffuse_like`]), the visible point where photons are
//! gathered; its direct light is still estimated there, with full weight, as BSDF sampling
//! does not continue. The paths never split into their wavelengths (a pass stores one
//! visible point per pixel); with spectral MIS they keep their 4 wavelengths at rough
//! dispersive interfaces under their own hero ([`crate::integrator::path::HeroOf`], whose
//! module proves the gather unbiased), otherwise the hero only.

use crate::integrator::path::{RoughLanes, Strategy};
use crate::shading::Surface;
use crate::spectrum::Carrier;

/// Camera paths that stop at a visible point (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VisiblePoints {
    /// Keep the 4 wavelengths at rough dispersive interfaces with spectral MIS under the
    /// path's own hero ([`crate::integrator::SppmSettings::spectral_mis`]); off: the hero
    /// only.
    pub spectral_mis: bool,
}

impl<C: Carrier> Strategy<C> for VisiblePoints {
    const STOPS: bool = true;

    fn rough(&self) -> RoughLanes {
        if self.spectral_mis {
            RoughLanes::OwnHero
        } else {
            RoughLanes::Hero
        }
    }

    fn splits(&self) -> bool {
        false
    }

    fn stops_at(&self, s: &Surface<C>) -> bool {
        s.bsdf.is_diffuse_like()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::SampledSpectrum;

    /// Visible points draw their own hero only with spectral MIS, never split, and stop.
    #[test]
    fn visible_points_keep_their_own_hero_and_stop() {
        type S = SampledSpectrum;
        let on = VisiblePoints { spectral_mis: true };
        let off = VisiblePoints {
            spectral_mis: false,
        };
        assert_eq!(Strategy::<S>::rough(&on), RoughLanes::OwnHero);
        assert_eq!(Strategy::<S>::rough(&off), RoughLanes::Hero);
        assert!(!Strategy::<S>::splits(&on));
        const { assert!(<VisiblePoints as Strategy<S>>::STOPS) };
    }
}
