//! The kernel's side of a lane's vertex on the scalar vertex ([`super::handoff`]): the
//! lane's state handed over in the scalar path's form and, when the path goes on, taken
//! back into the lane's arrays (throughput, wavelengths, the next ray, bounce counts, MIS
//! record, the volume it is in).
//!
//! Units: as [`super::paths`].

use super::super::state::Prev;
use super::colour::{lane, set_lane, take};
use super::handoff::{Back, Handed, Handing};
use super::paths::Paths;
use super::rules::{history, Rules};
use super::state::NONE_YET;
use crate::accel::packet::{lanes, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::math::Ray;
use crate::scene::Scene;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum};
use glam::Vec3;

/// [`Back`] in the lane's channels.
enum Returned<const M: usize> {
    /// The path ended with this radiance gathered from the hit on.
    Ended([f32; M]),
    /// It goes on: radiance at the vertex, throughput, wavelengths (spectral), next ray,
    /// the rest of the state.
    Goes([f32; M], [f32; M], Option<Lambdas>, Ray, Handed),
}

/// `back` in `M` channels (`lanes` a value's channels, `lam` its wavelengths).
fn channels<C: Carrier, const M: usize>(
    back: Back<C>,
    lanes: impl Fn(C) -> [f32; M],
    lam: impl Fn(C::Lambda) -> Option<Lambdas>,
) -> Returned<M> {
    match back {
        Back::Ended(e) => Returned::Ended(lanes(e)),
        Back::Goes {
            l,
            carried: (beta, lambda),
            ray,
            state,
        } => Returned::Goes(lanes(l), lanes(beta), lam(lambda), ray, state),
    }
}

impl<const N: usize, const M: usize> Paths<N, M> {
    /// Lane `i`'s state but throughput and wavelengths, as the scalar path holds it.
    fn handed(&self, i: usize) -> Handed {
        let st = &self.st;
        Handed {
            eta_scale: st.eta_scale[i],
            depth: st.depth[i],
            deltas: st.deltas[i],
            since_diffuse: (st.since[i] != NONE_YET).then_some(st.since[i]),
            inside: st.medium[i].checked_sub(1),
            prev: Prev {
                delta: st.prev_delta[i],
                pdf: st.prev_pdf[i],
                p: Vec3::new(st.prev_p[0][i], st.prev_p[1][i], st.prev_p[2][i]),
            },
        }
    }

    /// Lane `i` takes back the state `h` the scalar vertex left.
    fn take_back(&mut self, i: usize, h: &Handed) {
        let st = &mut self.st;
        st.eta_scale[i] = h.eta_scale;
        st.depth[i] = h.depth;
        st.deltas[i] = h.deltas;
        st.since[i] = h.since_diffuse.unwrap_or(NONE_YET);
        st.medium[i] = h.inside.map_or(0, |m| m + 1);
        st.prev_delta[i] = h.prev.delta;
        st.prev_pdf[i] = h.prev.pdf;
        (0..3).for_each(|c| st.prev_p[c][i] = h.prev.p[c]);
    }

    /// Shades lane `i`'s vertex, whose ray in `packet` met a material the kernel does not
    /// shade (or where the strategy gathers), on the scalar vertex of `rules`
    /// ([`handoff::Vertex`]) with the lane's own sample stream: adds what it gathers to the
    /// lane's radiance and, when the path goes on, takes its state back. Returns the rays
    /// traced and whether the path goes on.
    pub(super) fn hand_over(
        &mut self,
        i: usize,
        scene: &Scene,
        packet: &RayPacket<N>,
        rules: &Rules,
    ) -> (u64, bool)
    where
        Lanes<N>: PacketWidth,
    {
        let Some(r) = packet.hit(i) else {
            return (0, false);
        };
        let handed = self.handed(i);
        let at = (Ray::new(packet.origin(i), packet.dir(i)), r);
        let ctx = &mut self.ctx[i];
        let before = ctx.rays;
        let beta = lane(&self.st.beta, i);
        let back = match rules {
            Rules::Spectral(v, _) => {
                let carried = (SampledSpectrum::from_lanes(take(beta)), self.lam[i]);
                let back = v.vertex(scene, Handing::new(handed, carried, at), ctx);
                channels(back, |v| take(v.to_lanes()), Some)
            }
            Rules::Rgb(v) => {
                let carried = (Vec3::from_array(take(beta)), ());
                let back = v.vertex(scene, Handing::new(handed, carried, at), ctx);
                channels(back, |v| take(v.to_array()), |_| None)
            }
        };
        let rays = ctx.rays - before;
        match back {
            Returned::Ended(e) => {
                (0..M).for_each(|c| self.l[c][i] += e[c]);
                (rays, false)
            }
            Returned::Goes(l, beta, lam, next, state) => {
                (0..M).for_each(|c| self.l[c][i] += l[c]);
                set_lane(&mut self.st.beta, i, beta);
                if let Some(lam) = lam {
                    self.lam[i] = lam;
                }
                for c in 0..3 {
                    self.next.o[c][i] = next.origin[c];
                    self.next.d[c][i] = next.dir[c];
                }
                self.next.t_max[i] = next.t_max;
                self.take_back(i, &state);
                (rays, true)
            }
        }
    }

    /// Adds to the lanes `on` (at a Lambert or glossy vertex where the strategy of `rules`
    /// gathers, their rays and hits in `packet`) what it gathers there
    /// ([`super::handoff::Vertex::gather`]), times the lane's throughput.
    pub(super) fn gather(
        &mut self,
        on: LaneMask,
        scene: &Scene,
        packet: &RayPacket<N>,
        rules: &Rules,
    ) where
        Lanes<N>: PacketWidth,
    {
        let max_depth = rules.max_depth();
        for i in lanes(on) {
            let Some(r) = packet.hit(i) else {
                continue;
            };
            let at = (Ray::new(packet.origin(i), packet.dir(i)), r);
            let h = history(&self.st, i, max_depth);
            let inside = self.st.medium[i].checked_sub(1);
            let g: Option<[f32; M]> = match rules {
                Rules::Spectral(v, _) => v
                    .gather(scene, at, (self.lam[i], inside), &h)
                    .map(|g| take(g.to_lanes())),
                Rules::Rgb(v) => v
                    .gather(scene, at, ((), inside), &h)
                    .map(|g| take(g.to_array())),
            };
            for (c, g) in g.iter().flatten().enumerate() {
                self.l[c][i] += self.st.beta[c][i] * g;
            }
        }
    }
}
