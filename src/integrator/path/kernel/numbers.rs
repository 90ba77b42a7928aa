//! One bounce's random decisions for every lane ([`Draws`]), named as the scalar path
//! tracer's dimension schedule names them ([`crate::sampler::schedule::BounceDim`]): the
//! light choice, the member and position on the chosen light, the BSDF lobe and
//! direction, Russian roulette. Every lane draws every decision each turn, used or not,
//! so a sample's numbers do not depend on which decisions its neighbours took.
//!
//! The numbers come from each lane's own stream ([`super::rng`]).

use super::rng;

/// The decisions of one vertex per lane, each in [0, 1).
#[allow(dead_code)] // the light member and position: lights with an area
pub struct Draws<const N: usize> {
    /// Which light (group) next-event estimation samples.
    pub light_choice: [f32; N],
    /// Which member of the chosen group (an emissive triangle).
    pub light_member: [f32; N],
    /// The position on the chosen light (2D).
    pub light_position: [[f32; N]; 2],
    /// Which lobe the BSDF samples (reflection or transmission).
    pub lobe: [f32; N],
    /// The direction within the lobe (2D).
    pub direction: [[f32; N]; 2],
    /// Russian roulette.
    pub roulette: [f32; N],
}

impl<const N: usize> Draws<N> {
    /// The next vertex's decisions of every lane from its stream (`counter`, `salt`).
    #[inline(always)]
    pub fn draw(counter: &mut [u32; N], salt: &[u32; N]) -> Self {
        let mut next = || rng::draw(counter, salt);
        Draws {
            light_choice: next(),
            light_member: next(),
            light_position: [next(), next()],
            lobe: next(),
            direction: [next(), next()],
            roulette: next(),
        }
    }
}
