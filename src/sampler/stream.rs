//! The random numbers of one camera sample: which sampler a render uses
//! ([`SamplerKind`]), the per-render set-up that starts each pixel sample
//! ([`PixelSampler`]), and a bounce's scheduled decisions ([`Bounce`]).
//!
//! Invariants:
//! - Sample `k` of pixel `(x, y)` is a pure function of `(seed, x, y, k)` and the render's
//!   resolution and samples per pixel (the [`ZSobol`] block), whichever sampler is chosen, so
//!   an N-sample image is bit-identical however its samples are split into rounds, threads
//!   or shards.
//! - Every sample also carries the independent PCG stream `Rng::new(&[seed, x, y, k])` for
//!   decisions outside the [`super::schedule`]. With [`SamplerKind::Independent`] every
//!   scheduled decision draws from that stream too, in the order the integrator asks, which
//!   reproduces Iris's images from before the low-discrepancy sampler bit for bit.
//! - The hero wavelength: [`SamplerKind::ZSobol`] draws it from the 2D `WAVELENGTH`
//!   dimensions, randomised by a digit shift rather than Owen scrambling so a pixel's first
//!   2^k offsets lie on a regular grid, through [`hero_number`] (the sets of wavelengths
//!   evenly spread and the heroes stratified within the pixel); the independent sampler
//!   keeps the per-pixel rank-1 lattice `u_k = frac(o + k·φ⁻¹)` with a random offset `o`
//!   (a Cranley–Patterson rotation; Owen, "Monte Carlo theory, methods and examples",
//!   §15.4).

use super::schedule::{bounce_dimension, BounceDim, PIXEL, WAVELENGTH};
use super::zsobol::{Randomize, ZSobol};
use crate::error::{parse_name, Result};
use crate::math::Rng;
use crate::spectrum::hero_number;
use glam::Vec2;

/// Which numbers drive the camera paths (`--sampler`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SamplerKind {
    /// Owen-scrambled Sobol' per pixel in Morton order (pbrt-v4 `ZSobolSampler`): the
    /// default.
    #[default]
    ZSobol,
    /// Independent PCG numbers per sample, for comparisons (no stratification).
    Independent,
}

impl SamplerKind {
    /// Every sampler, in `--help` order.
    pub const ALL: [SamplerKind; 2] = [SamplerKind::ZSobol, SamplerKind::Independent];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::ZSobol => "zsobol",
            SamplerKind::Independent => "independent",
        }
    }

    /// Parses a `--sampler` value.
    pub fn parse(s: &str) -> Result<SamplerKind> {
        parse_name("--sampler", s, &SamplerKind::ALL.map(|k| (k.name(), k)))
    }
}

/// Stream key of the per-pixel offset of the independent sampler's wavelength lattice.
const LAMBDA_KEY: u64 = 0x1A4B_DA00;
/// 1/φ, the golden ratio's fractional part: the rank-1 lattice generator.
const INV_PHI: f64 = 0.618_033_988_749_894_9;

/// A render's sampler: starts the numbers of each pixel sample. Cheap to copy.
#[derive(Debug, Clone)]
pub struct PixelSampler {
    seed: u64,
    sobol: Option<ZSobol>,
}

impl PixelSampler {
    /// The sampler of a render of `resolution` = (width, height) taking up to
    /// `samples_per_pixel` samples (the Sobol' block per pixel), keyed by `seed`.
    pub fn new(
        kind: SamplerKind,
        samples_per_pixel: u64,
        resolution: (u32, u32),
        seed: u64,
    ) -> Self {
        let sobol = match kind {
            SamplerKind::ZSobol => Some(ZSobol::new(samples_per_pixel, resolution, seed)),
            SamplerKind::Independent => None,
        };
        PixelSampler { seed, sobol }
    }

    /// Makes `stream` the numbers of sample `k` of pixel `(x, y)`: [`PixelSampler::start`]
    /// without building a new stream (the per-sample loops reuse one per tile).
    pub fn restart(&self, stream: &mut SampleStream, x: u32, y: u32, k: u64) {
        stream.rng = Rng::new(&[self.seed, u64::from(x), u64::from(y), k]);
        stream.lattice = (self.seed, x, y, k);
        match (&self.sobol, &mut stream.sobol) {
            (Some(_), Some(z)) => z.start_pixel_sample(x, y, k),
            _ => *stream = self.start(x, y, k),
        }
    }

    /// The numbers of sample `k` of pixel `(x, y)`.
    pub fn start(&self, x: u32, y: u32, k: u64) -> SampleStream {
        let rng = Rng::new(&[self.seed, u64::from(x), u64::from(y), k]);
        let sobol = self.sobol.clone().map(|mut z| {
            z.start_pixel_sample(x, y, k);
            z
        });
        SampleStream {
            rng,
            sobol,
            lattice: (self.seed, x, y, k),
        }
    }
}

/// The numbers of one pixel sample.
#[derive(Debug, Clone)]
pub struct SampleStream {
    /// The sample's independent stream (decisions outside the schedule).
    pub rng: Rng,
    sobol: Option<ZSobol>,
    /// (seed, x, y, k): the independent sampler's wavelength lattice point.
    lattice: (u64, u32, u32, u64),
}

impl SampleStream {
    /// Numbers from `rng` alone (photon paths, tests): every decision draws the stream in
    /// order.
    pub fn independent(rng: Rng) -> Self {
        SampleStream {
            rng,
            sobol: None,
            lattice: (0, 0, 0, 0),
        }
    }

    /// A 1D number of dimension `dim` (the stream's next number without Sobol').
    pub fn get_1d(&mut self, dim: u32) -> f32 {
        match &mut self.sobol {
            Some(z) => {
                z.set_dimension(dim);
                z.get_1d()
            }
            None => self.rng.next_f32(),
        }
    }

    /// A 2D number of dimensions `dim`, `dim + 1`.
    pub fn get_2d(&mut self, dim: u32) -> Vec2 {
        match &mut self.sobol {
            Some(z) => {
                z.set_dimension(dim);
                Vec2::from(z.get_2d())
            }
            None => {
                let u = self.rng.next_f32();
                Vec2::new(u, self.rng.next_f32())
            }
        }
    }

    /// The film position within the pixel, in `[0, 1)²`.
    pub fn pixel(&mut self) -> Vec2 {
        self.get_2d(PIXEL)
    }

    /// The hero-wavelength number in `[0, 1)` (see the module docs).
    pub fn wavelength(&mut self) -> f32 {
        if let Some(z) = &mut self.sobol {
            z.set_dimension(WAVELENGTH);
            let [offset, member] = z.get_2d_with(Randomize::Xor);
            return hero_number(offset, member);
        }
        let (seed, x, y, k) = self.lattice;
        let offset = Rng::new(&[seed, u64::from(x), u64::from(y), LAMBDA_KEY]).next_f32() as f64;
        ((offset + k as f64 * INV_PHI).fract() as f32).min(1.0 - f32::EPSILON)
    }

    /// The decisions of scattering vertex `vertex` of the path (0 = the camera ray's hit).
    pub fn bounce(&mut self, vertex: u32) -> Bounce<'_> {
        Bounce {
            stream: self,
            vertex,
        }
    }
}

/// The scheduled decisions of one vertex of a camera path ([`super::schedule`]).
pub struct Bounce<'a> {
    stream: &'a mut SampleStream,
    vertex: u32,
}

impl Bounce<'_> {
    fn one(&mut self, what: BounceDim) -> f32 {
        self.stream.get_1d(bounce_dimension(self.vertex, what))
    }

    fn two(&mut self, what: BounceDim) -> Vec2 {
        self.stream.get_2d(bounce_dimension(self.vertex, what))
    }

    /// Passes over a decision this vertex does not need (a single light, a point light's
    /// position, a material with one layer): the Sobol' dimensions are fixed by the schedule,
    /// so nothing is computed; the independent sampler still draws its `n` numbers, so every
    /// later decision gets the number it had when this one was drawn.
    fn skip(&mut self, n: u32) {
        if self.stream.sobol.is_none() {
            for _ in 0..n {
                self.stream.rng.next_f32();
            }
        }
    }

    /// [`Bounce::light_choice`] not needed (one light to choose from).
    pub fn skip_light_choice(&mut self) {
        self.skip(1);
    }

    /// [`Bounce::light_member`] not needed (the light is not an emissive group).
    pub fn skip_light_member(&mut self) {
        self.skip(1);
    }

    /// [`Bounce::light_position`] not needed (a punctual light).
    pub fn skip_light_position(&mut self) {
        self.skip(2);
    }

    /// [`Bounce::layer`] not needed (the material has one layer here).
    pub fn skip_layer(&mut self) {
        self.skip(1);
    }

    /// [`Bounce::bsdf_lobe`] not needed (a BSDF with one lobe).
    pub fn skip_bsdf_lobe(&mut self) {
        self.skip(1);
    }

    /// [`Bounce::bsdf_direction`] not needed (a smooth dielectric's choice is the lobe's).
    pub fn skip_bsdf_direction(&mut self) {
        self.skip(2);
    }

    /// Which light group next-event estimation samples.
    pub fn light_choice(&mut self) -> f32 {
        self.one(BounceDim::LightChoice)
    }

    /// Which member of the group (emissive triangle).
    pub fn light_member(&mut self) -> f32 {
        self.one(BounceDim::LightMember)
    }

    /// The position on the chosen light (or the environment's direction).
    pub fn light_position(&mut self) -> Vec2 {
        self.two(BounceDim::LightPosition)
    }

    /// Which layer of the material scatters.
    pub fn layer(&mut self) -> f32 {
        self.one(BounceDim::Layer)
    }

    /// The BSDF lobe.
    pub fn bsdf_lobe(&mut self) -> f32 {
        self.one(BounceDim::BsdfLobe)
    }

    /// The BSDF direction within the lobe.
    pub fn bsdf_direction(&mut self) -> Vec2 {
        self.two(BounceDim::BsdfDirection)
    }

    /// [`Bounce::bsdf_direction`] for a BSDF that `samples` a direction, else skipped
    /// (zero): what every camera vertex draws.
    pub fn bsdf_direction_if(&mut self, samples: bool) -> Vec2 {
        if samples {
            self.bsdf_direction()
        } else {
            self.skip_bsdf_direction();
            Vec2::ZERO
        }
    }

    /// Russian roulette.
    pub fn roulette(&mut self) -> f32 {
        self.one(BounceDim::Roulette)
    }

    /// The number [`Bounce::roulette`] would return, without drawing it: the independent
    /// sampler's stream stays where it is. For a caller that needs the number before it
    /// knows whether the roulette is played (the SoA kernel's lanes); once it does, it
    /// passes over the number with [`Bounce::skip_roulette`] where the roulette was played.
    pub fn peek_roulette(&mut self) -> f32 {
        match self.stream.sobol {
            Some(_) => self.roulette(),
            None => self.stream.rng.clone().next_f32(),
        }
    }

    /// Passes over the roulette number (read before by [`Bounce::peek_roulette`]).
    pub fn skip_roulette(&mut self) {
        self.skip(1);
    }

    /// BLEND coverage: outside the schedule, from the independent stream.
    pub fn alpha(&mut self) -> f32 {
        self.stream.rng.next_f32()
    }

    /// The sample's independent stream.
    pub fn rng(&mut self) -> &mut Rng {
        &mut self.stream.rng
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn independent_draws_the_stream_in_order() {
        let p = PixelSampler::new(SamplerKind::Independent, 16, (8, 8), 3);
        let mut s = p.start(2, 5, 7);
        let mut r = Rng::new(&[3, 2, 5, 7]);
        let mut b = s.bounce(4);
        assert_eq!(b.light_choice(), r.next_f32());
        assert_eq!(b.light_position(), Vec2::new(r.next_f32(), r.next_f32()));
        assert_eq!(b.roulette(), r.next_f32());
    }

    #[test]
    fn sobol_decisions_do_not_depend_on_draw_order() {
        let p = PixelSampler::new(SamplerKind::ZSobol, 16, (8, 8), 3);
        let (mut a, mut b) = (p.start(2, 5, 7), p.start(2, 5, 7));
        let r1 = a.bounce(2).roulette();
        let mut bb = b.bounce(2);
        let _ = bb.light_position();
        let _ = bb.bsdf_direction();
        assert_eq!(bb.roulette(), r1);
        assert_ne!(a.bounce(3).roulette(), r1);
    }

    #[test]
    fn skipped_decisions_keep_every_later_number() {
        for kind in SamplerKind::ALL {
            let p = PixelSampler::new(kind, 16, (8, 8), 3);
            let (mut a, mut b) = (p.start(2, 5, 7), p.start(2, 5, 7));
            let mut ba = a.bounce(1);
            let _ = ba.light_choice();
            let _ = ba.light_position();
            let _ = ba.light_member();
            let _ = ba.layer();
            let want = (ba.bsdf_lobe(), ba.bsdf_direction(), ba.roulette());
            let mut bb = b.bounce(1);
            bb.skip_light_choice();
            bb.skip_light_position();
            bb.skip_light_member();
            bb.skip_layer();
            assert_eq!((bb.bsdf_lobe(), bb.bsdf_direction(), bb.roulette()), want);
            let (mut c, mut d) = (p.start(1, 1, 2), p.start(1, 1, 2));
            let (mut bc, mut bd) = (c.bounce(0), d.bounce(0));
            let _ = bc.bsdf_lobe();
            let _ = bc.bsdf_direction();
            bd.skip_bsdf_lobe();
            bd.skip_bsdf_direction();
            // A peeked roulette number is the drawn one, and passing over it afterwards
            // leaves the stream where drawing it does.
            let peeked = bd.peek_roulette();
            assert_eq!(bc.roulette(), peeked);
            bd.skip_roulette();
            assert_eq!(c.bounce(1).bsdf_lobe(), d.bounce(1).bsdf_lobe());
            assert_eq!(a.rng.next_u32(), b.rng.next_u32());
        }
    }

    #[test]
    fn restart_equals_start() {
        for kind in SamplerKind::ALL {
            let p = PixelSampler::new(kind, 8, (16, 16), 5);
            let mut s = p.start(0, 0, 0);
            for (x, y, k) in [(3, 4, 2), (15, 0, 7), (3, 4, 9)] {
                p.restart(&mut s, x, y, k);
                let mut fresh = p.start(x, y, k);
                assert_eq!(s.wavelength(), fresh.wavelength());
                assert_eq!(
                    s.bounce(1).bsdf_direction(),
                    fresh.bounce(1).bsdf_direction()
                );
                assert_eq!(s.rng.next_u32(), fresh.rng.next_u32());
            }
        }
    }

    #[test]
    fn parse_names_every_sampler() {
        for k in SamplerKind::ALL {
            assert_eq!(SamplerKind::parse(k.name()).unwrap(), k);
        }
        let e = SamplerKind::parse("halton").unwrap_err().to_string();
        assert!(e.contains("--sampler") && e.contains("zsobol"), "{e}");
    }
}
