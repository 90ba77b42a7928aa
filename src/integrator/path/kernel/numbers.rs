//! One vertex's random decisions for every lane ([`Draws`]), named and drawn as the scalar
//! path tracer's dimension schedule names and draws them
//! ([`crate::sampler::schedule::BounceDim`], [`crate::sampler::Bounce`]): the light
//! choice, the member and position on the chosen light, the BSDF lobe and direction,
//! Russian roulette.
//!
//! Each lane holds its camera sample's [`crate::sampler::SampleStream`] (in its
//! [`Context`], restarted by [`crate::render::Starts::start`]), and the decisions of the
//! path's vertex `b` (every scattering vertex before it counted, delta ones too) come
//! from `bounce_dimension(b, …)`, in the order the scalar path tracer reads them at such a
//! vertex ([`crate::integrator::path::vertex`]): at a Lambert or glossy vertex the layer
//! (skipped: one layer), the light choice (skipped with one light), the light position and
//! member (skipped where no light reads them), the lobe (read at a glossy vertex; skipped at
//! a Lambert one: the glTF BRDF with F0 = 0 samples its diffuse lobe whatever the number),
//! the direction and the roulette; at a
//! smooth dielectric the layer (skipped), the lobe and the direction (skipped). With the
//! Z-order Sobol' sampler a number depends on its dimension only; with `--sampler
//! independent` every number, skipped or not, advances the sample's stream in that order,
//! so a lane's numbers are the scalar path's numbers for the same sample either way.
//!
//! The roulette number is read before the lane knows whether it plays the roulette
//! ([`crate::sampler::Bounce::peek_roulette`]); [`Draws::played`] then passes over it where
//! it was played, as the scalar path draws it only then.

use crate::accel::packet::{lanes, LaneMask};
use crate::render::Context;

/// The decisions of one vertex per lane, each in [0, 1) (0 where the lane reads none).
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
    /// Russian roulette (read where the lane may play it).
    pub roulette: [f32; N],
}

/// Which lanes meet which kind of vertex, and which lights the scene has.
pub struct Vertices<'a, const N: usize> {
    /// Each lane's vertex index on its path (non-delta plus delta bounces so far).
    pub index: [u32; N],
    /// The lanes at a Lambert vertex.
    pub lambert: &'a [bool; N],
    /// The lanes at a glossy vertex ([`super::glossy`]).
    pub glossy: &'a [bool; N],
    /// The lanes at a smooth dielectric.
    pub glass: &'a [bool; N],
    /// The lanes that may play Russian roulette at this vertex (their third non-delta
    /// bounce or later).
    pub roulette: [bool; N],
    /// The lights next-event estimation chooses among.
    pub lights: usize,
    /// Whether some light reads a position and a member (an area light).
    pub area: bool,
}

impl<const N: usize> Draws<N> {
    /// The decisions at `at` of every lane's sample in `ctx` (module docs).
    #[inline(always)]
    pub fn draw(ctx: &mut [Box<Context>; N], at: &Vertices<N>) -> Self {
        let mut d = Draws {
            light_choice: [0.0; N],
            light_member: [0.0; N],
            light_position: [[0.0; N]; 2],
            lobe: [0.0; N],
            direction: [[0.0; N]; 2],
            roulette: [0.0; N],
        };
        for (i, c) in ctx.iter_mut().enumerate() {
            let (glossy, glass) = (at.glossy[i], at.glass[i]);
            if !(at.lambert[i] || glossy || glass) {
                continue;
            }
            let mut u = c.sample.bounce(at.index[i]);
            u.skip_layer();
            if glass {
                d.lobe[i] = u.bsdf_lobe();
                u.skip_bsdf_direction();
                continue;
            }
            d.light_choice[i] = if at.lights > 1 {
                u.light_choice()
            } else {
                u.skip_light_choice();
                0.0
            };
            if at.area {
                let p = u.light_position();
                (d.light_position[0][i], d.light_position[1][i]) = (p.x, p.y);
                d.light_member[i] = u.light_member();
            } else {
                u.skip_light_position();
                u.skip_light_member();
            }
            if glossy {
                d.lobe[i] = u.bsdf_lobe();
            } else {
                u.skip_bsdf_lobe();
            }
            let w = u.bsdf_direction();
            (d.direction[0][i], d.direction[1][i]) = (w.x, w.y);
            if at.roulette[i] {
                d.roulette[i] = u.peek_roulette();
            }
        }
        d
    }

    /// Passes over the roulette number of the lanes `played` (those whose roulette was
    /// played at `at`), as the scalar path draws it.
    #[inline(always)]
    pub fn played(ctx: &mut [Box<Context>; N], at: &Vertices<N>, played: LaneMask) {
        for i in lanes(played) {
            ctx[i].sample.bounce(at.index[i]).skip_roulette();
        }
    }
}
