//! Thin-film interference: the reflectance of one homogeneous film on a substrate, as
//! KHR_materials_iridescence asks (Belcour & Barla 2017, "A Practical Extension to
//! Microfacet Theory for the Modeling of Varying Iridescence", §3; Born & Wolf,
//! *Principles of Optics*, §1.6.4 "Theory of stratified media", eqs. 57–58).
//!
//! Stack: outside (index 1, the glTF "outside IOR"), a film of real index `n_film` and
//! thickness `d` (nm), a substrate of complex index η + iκ (κ = 0 for a dielectric).
//! Per polarisation (s and p) the amplitude reflectance is the Airy sum of the two
//! interfaces' Fresnel amplitudes r₀₁ and r₁₂,
//!
//! r = (r₀₁ + r₁₂ e^{2iδ}) / (1 + r₀₁ r₁₂ e^{2iδ}),  δ = 2π n_film d cos θ₁ / λ,
//!
//! so the round-trip phase is 4π n_film d cos θ₁/λ; the interfaces' own phase shifts (π at
//! a denser medium, the complex phase at a metal) are carried by the signs and phases of
//! the complex r's. The unpolarised reflectance is (|r_s|² + |r_p|²)/2. Everything is
//! evaluated in f64 with the time convention e^{−iωt} (absorbing media have κ > 0, the
//! principal square roots give decaying waves).
//!
//! Limits (tested in `tests::iridescence`): d = 0 gives the bare substrate's exact Fresnel
//! reflectance (r = r₀₂ identically), so a film thinner than ~λ/(4 n_film) fades into the
//! plain interface continuously; a quarter-wave layer at normal incidence gives
//! ((n₀n₂ − n₁²)/(n₀n₂ + n₁²))², a half-wave layer the bare substrate; for real indices
//! R + T = 1.
//!
//! Units: λ and d in nm; cosines of the angle in the outside medium, in [0, 1].

use crate::math::Complex;

/// Fresnel amplitude coefficients (r_s, r_p) from medium a to medium b, given n·cos θ in
/// each (`na_ca` = n_a cos θ_a) and the indices (Born & Wolf §1.5.2, eq. 21, with
/// r_p = (n_b cos θ_a − n_a cos θ_b)/(n_b cos θ_a + n_a cos θ_b)).
fn amplitudes(na: Complex, ca: Complex, nb: Complex, cb: Complex) -> (Complex, Complex) {
    let (a, b) = (na * ca, nb * cb);
    let rs = (a - b) / (a + b);
    let (pa, pb) = (nb * ca, na * cb);
    let rp = (pa - pb) / (pa + pb);
    (rs, rp)
}

/// e^{i z} for complex z.
fn exp_i(z: Complex) -> Complex {
    let m = (-z.im).exp();
    Complex::new(m * z.re.cos(), m * z.re.sin())
}

/// cos θ in a medium of index `n` for light arriving from index 1 at sin²θ₀ = `sin2`
/// (Snell; principal root, complex under total internal reflection or absorption).
fn cos_in(n: Complex, sin2: f64) -> Complex {
    (Complex::real(1.0) - Complex::real(sin2) / (n * n)).sqrt()
}

/// Unpolarised reflectance R and transmittance T (into the substrate) of the film stack at
/// wavelength `lambda_nm` for incidence cosine `cos0` (outside, index 1). T is exact for a
/// real substrate index and meaningless (returned as 1 − R − absorption is unknown) for an
/// absorbing one; callers of T use real indices. `d_nm` = 0 is the bare interface.
pub fn airy(cos0: f32, n_film: f32, d_nm: f32, eta: f32, kappa: f32, lambda_nm: f32) -> (f64, f64) {
    let c0 = f64::from(cos0.clamp(0.0, 1.0));
    let sin2 = (1.0 - c0) * (1.0 + c0);
    let n0 = Complex::real(1.0);
    let n1 = Complex::real(f64::from(n_film));
    let n2 = Complex::new(f64::from(eta), f64::from(kappa.max(0.0)));
    let (cc0, c1, c2) = (Complex::real(c0), cos_in(n1, sin2), cos_in(n2, sin2));
    let (r01s, r01p) = amplitudes(n0, cc0, n1, c1);
    let (r12s, r12p) = amplitudes(n1, c1, n2, c2);
    // Round-trip phase factor e^{2iδ}, δ = 2π n₁ d cos θ₁ / λ.
    let delta = n1 * c1 * (2.0 * std::f64::consts::PI * f64::from(d_nm) / f64::from(lambda_nm));
    let e2 = exp_i(delta * 2.0);
    let e1 = exp_i(delta);
    let one = Complex::real(1.0);
    let r = |r01: Complex, r12: Complex| (r01 + r12 * e2) / (one + r01 * r12 * e2);
    let (rs, rp) = (r(r01s, r12s), r(r01p, r12p));
    let reflect = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
    // Transmission amplitudes t = t₀₁ t₁₂ e^{iδ}/(1 + r₀₁ r₁₂ e^{2iδ}) with
    // t_s = 2 n_a cos_a/(n_a cos_a + n_b cos_b), t_p = 2 n_a cos_a/(n_b cos_a + n_a cos_b);
    // T_s = Re(n₂ cos θ₂)/(n₀ cos θ₀)|t_s|², T_p = Re(n₂ cos θ₂)/(n₀ cos θ₀)|t_p|² (real
    // indices; Born & Wolf §1.5.3).
    let ts =
        |na: Complex, ca: Complex, nb: Complex, cb: Complex| (na * ca * 2.0) / (na * ca + nb * cb);
    let tp =
        |na: Complex, ca: Complex, nb: Complex, cb: Complex| (na * ca * 2.0) / (nb * ca + na * cb);
    let t_s = ts(n0, cc0, n1, c1) * ts(n1, c1, n2, c2) * e1 / (one + r01s * r12s * e2);
    let t_p = tp(n0, cc0, n1, c1) * tp(n1, c1, n2, c2) * e1 / (one + r01p * r12p * e2);
    let ratio = if c0 > 0.0 { (n2 * c2).re / c0 } else { 0.0 };
    let transmit = 0.5 * ratio * (t_s.norm_sqr() + t_p.norm_sqr());
    (reflect, transmit)
}

/// Unpolarised film reflectance in [0, 1] (see [`airy`]); NaN-safe (1 on a degenerate
/// input, as the conductor Fresnel does).
pub fn reflectance(cos0: f32, n_film: f32, d_nm: f32, eta: f32, kappa: f32, lambda_nm: f32) -> f32 {
    let r = airy(cos0, n_film, d_nm, eta, kappa, lambda_nm).0;
    if r.is_nan() {
        1.0
    } else {
        r.clamp(0.0, 1.0) as f32
    }
}

/// Index of a dielectric with normal-incidence reflectance `f0` against index 1:
/// n = (1 + √F0)/(1 − √F0) (the inverse of F0 = ((n−1)/(n+1))²; KHR_materials_iridescence
/// reference code `Fresnel0ToIor`). `f0` is clamped to [0, 0.9999] as there.
pub fn f0_to_ior(f0: f32) -> f32 {
    let s = f0.clamp(0.0, 0.9999).sqrt();
    (1.0 + s) / (1.0 - s)
}
