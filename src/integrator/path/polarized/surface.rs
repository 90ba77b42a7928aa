//! The analyzer of a camera path across a surface's scattering: the surface's normalized
//! Mueller matrix ([`crate::shading::polarized::mueller`], depolarizing BSDFs as the ideal
//! depolarizer) applied in the s/p bases of its normal.
//!
//! Frames: the world directions of the light leaving (`wo`) and of where it arrived from
//! (`wi`: the light arrives along −wi).

use crate::bsdf::Bsdf;
use crate::math::Frame;
use crate::polar::stokes::{Analyzer, DEPOLARIZER};
use crate::shading::polarized::s_basis;
use crate::spectrum::Carrier;
use glam::Vec3;

/// The analyzer before a scattering at a surface with shading `frame` and BSDF `b`, the
/// path's analyzer after it being `after` (light leaving along the world `wo`), the light
/// arriving along −`wi` (world): N applied in the s/p bases of its normal.
pub(super) fn through<C: Carrier>(
    after: &Analyzer,
    b: &Bsdf<C>,
    frame: &Frame,
    (wo, wi): (Vec3, Vec3),
) -> Analyzer {
    let k_in = -wi;
    let (n, m) = match b.mueller(frame.to_local(wo), frame.to_local(wi)) {
        Some(x) => x,
        None => (DEPOLARIZER, Vec3::Z),
    };
    let s = s_basis(k_in, frame.to_world(m), after.x);
    after.through(&n, s, s, k_in, 1.0)
}
