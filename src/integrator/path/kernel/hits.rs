//! The hit records of a packet in structure-of-arrays form ([`Hits`]), built from Embree's
//! SoA hit packet ([`HitPacket`]) with the intersection layer's conventions
//! ([`crate::interaction`]): the position from barycentrics, the outward geometric normal
//! `ng` of the triangle, the interpolated shading normal flipped onto `ng`'s side (or `ng`
//! without vertex normals), `wo` the unit direction back along the ray, and the offset for
//! rays leaving the hit, [`OFFSET_SCALE`] × the triangle's largest coordinate magnitude
//! ([`crate::scene::Triangle::offset`]). Only the triangle's vertices, vertex normals and
//! material are gathered lane by lane; the rest is arithmetic over the lanes.
//!
//! Units: world space (metres); normals and `wo` unit length.

use super::colour::{reflectance, set_lane, spectral, Channels};
use super::features::Shade;
use crate::accel::packet::{lanes, HitPacket, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::scene::triangle::{geometric_normal, OFFSET_SCALE};
use crate::scene::{Scene, Triangle};
use crate::spectrum::Lambdas;
use glam::Vec3;

/// Three coordinates (x, y, z) or colour channels (r, g, b), each over the lanes.
pub type V3<const N: usize> = [[f32; N]; 3];

/// A [`V3`] of zeros.
pub const fn zero3<const N: usize>() -> V3<N> {
    [[0.0; N]; 3]
}

/// The dot product of two [`V3`]s at lane `i`.
#[inline(always)]
pub fn dot<const N: usize>(a: &V3<N>, b: &V3<N>, i: usize) -> f32 {
    a[0][i] * b[0][i] + a[1][i] * b[1][i] + a[2][i] * b[2][i]
}

/// The hits of one packet, lane `i` meaningful where `lambert[i]`, `glossy[i]`, `glass[i]`
/// or `scalar[i]` is set; colours in `M` channels ([`super::colour`]).
pub struct Hits<const N: usize, const M: usize> {
    /// Position.
    pub p: V3<N>,
    /// Unit geometric normal, outward.
    pub ng: V3<N>,
    /// Unit shading normal, on `ng`'s side.
    pub ns: V3<N>,
    /// Unit direction back along the ray.
    pub wo: V3<N>,
    /// Offset of rays leaving the hit.
    pub offset: [f32; N],
    /// The lane met a Lambert surface.
    pub lambert: [bool; N],
    /// The lane met a lobe the scalar BSDF shades per lane ([`super::glossy`]): a glTF
    /// BRDF with a specular or metal part, or rough glass.
    pub glossy: [bool; N],
    /// The lane met the dielectric.
    pub glass: [bool; N],
    /// The lane met a material the scalar vertex shades ([`Shade::Scalar`]).
    pub scalar: [bool; N],
    /// Lambert albedo or dielectric tint at the lane's wavelengths.
    pub col: Channels<N, M>,
    /// The dielectric's η, smooth or rough (1 elsewhere); at a dispersive one in spectral
    /// transport, η at the lane's hero wavelength.
    pub eta: [f32; N],
    /// The lane met a dispersive dielectric in spectral transport: its path keeps only
    /// the hero wavelength or splits there ([`super::branches`]).
    pub disperses: [bool; N],
    /// The triangle's material index.
    pub material: [u32; N],
    /// The triangle's index.
    pub prim: [u32; N],
}

/// What is gathered per lane: the triangle's vertices and vertex normals (zero without
/// them), and the barycentrics.
struct Gathered<const N: usize> {
    p: [V3<N>; 3],
    n: [V3<N>; 3],
    u: [f32; N],
    v: [f32; N],
}

impl<const N: usize, const M: usize> Hits<N, M>
where
    Lanes<N>: PacketWidth,
{
    /// The hits of the lanes `hit` of `raw`, traced along `rays`, shaded as `shades` says,
    /// their colours at the lanes' wavelengths `lam`.
    #[inline(always)]
    pub fn new(
        (scene, shades): (&Scene, &[Shade]),
        rays: &RayPacket<N>,
        raw: &HitPacket<N>,
        hit: LaneMask,
        lam: &[Lambdas; N],
    ) -> Hits<N, M> {
        let mut h = Hits {
            p: zero3(),
            ng: zero3(),
            ns: zero3(),
            wo: zero3(),
            offset: [0.0; N],
            lambert: [false; N],
            glossy: [false; N],
            glass: [false; N],
            scalar: [false; N],
            col: [[0.0; N]; M],
            eta: [1.0; N],
            disperses: [false; N],
            material: [0; N],
            prim: raw.prim,
        };
        let g = h.gather((scene, shades), raw, hit, lam);
        h.geometry(&g, rays);
        h
    }

    /// The per-lane reads: triangle vertices, vertex normals, material (its colour at the
    /// lane's wavelengths `lam`).
    #[inline(always)]
    fn gather(
        &mut self,
        (scene, shades): (&Scene, &[Shade]),
        raw: &HitPacket<N>,
        hit: LaneMask,
        lam: &[Lambdas; N],
    ) -> Gathered<N> {
        let mut g = Gathered {
            p: [zero3(); 3],
            n: [zero3(); 3],
            u: raw.u,
            v: raw.v,
        };
        let normals = &scene.vertices().normals;
        for i in lanes(hit) {
            let tri = scene.triangle(raw.prim[i]);
            for (k, q) in tri.p.iter().enumerate() {
                g.p[k][0][i] = q.x;
                g.p[k][1][i] = q.y;
                g.p[k][2][i] = q.z;
            }
            if tri.has(Triangle::HAS_NORMALS) {
                for (k, &vi) in tri.vertices.iter().enumerate() {
                    let q = normals[vi as usize];
                    g.n[k][0][i] = q.x;
                    g.n[k][1][i] = q.y;
                    g.n[k][2][i] = q.z;
                }
            }
            self.material[i] = tri.material();
            match shades[tri.material() as usize] {
                Shade::Lambert(albedo) => {
                    self.lambert[i] = true;
                    set_lane(&mut self.col, i, reflectance::<M>(albedo, &lam[i]));
                }
                Shade::Glass {
                    eta,
                    tint,
                    dispersive,
                } => {
                    self.glass[i] = true;
                    let disperses = spectral::<M>() && dispersive;
                    self.eta[i] = if disperses {
                        let m = &scene.materials()[tri.material() as usize];
                        m.ior_at(Some(lam[i].wl.hero()), true)
                    } else {
                        eta
                    };
                    self.disperses[i] = disperses;
                    set_lane(&mut self.col, i, reflectance::<M>(tint, &lam[i]));
                }
                Shade::Glossy => self.glossy[i] = true,
                Shade::RoughGlass { eta } => {
                    self.glossy[i] = true;
                    self.eta[i] = eta;
                }
                Shade::Scalar => self.scalar[i] = true,
                Shade::Unused => {}
            }
        }
        g
    }

    /// Position, normals, `wo` and offset over all lanes (the intersection layer's
    /// `make_hit` as arithmetic over the lanes).
    #[inline(always)]
    fn geometry(&mut self, g: &Gathered<N>, rays: &RayPacket<N>) {
        let [p0, p1, p2] = &g.p;
        let [n0, n1, n2] = &g.n;
        for i in 0..N {
            let (u, v) = (g.u[i], g.v[i]);
            let w = 1.0 - u - v;
            let mut e1 = [0.0; 3];
            let mut e2 = [0.0; 3];
            let mut ns = [0.0; 3];
            let mut mag = 0.0f32;
            for c in 0..3 {
                self.p[c][i] = p0[c][i] * w + p1[c][i] * u + p2[c][i] * v;
                e1[c] = p1[c][i] - p0[c][i];
                e2[c] = p2[c][i] - p0[c][i];
                ns[c] = n0[c][i] * w + n1[c][i] * u + n2[c][i] * v;
                mag = mag
                    .max(p0[c][i].abs())
                    .max(p1[c][i].abs())
                    .max(p2[c][i].abs());
            }
            let cx = e1[1] * e2[2] - e1[2] * e2[1];
            let cy = e1[2] * e2[0] - e1[0] * e2[2];
            let cz = e1[0] * e2[1] - e1[1] * e2[0];
            let rcp = 1.0 / (cx * cx + cy * cy + cz * cz).sqrt();
            // A cross product whose square over- or underflows (a huge or tiny triangle)
            // takes the scalar rule's rescaling below; a degenerate triangle (never
            // returned by the backends) gets +z there.
            let ok = rcp.is_finite() && rcp > 0.0;
            let ng = if ok {
                [cx * rcp, cy * rcp, cz * rcp]
            } else {
                let p = [p0, p1, p2].map(|q| Vec3::new(q[0][i], q[1][i], q[2][i]));
                geometric_normal(p).unwrap_or(Vec3::Z).to_array()
            };
            let nrcp = 1.0 / (ns[0] * ns[0] + ns[1] * ns[1] + ns[2] * ns[2]).sqrt();
            let has = nrcp.is_finite() && nrcp > 0.0;
            let side = ns[0] * ng[0] + ns[1] * ng[1] + ns[2] * ng[2];
            let s = if side < 0.0 { -nrcp } else { nrcp };
            let d = [rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]];
            let inv = 1.0 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            for c in 0..3 {
                self.ng[c][i] = ng[c];
                self.ns[c][i] = if has { ns[c] * s } else { ng[c] };
                self.wo[c][i] = -d[c] * inv;
            }
            self.offset[i] = mag * OFFSET_SCALE;
        }
    }
}
