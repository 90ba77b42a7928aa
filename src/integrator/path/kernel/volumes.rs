//! Beer–Lambert absorption on the segments inside an absorbing glass ([`absorb`]), as the
//! scalar path tracer takes it ([`crate::shading::arrival`] with
//! [`crate::medium_stack::segment_medium`] and [`crate::material::Material::transmittance_at`]):
//! the segment's medium is the glass volume the path entered (the kernel's volumes never
//! nest, so its medium stack holds at most one: [`super::shade::Throughput::medium`]), or,
//! in air, the volume whose back face the ray hits (a path starting inside); its
//! transmittance e^(−σx) = c^(x/d) per channel over the segment's length x (in spectral
//! transport c is the attenuation colour's reflectance at the lane's wavelengths, through
//! the material's own [`crate::material::Material::transmittance_at`]).
//!
//! Units: lengths in scene units (metres); σ per scene unit.

use super::colour::{spectral, transmittance};
use super::features::Tables;
use super::hits::{dot, Hits};
use super::state::Throughput;
use crate::accel::packet::{lanes, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::scene::Scene;
use crate::spectrum::Lambdas;

/// Multiplies β of `st` by the transmittance of the segment each lane `hit` crossed along
/// its ray in `rays` (`t_max` lowered to the hit, [`RayPacket::hit`]) to its hit in `h`,
/// at the lanes' wavelengths `lam`.
#[inline(always)]
pub fn absorb<const N: usize, const M: usize>(
    (tables, scene, lam): (&Tables, &Scene, &[Lambdas; N]),
    rays: &RayPacket<N>,
    (h, hit): (&Hits<N, M>, LaneMask),
    st: &mut Throughput<N, M>,
) where
    Lanes<N>: PacketWidth,
{
    let mut sigma = [[0.0f32; N]; 3];
    let mut inside = [u32::MAX; N];
    let mut any = false;
    for i in lanes(hit) {
        let back = dot(&h.wo, &h.ng, i) < 0.0;
        let m = match st.medium[i] {
            0 if back => h.material[i],
            0 => continue,
            m => m - 1,
        };
        let s = tables.absorption[m as usize];
        any |= s != [0.0; 3];
        inside[i] = if s != [0.0; 3] { m } else { u32::MAX };
        (0..3).for_each(|c| sigma[c][i] = s[c]);
    }
    if !any {
        return;
    }
    let x: [f32; N] = std::array::from_fn(|i| {
        let d = [rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]];
        rays.t_max[i] * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    });
    if spectral::<M>() {
        for i in (0..N).filter(|&i| inside[i] != u32::MAX) {
            let m = &scene.materials()[inside[i] as usize];
            let t = transmittance::<M>(m, x[i], &lam[i]);
            (0..M).for_each(|c| st.beta[c][i] *= t[c]);
        }
        return;
    }
    for (beta, sigma) in st.beta.iter_mut().zip(&sigma) {
        for ((b, s), x) in beta.iter_mut().zip(sigma).zip(&x) {
            // σ = ∞ (a black channel) at x = 0 would be NaN: c^0 = 1.
            let t = if *s > 0.0 && *x > 0.0 {
                (-s * x).exp()
            } else {
                1.0
            };
            *b *= t;
        }
    }
}
