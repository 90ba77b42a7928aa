//! A birefringent crystal material ([`CrystalDesc`]): its optics (an entry of the crystal
//! table [`crate::spectrum::crystals`] or principal indices given in the file) and the
//! orientation of its principal axes.
//!
//! Frames: `axes` holds the principal axes x, y, z as orthonormal columns, in the frame of
//! the mesh the material is on as loaded, and in world space once the scene is built
//! ([`crate::scene`] gives each orientation its own material). For a uniaxial crystal z is
//! the optic axis c; for a biaxial one x, y, z carry n_α < n_β < n_γ.
//!
//! In a glTF file: material `extras.iris_crystal` (docs/gem-optics.md), e.g.
//! `{"stone": "calcite", "optic_axis": [0, 0, 1]}` or
//! `{"n": [1.654, 1.672, 1.690], "optic_axis": [0, 1, 0], "x_axis": [1, 0, 0]}`.

use crate::spectrum::crystals::{character_of, Character, Crystal};
use glam::{Mat3, Vec3};

/// Where a crystal's principal indices come from.
#[derive(Debug, Clone, Copy)]
pub enum CrystalOptics {
    /// An entry of the crystal table: dispersive indices and, for pleochroic stones,
    /// absorption per axis.
    Table(&'static Crystal),
    /// Principal indices n_x, n_y, n_z without dispersion or absorption.
    Indices([f32; 3]),
}

impl PartialEq for CrystalOptics {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (CrystalOptics::Table(a), CrystalOptics::Table(b)) => a.name == b.name,
            (CrystalOptics::Indices(a), CrystalOptics::Indices(b)) => a == b,
            _ => false,
        }
    }
}

/// The lowest and highest principal index accepted (air to beyond rutile's n_e ≈ 2.9).
pub const INDEX_RANGE: (f32, f32) = (1.0, 4.0);

/// A crystal material's optics and axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrystalDesc {
    /// The indices (and absorption).
    pub optics: CrystalOptics,
    /// The principal axes as orthonormal columns (module docs for the frame).
    pub axes: Mat3,
}

impl CrystalDesc {
    /// A crystal with its optic (z) axis along `c` and its x axis toward `x` (any
    /// direction ⊥ c when `None`); both must be finite and non-zero, and not parallel.
    pub fn oriented(optics: CrystalOptics, c: Vec3, x: Option<Vec3>) -> Result<Self, String> {
        let z = unit(c, "optic_axis")?;
        let x = match x {
            Some(x) => {
                let x = unit(x, "x_axis")?;
                let t = x - z * x.dot(z);
                if t.length() < 1e-3 {
                    return Err("x_axis is parallel to optic_axis".into());
                }
                t.normalize()
            }
            None => z.any_orthonormal_vector(),
        };
        let y = z.cross(x);
        Ok(CrystalDesc {
            optics,
            axes: Mat3::from_cols(x, y, z),
        })
    }

    /// The principal indices at `nm`.
    pub fn indices(&self, nm: f32) -> [f32; 3] {
        match self.optics {
            CrystalOptics::Table(c) => c.indices(nm),
            CrystalOptics::Indices(n) => n,
        }
    }

    /// Absorption coefficients (1/m) for light polarized along x, y, z at `nm`.
    pub fn absorption(&self, nm: f32) -> [f32; 3] {
        match self.optics {
            CrystalOptics::Table(c) => c.absorption_at(nm),
            CrystalOptics::Indices(_) => [0.0; 3],
        }
    }

    /// The optical character at 589.3 nm.
    pub fn character(&self) -> Character {
        match self.optics {
            CrystalOptics::Table(c) => c.character(),
            CrystalOptics::Indices(n) => character_of(n),
        }
    }

    /// The mean of the principal indices at `nm`: the index an isotropic stand-in uses.
    pub fn mean_index(&self, nm: f32) -> f32 {
        let n = self.indices(nm);
        (n[0] + n[1] + n[2]) / 3.0
    }

    /// The crystal at `nm` for the optics of [`crate::polar::crystal`].
    pub fn at(&self, nm: f32) -> crate::polar::crystal::Indicatrix {
        crate::polar::crystal::Indicatrix {
            axes: self.axes,
            n: self.indices(nm),
        }
    }

    /// The transmittance e^(−σ t) over `t` metres of light at `nm` in the mode whose D field
    /// is along `d` (σ from the absorption per axis, [`crate::polar::crystal::Indicatrix::absorption`]);
    /// `None` for a crystal without an absorption table (the material's Beer–Lambert volume
    /// applies then).
    pub fn mode_transmittance(&self, nm: f32, d: glam::Vec3, t: f32) -> Option<f32> {
        let sigma = self.absorption(nm);
        if sigma == [0.0; 3] {
            return None;
        }
        Some((-self.at(nm).absorption(d, sigma) * t).exp())
    }
}

/// A material's optical character for `iris info`: the crystal's class, indices at
/// 589.3 nm, birefringence, optic axis and pleochroism; "isotropic" for other transmissive
/// volumes; `None` for the rest.
pub fn describe_optics(m: &super::MaterialDesc) -> Option<String> {
    let Some(c) = &m.crystal else {
        return (m.transmission > 0.0 && m.thickness > 0.0).then(|| "optics isotropic".into());
    };
    let nm = crate::spectrum::crystals::LAMBDA_NA_D;
    let n = c.indices(nm);
    let (class, ns) = match c.character() {
        Character::Isotropic => ("isotropic".to_string(), format!("n {:.4}", n[0])),
        Character::Uniaxial { positive } => (
            format!("uniaxial {}", if positive { "+" } else { "−" }),
            format!("n_o {:.4} n_e {:.4}", n[0], n[2]),
        ),
        Character::Biaxial { positive } => (
            format!("biaxial {}", if positive { "+" } else { "−" }),
            format!("n_α {:.4} n_β {:.4} n_γ {:.4}", n[0], n[1], n[2]),
        ),
    };
    let max = n.iter().copied().fold(f32::MIN, f32::max);
    let min = n.iter().copied().fold(f32::MAX, f32::min);
    let name = match c.optics {
        CrystalOptics::Table(t) => format!(" {}", t.name),
        CrystalOptics::Indices(_) => String::new(),
    };
    let z = c.axes.z_axis;
    let pleo = match c.optics {
        CrystalOptics::Table(t) if t.absorption.is_some() => ", pleochroic",
        _ => "",
    };
    Some(format!(
        "optics{name} {class} ({ns} at {nm} nm, birefringence {:.4}, optic axis [{:.3} {:.3} {:.3}]{pleo})",
        max - min,
        z.x,
        z.y,
        z.z
    ))
}

/// Checks principal indices given in a file: finite, within [`INDEX_RANGE`].
pub fn check_indices(n: &[f32]) -> Result<(), String> {
    for (i, v) in n.iter().enumerate() {
        if !v.is_finite() || *v < INDEX_RANGE.0 || *v > INDEX_RANGE.1 {
            return Err(format!(
                "index {} = {v} must be a finite number from {} to {}",
                i + 1,
                INDEX_RANGE.0,
                INDEX_RANGE.1
            ));
        }
    }
    Ok(())
}

/// `v` as a unit vector ([`crate::math::unit_direction`]); the error names `what`.
fn unit(v: Vec3, what: &str) -> Result<Vec3, String> {
    crate::math::unit_direction(v.as_dvec3()).map_err(|why| format!("{what} {why}: {v}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_are_orthonormal_with_z_along_the_optic_axis() {
        let c = CrystalDesc::oriented(
            CrystalOptics::Indices([1.6, 1.6, 1.5]),
            Vec3::new(0.0, 2.0, 0.0),
            Some(Vec3::new(1.0, 1.0, 0.0)),
        )
        .unwrap();
        assert!((c.axes.z_axis - Vec3::Y).length() < 1e-6);
        assert!((c.axes.x_axis - Vec3::X).length() < 1e-6);
        assert!((c.axes.determinant() - 1.0).abs() < 1e-6);
        assert_eq!(c.character(), Character::Uniaxial { positive: false });
    }

    #[test]
    fn bad_axes_and_indices_are_refused() {
        let o = CrystalOptics::Indices([1.6, 1.6, 1.5]);
        assert!(CrystalDesc::oriented(o, Vec3::ZERO, None)
            .unwrap_err()
            .contains("zero"));
        assert!(
            CrystalDesc::oriented(o, Vec3::new(f32::NAN, 0.0, 1.0), None)
                .unwrap_err()
                .contains("not finite")
        );
        assert!(CrystalDesc::oriented(o, Vec3::Z, Some(Vec3::Z))
            .unwrap_err()
            .contains("parallel"));
        assert!(check_indices(&[1.6, 0.5]).is_err());
        assert!(check_indices(&[1.6, f32::INFINITY]).is_err());
        assert!(check_indices(&[1.6, 1.5]).is_ok());
    }
}
