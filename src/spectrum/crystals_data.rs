//! The crystal table (data only; the types, functions and the sources of every number are in
//! [`super`], whose module table this file follows row by row).
//!
//! Sellmeier coefficients keep their sources' digits (refractiveindex.info files named in
//! each entry); λ_i given in µm by a source are squared by [`squared`]. Absorption tables
//! are σ in 1/m every 20 nm from 380 to 780 nm ([`NM`]), designed as the parent module
//! describes (cited band positions, chosen widths and heights), two significant digits.
#![allow(clippy::excessive_precision)]

use super::{cauchy_through, pole_form, Absorption, Crystal};
use crate::spectrum::ior::IorModel;

/// Squares resonance wavelengths (µm → µm²), for sources that tabulate λ_i rather than C_i.
const fn squared(l: [f32; 3]) -> [f32; 4] {
    [l[0] * l[0], l[1] * l[1], l[2] * l[2], 0.0]
}

/// Three Sellmeier terms padded to four.
const fn sellmeier3(b: [f32; 3], c: [f32; 4]) -> IorModel {
    IorModel::Sellmeier {
        b: [b[0], b[1], b[2], 0.0],
        c,
    }
}

/// Ghosh 1999 form n² − 1 = A + B₁λ²/(λ² − C₁) + B₂λ²/(λ² − C₂) (refractiveindex.info
/// "formula 2"; the constant A is a term with C = 0).
const fn ghosh(a: f32, b1: f32, c1: f32, b2: f32, c2: f32) -> IorModel {
    sellmeier3([a, b1, b2], [0.0, c1, c2, 0.0])
}

/// The ordinary index along x and y, the extraordinary along z.
const fn uniaxial(o: IorModel, e: IorModel) -> [IorModel; 3] {
    [o, o, e]
}

/// One table for light polarised along x and y (E ⊥ c), one along z (E ∥ c).
const fn dichroic(o: &'static [f32], e: &'static [f32]) -> Option<[Absorption; 3]> {
    let (o, e) = (
        Absorption { nm: &NM, per_m: o },
        Absorption { nm: &NM, per_m: e },
    );
    Some([o, o, e])
}

/// Wavelengths of every absorption table, nm.
#[rustfmt::skip]
pub const NM: [f32; 21] = [
    380.0, 400.0, 420.0, 440.0, 460.0, 480.0, 500.0, 520.0, 540.0, 560.0, 580.0,
    600.0, 620.0, 640.0, 660.0, 680.0, 700.0, 720.0, 740.0, 760.0, 780.0,
];

/// Ruby, E ⊥ c: Cr³⁺ U band at 560 nm, Y band at 410 nm, violet edge.
#[rustfmt::skip]
const RUBY_O: [f32; 21] = [
    1100.0, 1400.0, 1400.0, 980.0, 560.0, 300.0, 290.0, 600.0, 1000.0, 1200.0, 1000.0,
    670.0, 350.0, 160.0, 60.0, 20.0, 6.0, 1.0, 0.0, 0.0, 0.0,
];
/// Ruby, E ∥ c: U band at 550 nm with 0.45 of the E ⊥ c height, Y band at 400 nm.
#[rustfmt::skip]
const RUBY_E: [f32; 21] = [
    1400.0, 1600.0, 1300.0, 850.0, 470.0, 250.0, 230.0, 380.0, 530.0, 520.0, 380.0,
    210.0, 96.0, 37.0, 13.0, 3.0, 1.0, 0.0, 0.0, 0.0, 0.0,
];
/// Blue sapphire, E ⊥ c: Fe²⁺–Ti⁴⁺ band at 580 nm, weak Fe³⁺ 450 nm, violet edge.
#[rustfmt::skip]
const SAPPHIRE_O: [f32; 21] = [
    300.0, 110.0, 48.0, 69.0, 110.0, 170.0, 300.0, 450.0, 580.0, 670.0, 700.0,
    670.0, 610.0, 520.0, 430.0, 340.0, 270.0, 200.0, 150.0, 110.0, 80.0,
];
/// Blue sapphire, E ∥ c: Fe²⁺–Ti⁴⁺ band at 700 nm with 0.6 of the E ⊥ c height.
#[rustfmt::skip]
const SAPPHIRE_E: [f32; 21] = [
    300.0, 110.0, 43.0, 59.0, 53.0, 16.0, 22.0, 45.0, 81.0, 130.0, 190.0,
    250.0, 310.0, 360.0, 390.0, 410.0, 420.0, 410.0, 400.0, 370.0, 340.0,
];
/// Green tourmaline, E ⊥ c: Fe²⁺ 730 nm, 450 nm charge transfer, a flat 2.2/cm background.
#[rustfmt::skip]
const TOURMALINE_O: [f32; 21] = [
    870.0, 640.0, 610.0, 610.0, 590.0, 510.0, 430.0, 370.0, 340.0, 360.0, 420.0,
    530.0, 670.0, 820.0, 970.0, 1100.0, 1200.0, 1200.0, 1200.0, 1200.0, 1100.0,
];
/// Green tourmaline, E ∥ c: the same bands, 730 nm at a quarter of the E ⊥ c height.
#[rustfmt::skip]
const TOURMALINE_E: [f32; 21] = [
    440.0, 270.0, 220.0, 210.0, 190.0, 160.0, 120.0, 85.0, 66.0, 63.0, 75.0,
    100.0, 130.0, 170.0, 210.0, 240.0, 260.0, 270.0, 270.0, 260.0, 240.0,
];
/// Tanzanite X (α, ∥ a): 530 nm strong, 595 nm weak: red and blue pass, violet.
#[rustfmt::skip]
const TANZANITE_X: [f32; 21] = [
    100.0, 37.0, 14.0, 5.0, 11.0, 64.0, 200.0, 340.0, 360.0, 300.0, 220.0,
    160.0, 110.0, 68.0, 36.0, 17.0, 7.0, 2.0, 0.0, 0.0, 0.0,
];
/// Tanzanite Y (β, ∥ b): 595 nm strong and broad, 530 nm weaker: blue.
#[rustfmt::skip]
const TANZANITE_Y: [f32; 21] = [
    100.0, 37.0, 14.0, 5.0, 5.0, 29.0, 99.0, 200.0, 320.0, 430.0, 510.0,
    510.0, 430.0, 310.0, 190.0, 110.0, 53.0, 25.0, 11.0, 4.0, 1.0,
];
/// Tanzanite Z (γ, ∥ c): 455 and 520 nm (the bands heating removes), 595 nm weak: brownish
/// yellow.
#[rustfmt::skip]
const TANZANITE_Z: [f32; 21] = [
    200.0, 81.0, 130.0, 360.0, 450.0, 300.0, 200.0, 170.0, 140.0, 92.0, 63.0,
    48.0, 36.0, 25.0, 15.0, 8.0, 4.0, 2.0, 0.0, 0.0, 0.0,
];
/// Peridot, every axis: tails of the Fe²⁺ 850 and 1050 nm bands, 453/473/493 nm lines, edge.
#[rustfmt::skip]
const PERIDOT: [f32; 21] = [
    1200.0, 540.0, 240.0, 120.0, 100.0, 95.0, 61.0, 5.0, 3.0, 6.0, 15.0,
    34.0, 68.0, 120.0, 200.0, 300.0, 430.0, 580.0, 750.0, 940.0, 1200.0,
];
/// Emerald, both axes: Cr³⁺ bands at 430 and 615 nm.
#[rustfmt::skip]
const EMERALD: [f32; 21] = [
    54.0, 230.0, 420.0, 420.0, 270.0, 120.0, 46.0, 38.0, 86.0, 180.0, 300.0,
    380.0, 400.0, 350.0, 270.0, 190.0, 120.0, 71.0, 39.0, 21.0, 10.0,
];

/// Malitson & Dodge 1972, corundum ordinary ray (Al2O3 Malitson-o; λ_i in µm); identical to
/// [`IorModel::named`] "sapphire".
const CORUNDUM_O: IorModel = sellmeier3(
    [1.4313493, 0.65054713, 5.3414021],
    squared([0.0726631, 0.1193242, 18.028251]),
);
/// Malitson & Dodge 1972, corundum extraordinary ray (Al2O3 Malitson-e).
const CORUNDUM_E: IorModel = sellmeier3(
    [1.5039759, 0.55069141, 6.5927379],
    squared([0.0740288, 0.1216529, 20.072248]),
);

/// Peter 1923 (C Peter; λ_i in µm); identical to [`IorModel::named`] "diamond".
const DIAMOND: IorModel = IorModel::Sellmeier {
    b: [0.3306, 4.3356, 0.0, 0.0],
    c: [0.1750 * 0.1750, 0.1060 * 0.1060, 0.0, 0.0],
};
/// Wood & Nassau 1982, 12 mol % Y₂O₃ (ZrO2-Y2O3 Wood; λ_i in µm).
const CUBIC_ZIRCONIA: IorModel = sellmeier3(
    [1.347091, 2.117788, 9.452943],
    squared([0.062543, 0.166739, 24.320570]),
);
/// SCHOTT N-BK7 (C_i in µm²); identical to [`IorModel::named`] "N-BK7".
const N_BK7: IorModel = sellmeier3(
    [1.03961212, 0.231792344, 1.01046945],
    [0.00600069867, 0.0200179144, 103.560653, 0.0],
);

/// Every crystal, in the module table's order.
pub static CRYSTALS: [Crystal; 15] = [
    Crystal {
        name: "calcite",
        axes: uniaxial(
            ghosh(0.73358749, 0.96464345, 1.94325203e-2, 1.82831454, 120.0),
            ghosh(0.35859695, 0.82427830, 1.06689543e-2, 0.14429128, 120.0),
        ),
        absorption: None,
        source: "Ghosh, Opt. Commun. 163, 95 (1999), o and e; HOM calcite",
    },
    Crystal {
        name: "quartz",
        axes: uniaxial(
            ghosh(0.28604141, 1.07044083, 1.00585997e-2, 1.10202242, 100.0),
            ghosh(0.28851804, 1.09509924, 1.02101864e-2, 1.15662475, 100.0),
        ),
        absorption: None,
        source: "Ghosh, Opt. Commun. 163, 95 (1999), o and e; GIA Gem Reference Guide",
    },
    Crystal {
        name: "sapphire",
        axes: uniaxial(CORUNDUM_O, CORUNDUM_E),
        absorption: dichroic(&SAPPHIRE_O, &SAPPHIRE_E),
        source: "Malitson & Dodge, JOSA 62, 1405 (1972); colour: Emmett et al. and \
                 Dubinsky et al., G&G 56(1) (2020), shaped, not measured",
    },
    Crystal {
        name: "ruby",
        axes: uniaxial(CORUNDUM_O, CORUNDUM_E),
        absorption: dichroic(&RUBY_O, &RUBY_E),
        source: "Malitson & Dodge, JOSA 62, 1405 (1972); colour: Mandarino, Am. Mineral. 44, \
                 961 (1959), shaped, not measured",
    },
    Crystal {
        name: "emerald",
        axes: uniaxial(cauchy_through(1.583, 0.014), cauchy_through(1.577, 0.014)),
        absorption: dichroic(&EMERALD, &EMERALD),
        source: "GIA Gem Reference Guide; GemSelect dispersion chart; Cauchy fit",
    },
    Crystal {
        name: "zircon",
        axes: uniaxial(cauchy_through(1.925, 0.039), cauchy_through(1.984, 0.039)),
        absorption: None,
        source: "GIA Gem Reference Guide (high zircon); HOM zircon; Schumann (2009); Cauchy fit",
    },
    Crystal {
        name: "tourmaline",
        axes: uniaxial(cauchy_through(1.644, 0.017), cauchy_through(1.624, 0.017)),
        absorption: dichroic(&TOURMALINE_O, &TOURMALINE_E),
        source: "GIA Gem Reference Guide; Schumann (2009); Cauchy fit; colour: Mattson & \
                 Rossman, Phys. Chem. Minerals 14, 163 (1987), shaped, not measured",
    },
    Crystal {
        name: "peridot",
        axes: [
            cauchy_through(1.654, 0.020),
            cauchy_through(1.671, 0.020),
            cauchy_through(1.690, 0.020),
        ],
        absorption: Some([
            Absorption {
                nm: &NM,
                per_m: &PERIDOT,
            },
            Absorption {
                nm: &NM,
                per_m: &PERIDOT,
            },
            Absorption {
                nm: &NM,
                per_m: &PERIDOT,
            },
        ]),
        source: "GIA Gem Reference Guide (n_beta chosen, see module doc); HOM forsterite; \
                 Cauchy fit; colour shaped, not measured",
    },
    Crystal {
        name: "tanzanite",
        axes: [
            cauchy_through(1.692, 0.030),
            cauchy_through(1.693, 0.030),
            cauchy_through(1.700, 0.030),
        ],
        absorption: Some([
            Absorption {
                nm: &NM,
                per_m: &TANZANITE_X,
            },
            Absorption {
                nm: &NM,
                per_m: &TANZANITE_Y,
            },
            Absorption {
                nm: &NM,
                per_m: &TANZANITE_Z,
            },
        ]),
        source: "O'Donoghue, Gems (2006); HOM zoisite; Cauchy fit; colour: Pluthametwisute \
                 et al., Molecules 25, 3743 (2020), shaped, not measured",
    },
    Crystal {
        name: "topaz",
        axes: [
            cauchy_through(1.609, 0.014),
            // Derived from alpha, gamma and 2V_z = 58 degrees (module doc).
            cauchy_through(1.6109, 0.014),
            cauchy_through(1.617, 0.014),
        ],
        absorption: None,
        source: "GIA Gem Reference Guide; HOM topaz (2V, n_beta derived); GemSelect; Cauchy fit",
    },
    Crystal {
        name: "moissanite",
        axes: uniaxial(
            pole_form(6.57232, 0.1401, 0.03178, -0.02153),
            pole_form(6.7452, 0.15352, 0.03597, -0.02249),
        ),
        absorption: None,
        source: "Wang et al., Laser Photonics Rev. 7, 831 (2013), 6H-SiC o and e; GIA",
    },
    Crystal {
        name: "rutile",
        axes: uniaxial(
            pole_form(5.913, 0.2441, 0.0803, 0.0),
            pole_form(7.197, 0.3322, 0.0843, 0.0),
        ),
        absorption: None,
        source: "DeVore, JOSA 41, 416 (1951), o and e; GIA; Bond, J. Appl. Phys. 36, 1674 (1965)",
    },
    Crystal {
        name: "diamond",
        axes: [DIAMOND; 3],
        absorption: None,
        source: "Peter, Z. Phys. 15, 358 (1923); GIA Gem Reference Guide",
    },
    Crystal {
        name: "cubic-zirconia",
        axes: [CUBIC_ZIRCONIA; 3],
        absorption: None,
        source: "Wood & Nassau, Appl. Opt. 21, 2978 (1982); GIA Gem Reference Guide",
    },
    Crystal {
        name: "crown-glass",
        axes: [N_BK7; 3],
        absorption: None,
        source: "SCHOTT N-BK7 data sheet",
    },
];
