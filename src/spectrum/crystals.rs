//! Crystal optics of gemstones: principal refractive indices n(λ) along three axes, optical
//! character, birefringence, the biaxial optic angle 2V and polarised absorption spectra.
//! Data and small pure functions only; the transport that uses them lives elsewhere.
//!
//! Units: λ in nm (vacuum) at the API (the dispersion formulas take µm inside
//! [`IorModel`]); absorption coefficients σ in 1/m (transmittance exp(−σ·d), d in metres).
//! Frames: each crystal is described in its principal frame (x, y, z). Uniaxial: x = y =
//! ordinary (E ⊥ c, n_o), z = the optic axis c (E ∥ c, n_e). Biaxial: n_x = n_α < n_y = n_β <
//! n_z = n_γ (x, y, z = X, Y, Z of the indicatrix). Absorption is given for light polarised
//! (E, strictly D) along each axis. Gemmological indices are quoted at the sodium D line,
//! [`LAMBDA_NA_D`] = 589.3 nm; character, birefringence and 2V are derived there.
//!
//! | stone | character | n at 589.3 nm (x, y, z) | Δn | dispersion n(λ) | source of the numbers |
//! |---|---|---|---|---|---|
//! | calcite | uniaxial − | 1.6583, 1.6583, 1.4861 | 0.172 | Sellmeier, o and e | G. Ghosh, Opt. Commun. 163, 95 (1999) (refractiveindex.info CaCO3 Ghosh-o/e); Handbook of Mineralogy (HOM) calcite: ω 1.658, ε 1.486 |
//! | quartz | uniaxial + | 1.5442, 1.5442, 1.5533 | 0.009 | Sellmeier, o and e | Ghosh 1999 (SiO2 Ghosh-o/e); GIA Gem Reference Guide (GIA GRG): 1.544–1.553, Δn 0.009 |
//! | sapphire, ruby (corundum) | uniaxial − | 1.7681, 1.7681, 1.7600 | 0.008 | Sellmeier, o and e | I. H. Malitson & M. J. Dodge, JOSA 62, 1405 (1972) (Al2O3 Malitson-o/e); GIA GRG: 1.762–1.770, Δn 0.008 |
//! | emerald (beryl) | uniaxial − | 1.583, 1.583, 1.577 | 0.006 | Cauchy through n_D and n_G − n_B = 0.014 | GIA GRG: 1.577–1.583, Δn 0.005–0.009; B–G 0.014: GemSelect dispersion chart |
//! | zircon (high) | uniaxial + | 1.925, 1.925, 1.984 | 0.059 | Cauchy through n_D and n_G − n_B = 0.039 | GIA GRG high zircon 1.925–1.984, Δn 0.059; HOM zircon ω 1.925–1.961, ε 1.980–2.015; B–G 0.039 (C–F 0.022): W. Schumann, *Gemstones of the World* (2009), pp. 41–42 |
//! | tourmaline (green elbaite) | uniaxial − | 1.644, 1.644, 1.624 | 0.020 | Cauchy through n_D and n_G − n_B = 0.017 | GIA GRG tourmaline 1.624–1.644, Δn 0.020; B–G 0.017 (C–F 0.009–0.011): Schumann 2009 |
//! | peridot (forsterite-rich olivine) | biaxial +, 2V_z 87.7° | 1.654, 1.671, 1.690 | 0.036 | Cauchy through n_D and n_G − n_B = 0.020 | GIA GRG peridot 1.654–1.690, Δn 0.036, "β usually near halfway between α and γ", sign + or −, dispersion 0.020; n_β see below |
//! | tanzanite (zoisite) | biaxial +, 2V_z 41.5° | 1.692, 1.693, 1.700 | 0.008 | Cauchy through n_D and n_G − n_B = 0.030 | M. O'Donoghue (ed.), *Gems* 6th ed. (2006): α 1.692, β 1.693, γ 1.700; HOM zoisite 2V_z 0–69°; B–G 0.030: GemSelect dispersion chart (other tables give 0.012–0.021) |
//! | topaz (colourless to blue) | biaxial +, 2V_z 58.5° | 1.609, 1.6109, 1.617 | 0.008 | Cauchy through n_D and n_G − n_B = 0.014 | GIA GRG topaz 1.609–1.617, Δn 0.008–0.010; HOM topaz 2V_z 48–68°; n_β see below; B–G 0.014: GemSelect dispersion chart |
//! | moissanite (6H-SiC) | uniaxial + | 2.6474, 2.6474, 2.6890 | 0.042 | n² = A + B/(λ² − C) + Dλ², o and e | S. Wang et al., Laser Photonics Rev. 7, 831 (2013) (SiC Wang-6H-o/e); GIA GRG synthetic moissanite 2.648–2.691, Δn 0.043 |
//! | rutile (TiO₂) | uniaxial + | 2.6129, 2.6129, 2.9087 | 0.296 | n² = A + B/(λ² − C), o and e | J. R. DeVore, JOSA 41, 416 (1951) (TiO2 Devore-o/e); GIA GRG synthetic rutile 2.616–2.903, Δn 0.287; W. L. Bond, J. Appl. Phys. 36, 1674 (1965) measured n_e 0.009 lower at 600 nm |
//! | diamond | isotropic | 2.4173 | 0 | Sellmeier | F. Peter, Z. Phys. 15, 358 (1923) (as [`IorModel::named`] "diamond"); GIA GRG 2.417 |
//! | cubic zirconia | isotropic | 2.1585 | 0 | Sellmeier | D. L. Wood & K. Nassau, Appl. Opt. 21, 2978 (1982) (ZrO2-Y2O3 Wood, 12 mol % Y₂O₃); GIA GRG 2.15–2.18 |
//! | crown glass (N-BK7) | isotropic | 1.5167 | 0 | Sellmeier | SCHOTT N-BK7 data sheet (as [`IorModel::named`] "N-BK7") |
//!
//! Dispersion where no measured formula exists (emerald, zircon, tourmaline, peridot,
//! tanzanite, topaz): gem tables give n at the D line and the "dispersion" n_G − n_B between
//! the Fraunhofer G (430.8 nm) and B (686.7 nm) lines. [`cauchy_through`] fits n = b + c/λ²
//! through both, one c for all axes (the tables give one value). Cross-check: this gives
//! n_F − n_C = 0.0228 for zircon and 0.0099 for tourmaline, where Schumann lists 0.022 and
//! 0.009–0.011. The refractiveindex.info formulas keep their authors' coefficients; the
//! "formula 4" ones (DeVore, Wang) are rewritten exactly as Sellmeier terms ([`pole_form`]),
//! Wang's −Dλ² term as a pole at 31.6 µm (relative error < 1e-6 in n up to 830 nm).
//! Below their measured ranges (Wang from 436 nm, DeVore from 430 nm) n is extrapolated;
//! real moissanite and rutile absorb there (band edges near 410 nm), which the tables do not
//! model.
//!
//! Chosen numbers, not measured: peridot's n_β = 1.671. GIA puts β near halfway, but exactly
//! halfway (1.672) gives 2V_z = 90.9°, an optically negative stone; 1.671 (one refractometer
//! step lower) gives 2V_z = 87.7°, positive, between HOM's forsterite 2V_z 82° (Fo₁₀₀) and
//! 90° (Mindat forsterite 74–90°; olivine turns negative near Fo₈₈, and gem peridot is
//! Fo₈₉–Fo₉₂: M. Q. Jan & M. A. Khan, J. Himalayan Earth Sci. 29 (1996)); HOM forsterite:
//! X = b, Y = c, Z = a. Topaz's n_β is
//! derived, not quoted: from GIA's α 1.609, γ 1.617 and 2V_z = 58°, the middle of HOM's
//! 48–68° (sources disagree on which way 2V moves with the F content, so no end is
//! preferred), through 1/n_β² = 1/n_γ² + cos²V_z (1/n_α² − 1/n_γ²) = 1/1.6109²; with the
//! rounded 1.6109, 2V_z = 58.5°.
//!
//! ## Absorption (pleochroism)
//!
//! Tables are piecewise linear every 20 nm over 380–780 nm ([`Absorption::at`] holds the end
//! values beyond). **None is a measured spectrum.** Each is a sum of the bands the cited
//! spectroscopy places (centres and which polarisation carries them, from the source), with
//! widths (2,500–5,500 cm⁻¹, as room-temperature d–d and charge-transfer bands) and heights
//! chosen here, scaled so that a 5 mm path ([`TYPICAL_PATH`]) under D65 gives the
//! gemmologist's described colour for each axis; the tests check those colours.
//!
//! | stone | axis: described colour | bands placed (source) |
//! |---|---|---|
//! | ruby | x, y (E ⊥ c): purplish red; z (E ∥ c): orange-red | Cr³⁺ ⁴T₂ ("U") and ⁴T₁ ("Y"): E ⊥ c maxima ≈ 560 and 410 nm, E ∥ c ≈ 550 and 400 nm; U about twice as strong for E ⊥ c (ratio 1.37–2.25), Y about equal (J. A. Mandarino, Am. Mineral. 44, 961 (1959), as quoted by the indicatrix gem catalogue, github.com/suitable-name/indicatrix); GIA GRG pleochroism |
//! | sapphire (blue) | x, y: violetish blue; z: greenish blue | Fe²⁺–Ti⁴⁺ intervalence band: E ⊥ c at 580 nm, E ∥ c at 700 nm and weaker (A. J. Emmett et al., "The colors of sapphires", G&G 56(1), 2020, as quoted by the indicatrix catalogue; Z. Dubinsky et al., "A quantitative description of the causes of color in corundum", same issue); the weak Fe³⁺ 450 nm band of blue sapphire's spectroscope picture |
//! | tourmaline (green) | x, y (E ⊥ c): dark green; z (E ∥ c): light yellowish green | Fe²⁺ bands ≈ 700–730 nm (and 1100 nm) and a 420–460 nm charge-transfer band (J.-M. Derochette, polarised green tourmaline spectra); Fe²⁺–Fe³⁺ interaction absorbs strongly for E ⊥ c at higher Fe (G. R. Rossman, Caltech Mineral Spectroscopy Server, elbaite; R. P. Mattson & G. R. Rossman, Phys. Chem. Minerals 14, 163 (1987)); E ⊥ c : E ∥ c = 4 at 730 nm chosen |
//! | tanzanite (unheated, trichroic) | x = X ∥ a: violet; y = Y ∥ b: blue; z = Z ∥ c: brownish yellow | bands at 595, 528 and 455 nm (O'Donoghue 2006); the 455 and ≈ 520 nm bands lie along c and fade on heating (T. Pluthametwisute et al., Molecules 25, 3743 (2020)); zoisite a = X, b = Y, c = Z (MINTS mineral database, UWC); HOM zoisite: X red-violet, Y deep blue, Z yellow to yellow-green. Heated stones (blue and violet only) are not in the table |
//! | peridot | all axes: yellowish green (pleochroism weak; not modelled: one spectrum on all three) | Fe²⁺ bands in the near infrared (≈ 850 and 1050 nm) whose tails absorb red, the 453, 473, 493 nm Fe²⁺ lines of peridot's spectroscope picture, a violet absorption edge |
//! | emerald | both axes: green (dichroism weak; not modelled: one spectrum on both) | Cr³⁺ bands near 430 and 600–620 nm leaving a green window (J.-M. Derochette, polarised emerald spectra; GIA GRG) |
//!
//! The other stones carry no absorption (`absorption: None`): colourless.

use super::ior::IorModel;

#[path = "crystals_data.rs"]
mod data;

pub use data::CRYSTALS;

/// The sodium D line, nm: where gemmological refractive indices are quoted.
pub const LAMBDA_NA_D: f32 = 589.3;
/// Fraunhofer B line (oxygen, 686.7 nm): the red end of gemmological dispersion n_G − n_B.
pub const LAMBDA_B: f32 = 686.7;
/// Fraunhofer G line (430.8 nm): the violet end of gemmological dispersion n_G − n_B.
pub const LAMBDA_G: f32 = 430.8;
/// Path length, metres, over which the absorption tables give the described colours.
pub const TYPICAL_PATH: f32 = 0.005;

/// Optical character.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Character {
    /// Cubic (or amorphous): one index.
    Isotropic,
    /// Tetragonal, trigonal, hexagonal: one optic axis; positive when n_e > n_o.
    Uniaxial {
        /// n_e > n_o.
        positive: bool,
    },
    /// Orthorhombic, monoclinic, triclinic: two optic axes; positive when the acute
    /// bisectrix is Z (2V_z < 90°).
    Biaxial {
        /// 2V_z < 90°.
        positive: bool,
    },
}

/// Absorption coefficient spectrum, 1/m, piecewise linear in λ (nm), constant beyond the ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Absorption {
    /// Wavelengths of the rows, nm, ascending.
    pub nm: &'static [f32],
    /// σ at each row, 1/m, ≥ 0 (same length as `nm`).
    pub per_m: &'static [f32],
}

impl Absorption {
    /// σ at `nm`, 1/m: linear between rows, the end rows held beyond them; 0 for a NaN
    /// wavelength or an empty table.
    pub fn at(&self, nm: f32) -> f32 {
        let (x, y) = (self.nm, self.per_m);
        let n = x.len().min(y.len());
        if n == 0 || nm.is_nan() {
            return 0.0;
        }
        if nm <= x[0] {
            return y[0];
        }
        if nm >= x[n - 1] {
            return y[n - 1];
        }
        // First row above nm; 1 ≤ i ≤ n − 1 here.
        let i = x[..n].partition_point(|&l| l <= nm);
        let t = (nm - x[i - 1]) / (x[i] - x[i - 1]);
        y[i - 1] + (y[i] - y[i - 1]) * t
    }
}

/// A crystal's optics in its principal frame (x, y, z). Uniaxial: x = y = ordinary (n_o),
/// z = the optic axis c (n_e). Biaxial: n_x = n_α < n_y = n_β < n_z = n_γ (x = X, y = Y,
/// z = Z of the indicatrix).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crystal {
    /// Name, lower case with '-' between words, e.g. "calcite", "cubic-zirconia".
    pub name: &'static str,
    /// n along x, y, z (for light polarised along that axis).
    pub axes: [IorModel; 3],
    /// Absorption for light polarised along x, y, z; `None` = colourless.
    pub absorption: Option<[Absorption; 3]>,
    /// One-line citation(s) for the numbers (the module table has the details).
    pub source: &'static str,
}

impl Crystal {
    /// The three principal indices at `nm` (vacuum wavelength, nm).
    pub fn indices(&self, nm: f32) -> [f32; 3] {
        self.axes.map(|m| m.ior(nm))
    }

    /// Optical character, from the indices at [`LAMBDA_NA_D`]: two equal indices make a
    /// uniaxial crystal, three an isotropic one (equal to 1e-5).
    pub fn character(&self) -> Character {
        character_of(self.indices(LAMBDA_NA_D))
    }

    /// n_max − n_min at [`LAMBDA_NA_D`].
    pub fn birefringence(&self) -> f32 {
        let [a, _, g] = sorted(self.indices(LAMBDA_NA_D));
        g - a
    }

    /// σ for light polarised along x, y, z at `nm`, 1/m; zeros when colourless.
    pub fn absorption_at(&self, nm: f32) -> [f32; 3] {
        match &self.absorption {
            Some(axes) => axes.map(|a| a.at(nm)),
            None => [0.0; 3],
        }
    }

    /// 2V_z, the optic axial angle bisected by Z, degrees, from n_α n_β n_γ at
    /// [`LAMBDA_NA_D`] ([`two_v_z_deg`]): below 90° for a positive crystal, above for a
    /// negative one (whose acute 2V is 180° − 2V_z). `None` when not biaxial.
    pub fn optic_angle_deg(&self) -> Option<f32> {
        match self.character() {
            Character::Biaxial { .. } => {
                let [a, b, g] = sorted(self.indices(LAMBDA_NA_D));
                Some(two_v_z_deg(a, b, g))
            }
            _ => None,
        }
    }
}

/// The crystal named `name`: case-insensitive, '_' and ' ' as '-', surrounding space
/// ignored; `None` when not in [`CRYSTALS`].
pub fn named(name: &str) -> Option<&'static Crystal> {
    let key: String = name
        .trim()
        .chars()
        .map(|ch| match ch {
            '_' | ' ' => '-',
            _ => ch.to_ascii_lowercase(),
        })
        .collect();
    CRYSTALS.iter().find(|c| c.name == key)
}

/// 2V_z in degrees from the principal indices n_α < n_β < n_γ:
/// cos²V_z = n_α²(n_γ² − n_β²) / (n_β²(n_γ² − n_α²)) (the indicatrix; e.g. W. D. Nesse,
/// *Introduction to Optical Mineralogy*). 90° when n_γ = n_α; the ratio is clamped to [0, 1].
pub fn two_v_z_deg(n_alpha: f32, n_beta: f32, n_gamma: f32) -> f32 {
    let (a2, b2, g2) = (
        f64::from(n_alpha).powi(2),
        f64::from(n_beta).powi(2),
        f64::from(n_gamma).powi(2),
    );
    let den = b2 * (g2 - a2);
    if den.is_nan() || den <= 0.0 {
        return 90.0;
    }
    let cos2 = (a2 * (g2 - b2) / den).clamp(0.0, 1.0);
    (2.0 * cos2.sqrt().acos().to_degrees()) as f32
}

/// Cauchy model n = b + c/λ² through n at [`LAMBDA_NA_D`] and the gemmological dispersion
/// n_G − n_B (Fraunhofer G 430.8 nm, B 686.7 nm), for minerals with no measured formula.
pub const fn cauchy_through(n_d: f32, dispersion_bg: f32) -> IorModel {
    let (g, b, d) = (
        LAMBDA_G as f64 * 1e-3,
        LAMBDA_B as f64 * 1e-3,
        LAMBDA_NA_D as f64 * 1e-3,
    );
    let c = dispersion_bg as f64 / (1.0 / (g * g) - 1.0 / (b * b));
    IorModel::Cauchy {
        b: (n_d as f64 - c / (d * d)) as f32,
        c: c as f32,
    }
}

/// n² = a + b/(λ² − c) + d·λ² (λ in µm; refractiveindex.info "formula 4" with one pole and
/// a λ² term, as DeVore 1951 and Wang et al. 2013 publish it) as an [`IorModel::Sellmeier`]:
/// b/(λ² − c) = (b/c)·λ²/(λ² − c) − b/c exactly, the constant a − 1 − b/c as a term with
/// C = 0, and d·λ² (d ≤ 0) as the far-infrared pole −d·P·λ²/(λ² − P), P = 1000 µm², which
/// differs from d·λ² by the factor 1/(1 − λ²/P) (< 1.0007 up to 830 nm).
pub const fn pole_form(a: f32, b: f32, c: f32, d: f32) -> IorModel {
    const P: f64 = 1000.0;
    let (a, b, c, d) = (a as f64, b as f64, c as f64, d as f64);
    IorModel::Sellmeier {
        b: [
            (a - 1.0 - b / c) as f32,
            (b / c) as f32,
            (-d * P) as f32,
            0.0,
        ],
        c: [0.0, c as f32, if d == 0.0 { 0.0 } else { P as f32 }, 0.0],
    }
}

/// Ascending copy of three indices.
fn sorted(mut n: [f32; 3]) -> [f32; 3] {
    n.sort_by(f32::total_cmp);
    n
}

/// Character from three principal indices (any order); equal means within 1e-5.
pub fn character_of(n: [f32; 3]) -> Character {
    const EQ: f32 = 1e-5;
    let [a, b, g] = sorted(n);
    if g - a <= EQ {
        Character::Isotropic
    } else if b - a <= EQ {
        // The odd index is the largest: n_e > n_o.
        Character::Uniaxial { positive: true }
    } else if g - b <= EQ {
        Character::Uniaxial { positive: false }
    } else {
        Character::Biaxial {
            positive: two_v_z_deg(a, b, g) < 90.0,
        }
    }
}

#[cfg(test)]
#[path = "crystals_tests.rs"]
mod tests;
