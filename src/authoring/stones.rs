//! Named gem materials for `iris gem`: refractive index at the sodium d line (n_d,
//! 587.6 nm), Abbe number V_d = (n_d − 1)/(n_F − n_C) and, for coloured stones, a
//! KHR_materials_volume absorption.
//!
//! The glTF material is smooth (roughness 0), fully transmissive (KHR_materials_transmission
//! 1), with KHR_materials_ior = n_d and KHR_materials_dispersion = 20 / V_d (the extension's
//! definition). The birefringent stones (every one but diamond, cubic zirconia and the
//! glass) are also crystals of the crystal table ([`crate::spectrum::crystals`], which
//! holds their principal indices, absorption per axis and sources): material
//! `extras.iris_crystal = {"stone": NAME}` with the optic axis along the model's +Y (the
//! table normal of Iris's cuts), so polarized transport renders their two modes; n_d and
//! V_d are then their ordinary (uniaxial) or n_β (biaxial) index's, what renderers without
//! birefringence use.
//!
//! | stone | n_d | V_d | source |
//! |---|---|---|---|
//! | diamond | 2.417 | 55 | GIA Gem Reference Guide (RI 2.417); refractiveindex.info, C (diamond), Phillip & Taft 1964: V_d ≈ 55 |
//! | sapphire, ruby (corundum) | 1.770 | 72 | GIA Gem Reference Guide (RI 1.762–1.770); refractiveindex.info, Al₂O₃ ordinary ray, Malitson 1962: V_d ≈ 72 |
//! | emerald (beryl) | 1.583 | 72 | GIA Gem Reference Guide (RI 1.577–1.583, ordinary 1.583; dispersion 0.014 between the B and G lines); V_d estimated as (n_d − 1)/(0.58 × 0.014): n_F − n_C is 0.58 of n_G − n_B for corundum, diamond and fused silica (their Sellmeier fits in `spectrum::ior`) |
//! | cubic zirconia | 2.16 | 28 | GIA Gem Reference Guide (RI 2.15–2.18); refractiveindex.info, ZrO₂:Y₂O₃, Wood & Nassau 1982: V_d ≈ 28 |
//! | quartz | 1.544 | 70 | GIA Gem Reference Guide (RI 1.544–1.553, ordinary 1.544); refractiveindex.info, SiO₂ ordinary ray, Ghosh 1999: V_d ≈ 70 |
//! | crown glass (N-BK7) | 1.5168 | 64.17 | SCHOTT N-BK7 data sheet |
//! | calcite, zircon, peridot, tourmaline, tanzanite, topaz, moissanite, rutile | the crystal table's n_o or n_β at 587.6 nm | from the same model's n_F, n_C | [`crate::spectrum::crystals`] |
//!
//! Colours (linear RGB `attenuationColor` reached after `attenuationDistance`) are visual
//! choices, not measured spectra: ruby (0.9, 0.08, 0.16), sapphire (0.12, 0.25, 0.9) and
//! emerald (0.12, 0.7, 0.3), all over 4 mm, so a 6.5 mm stone is saturated but not black.
//!
//! The same table makes any model a stone (`iris render --stone NAME`,
//! [`crate::prepare::looks`]): [`Stone::material_desc`].

use crate::error::{Error, Result};
use crate::material::{CrystalDesc, CrystalOptics, MaterialDesc};
use crate::spectrum::cie;
use crate::spectrum::crystals::{self, Character, Crystal};
use crate::spectrum::ior::{IorModel, LAMBDA_D};
use glam::{Vec3, Vec4};

/// A named gem material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stone {
    /// Colourless diamond.
    Diamond,
    /// Blue corundum.
    Sapphire,
    /// Red corundum.
    Ruby,
    /// Green beryl.
    Emerald,
    /// Cubic zirconia (yttria-stabilised ZrO₂), colourless.
    CubicZirconia,
    /// Colourless (rock crystal) quartz.
    Quartz,
    /// SCHOTT N-BK7 crown glass.
    CrownGlass,
    /// Calcite (Iceland spar): strongly birefringent, colourless.
    Calcite,
    /// High zircon: birefringent, high dispersion.
    Zircon,
    /// Peridot (forsterite-rich olivine): biaxial, yellowish green.
    Peridot,
    /// Green tourmaline (elbaite): strongly dichroic.
    Tourmaline,
    /// Tanzanite (zoisite): trichroic.
    Tanzanite,
    /// Topaz: biaxial, colourless.
    Topaz,
    /// Moissanite (6H-SiC): birefringent, high index and dispersion.
    Moissanite,
    /// Rutile (TiO₂): extreme birefringence and dispersion.
    Rutile,
}

/// Every stone, in the order the CLI lists them.
pub const STONES: [Stone; 15] = [
    Stone::Diamond,
    Stone::Sapphire,
    Stone::Ruby,
    Stone::Emerald,
    Stone::CubicZirconia,
    Stone::Quartz,
    Stone::CrownGlass,
    Stone::Calcite,
    Stone::Zircon,
    Stone::Peridot,
    Stone::Tourmaline,
    Stone::Tanzanite,
    Stone::Topaz,
    Stone::Moissanite,
    Stone::Rutile,
];

/// Distance over which the coloured stones reach their attenuation colour, metres.
pub const COLOUR_DISTANCE: f32 = 0.004;

impl Stone {
    /// The CLI name (`--stone`).
    pub fn name(self) -> &'static str {
        match self {
            Stone::Diamond => "diamond",
            Stone::Sapphire => "sapphire",
            Stone::Ruby => "ruby",
            Stone::Emerald => "emerald",
            Stone::CubicZirconia => "cubic-zirconia",
            Stone::Quartz => "quartz",
            Stone::CrownGlass => "crown-glass",
            Stone::Calcite => "calcite",
            Stone::Zircon => "zircon",
            Stone::Peridot => "peridot",
            Stone::Tourmaline => "tourmaline",
            Stone::Tanzanite => "tanzanite",
            Stone::Topaz => "topaz",
            Stone::Moissanite => "moissanite",
            Stone::Rutile => "rutile",
        }
    }

    /// The stone's entry in the crystal table when it is birefringent
    /// ([`crate::spectrum::crystals`]); `None` for the isotropic ones.
    pub fn crystal(self) -> Option<&'static Crystal> {
        crystals::named(self.name()).filter(|c| c.character() != Character::Isotropic)
    }

    /// The index the isotropic stand-in uses from the crystal table: n_o (uniaxial) or
    /// n_β (biaxial), the principal y index.
    fn table_index(self) -> Option<IorModel> {
        crystals::named(self.name()).map(|c| c.axes[1])
    }

    /// Parses a CLI name (case-insensitive; `_` and `-` alike); the error lists the names.
    pub fn parse(s: &str) -> Result<Stone> {
        let key = s.trim().to_ascii_lowercase().replace('_', "-");
        STONES
            .into_iter()
            .find(|st| st.name() == key)
            .ok_or_else(|| {
                let names: Vec<&str> = STONES.iter().map(|st| st.name()).collect();
                Error::Usage(format!(
                    "--stone {s:?}: unknown stone (expected one of: {})",
                    names.join(", ")
                ))
            })
    }

    /// Refractive index at 587.6 nm (see the module table), rounded to 4 decimals for the
    /// crystal table's stones.
    pub fn n_d(self) -> f32 {
        match self {
            Stone::Diamond => 2.417,
            Stone::Sapphire | Stone::Ruby => 1.770,
            Stone::Emerald => 1.583,
            Stone::CubicZirconia => 2.16,
            Stone::Quartz => 1.544,
            Stone::CrownGlass => 1.5168,
            _ => self
                .table_index()
                .map_or(1.5, |m| (m.ior(LAMBDA_D) * 1e4).round() / 1e4),
        }
    }

    /// Abbe number V_d (see the module table), rounded to 0.1 for the crystal table's
    /// stones.
    pub fn abbe(self) -> f32 {
        match self {
            Stone::Diamond => 55.0,
            Stone::Sapphire | Stone::Ruby | Stone::Emerald => 72.0,
            Stone::CubicZirconia => 28.0,
            Stone::Quartz => 70.0,
            Stone::CrownGlass => 64.17,
            _ => self
                .table_index()
                .map_or(60.0, |m| (m.abbe_number() * 10.0).round() / 10.0),
        }
    }

    /// KHR_materials_dispersion `dispersion` = 20 / V_d.
    pub fn dispersion(self) -> f32 {
        20.0 / self.abbe()
    }

    /// Linear RGB colour reached after [`COLOUR_DISTANCE`], `None` for colourless stones:
    /// chosen for ruby, sapphire and emerald; for the other pleochroic stones the colour of
    /// D65 light through [`COLOUR_DISTANCE`] with the mean of the table's three absorption
    /// spectra (unpolarized light sees their mean on average), white normalized to 1.
    pub fn attenuation(self) -> Option<Vec3> {
        match self {
            Stone::Ruby => Some(Vec3::new(0.9, 0.08, 0.16)),
            Stone::Sapphire => Some(Vec3::new(0.12, 0.25, 0.9)),
            Stone::Emerald => Some(Vec3::new(0.12, 0.7, 0.3)),
            _ => self.crystal().and_then(mean_colour),
        }
    }

    /// Display name used for the glTF material, e.g. `Diamond (n_d 2.417, Abbe 55)`.
    pub fn title(self) -> String {
        let name = match self {
            Stone::Diamond => "Diamond",
            Stone::Sapphire => "Sapphire",
            Stone::Ruby => "Ruby",
            Stone::Emerald => "Emerald",
            Stone::CubicZirconia => "Cubic zirconia",
            Stone::Quartz => "Quartz",
            Stone::CrownGlass => "Crown glass N-BK7",
            Stone::Calcite => "Calcite",
            Stone::Zircon => "Zircon",
            Stone::Peridot => "Peridot",
            Stone::Tourmaline => "Tourmaline",
            Stone::Tanzanite => "Tanzanite",
            Stone::Topaz => "Topaz",
            Stone::Moissanite => "Moissanite",
            Stone::Rutile => "Rutile",
        };
        format!("{name} (n_d {}, Abbe {})", self.n_d(), self.abbe())
    }

    /// The glTF material for a stone whose typical thickness (KHR_materials_volume
    /// `thicknessFactor`, used by rasterisers only) is `thickness` metres.
    /// It is [`Stone::material_desc`] named [`Stone::title`] with its colour reached after
    /// [`COLOUR_DISTANCE`], its IOR, transmission and volume extensions stated, and a
    /// crystal's `extras.iris_crystal` naming the stone (the key its `crystal` is read from).
    pub fn material(self, thickness: f32) -> MaterialDesc {
        MaterialDesc {
            thickness,
            stated: super::material::glass_extensions(),
            extras: self
                .crystal()
                .map(|_| serde_json::json!({"iris_crystal": {"stone": self.name()}})),
            ..self.material_desc(self.title(), COLOUR_DISTANCE)
        }
    }
}

impl Stone {
    /// The stone as a render material, what `--stone` puts on a model
    /// ([`crate::prepare::looks`]): the same values as [`Stone::material`] — smooth
    /// (roughness 0), transmission 1, KHR_materials_ior n_d, KHR_materials_dispersion
    /// 20/V_d, a volume (thickness 1: any value > 0 makes the mesh bound a medium in Iris;
    /// only rasterisers read the number) — with coloured stones reaching their attenuation
    /// colour after `colour_distance` metres. Everything else is the glTF default: white,
    /// not metallic, untextured, not emissive, opaque alpha. `name` names it in messages.
    pub fn material_desc(self, name: String, colour_distance: f32) -> MaterialDesc {
        let (attenuation_color, attenuation_distance) = match self.attenuation() {
            Some(c) => (c, colour_distance),
            None => (Vec3::ONE, f32::INFINITY),
        };
        MaterialDesc {
            name,
            base_color: Vec4::ONE,
            metallic: 0.0,
            roughness: 0.0,
            ior: self.n_d(),
            dispersion: self.dispersion(),
            transmission: 1.0,
            thickness: 1.0,
            attenuation_color,
            attenuation_distance,
            crystal: self
                .crystal()
                .and_then(|c| CrystalDesc::oriented(CrystalOptics::Table(c), Vec3::Y, None).ok()),
            ..MaterialDesc::default()
        }
    }
}

/// The colour of D65 through [`COLOUR_DISTANCE`] of the mean of a crystal's three
/// absorption spectra, normalized so that no absorption is white (1, 1, 1); `None`
/// without absorption.
fn mean_colour(c: &Crystal) -> Option<Vec3> {
    c.absorption.as_ref()?;
    let through = |nm: f32| {
        let a = c.absorption_at(nm);
        cie::d65_normalized(nm) * (-(a[0] + a[1] + a[2]) / 3.0 * COLOUR_DISTANCE).exp()
    };
    let rgb = cie::xyz_to_linear_srgb(cie::spectrum_to_xyz(through));
    let white = cie::xyz_to_linear_srgb(cie::spectrum_to_xyz(cie::d65_normalized));
    Some(Vec3::from(rgb) / Vec3::from(white)).map(|v| v.clamp(Vec3::splat(1e-3), Vec3::ONE))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_names_list_the_choices() {
        for st in STONES {
            assert_eq!(Stone::parse(st.name()).ok(), Some(st));
        }
        assert_eq!(
            Stone::parse("Cubic_Zirconia").ok(),
            Some(Stone::CubicZirconia)
        );
        let err = Stone::parse("glass").expect_err("unknown").to_string();
        assert!(
            err.contains("crown-glass") && err.contains("glass"),
            "{err}"
        );
    }

    #[test]
    fn materials_carry_ior_dispersion_and_colour() {
        let d = Stone::Diamond.material(0.004);
        assert_eq!(d.ior, 2.417);
        // 20/55 = 0.363636…, exact to f32 rounding.
        assert!((d.dispersion - 20.0 / 55.0).abs() < 1e-7);
        assert_eq!((d.transmission, d.thickness), (1.0, 0.004));
        assert!(d.attenuation_distance.is_infinite());
        let r = Stone::Ruby.material(0.004);
        assert!(r.attenuation_color.x > r.attenuation_color.y);
        assert_eq!(r.attenuation_distance, COLOUR_DISTANCE);
        let s = Stone::Sapphire.material(0.004).attenuation_color;
        assert!(s.z > s.x);
        let e = Stone::Emerald.material(0.004).attenuation_color;
        assert!(e.y > e.x.max(e.z));
    }

    /// A crystal's written material names it in `extras` and carries its reading.
    #[test]
    fn crystal_materials_name_their_stone() {
        for st in STONES {
            let m = st.material(0.004);
            assert_eq!(m.crystal.is_some(), st.crystal().is_some(), "{}", st.name());
            assert_eq!(
                m.extras
                    .is_some_and(|x| x["iris_crystal"]["stone"] == st.name()),
                st.crystal().is_some()
            );
        }
    }
}
