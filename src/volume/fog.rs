//! The scene-wide medium: fog or haze filling the air of a scene (`--fog SPEC`, or the glTF
//! scene's `extras.iris_fog` with the same text), bounded by the scene's bounding box so an
//! environment light still reaches the scene from outside it.
//!
//! SPEC is comma-separated `key=value` pairs (a bare number is `density`):
//! - `density=D`: grey extinction σ_t = D per scene unit (m⁻¹ for metric files);
//! - `rayleigh=S`: Rayleigh scattering, σ_s(λ) = S (550/λ)⁴, Rayleigh's phase function;
//! - `color=R:G:B`: the fog's multiple-scattering albedo (KHR_materials_scatter's
//!   `multiscatterColor`, linear RGB in [0, 1], default white: nothing absorbed);
//! - `g=G`: Henyey–Greenstein anisotropy in (−1, 1) (default 0, isotropic).
//!
//! Each key at most once (a repeated key is an error, not the last value); exactly one of
//! `density` and `rayleigh`; `color` goes with `density` only. The fog
//! applies where a path is in air (inside no volume); volumes keep their own media.

use super::medium::{Medium, Scattering};
use super::phase::Phase;
use glam::Vec3;

/// A medium filling an axis-aligned box of air.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// The medium.
    pub medium: Medium,
    /// The box it fills (min, max corners, world space).
    pub bounds: (Vec3, Vec3),
}

impl Fog {
    /// The part [t0, t1] of the ray `origin + t dir` (t in [t_min, t_max], `dir` of any
    /// length, t in its units; t_min ≤ 0 where the ray really starts behind its origin)
    /// inside the box; `None` if it misses or the part is empty (slab method, Kay & Kajiya
    /// 1986).
    pub fn clip(&self, origin: Vec3, dir: Vec3, (t_min, t_max): (f32, f32)) -> Option<(f32, f32)> {
        let (lo, hi) = self.bounds;
        let inv = dir.recip();
        let a = (lo - origin) * inv;
        let b = (hi - origin) * inv;
        let near = a.min(b);
        let far = a.max(b);
        // NaN (0 · ∞ on an axis-parallel ray through a face) is ignored by max/min.
        let t0 = near.x.max(near.y).max(near.z).max(t_min);
        let t1 = far.x.min(far.y).min(far.z).min(t_max);
        (t0 < t1).then_some((t0, t1))
    }
}

/// A fog specification (module docs) parsed into its medium; `Err` says what is wrong.
pub fn parse(spec: &str) -> Result<Medium, String> {
    let (mut density, mut rayleigh, mut color, mut g) = (None, None, None, 0.0f32);
    let mut seen: Vec<&str> = Vec::new();
    for part in spec.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (key, value) = part.split_once('=').unwrap_or(("density", part));
        let number = |v: &str| -> Result<f32, String> {
            v.trim()
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{key}={v}: not a finite number"))
        };
        let key = key.trim();
        let canonical = if key == "colour" { "color" } else { key };
        if seen.contains(&canonical) {
            return Err(format!(
                "{canonical} is given twice (each key at most once; a bare number is density)"
            ));
        }
        seen.push(canonical);
        match key {
            "density" => density = Some(number(value)?),
            "rayleigh" => rayleigh = Some(number(value)?),
            "g" => g = number(value)?,
            "color" | "colour" => {
                let c: Vec<f32> = value.split(':').map(number).collect::<Result<_, _>>()?;
                if c.len() != 3 {
                    return Err(format!("color={value}: give R:G:B"));
                }
                color = Some(Vec3::new(c[0], c[1], c[2]));
            }
            other => {
                return Err(format!(
                    "unknown key {other:?}: use density, rayleigh, color or g"
                ))
            }
        }
    }
    if !(g > -1.0 && g < 1.0) {
        return Err(format!("g={g} must lie in (-1, 1)"));
    }
    let phase = |default: Phase| {
        if g != 0.0 {
            Phase::HenyeyGreenstein { g }
        } else {
            default
        }
    };
    let medium = match (density, rayleigh) {
        (Some(d), None) => {
            if d < 0.0 {
                return Err(format!("density={d} must not be negative"));
            }
            Medium {
                // −ln(e⁻¹) · d = d.
                attenuation_color: Vec3::splat((-1.0f32).exp()),
                attenuation_distance: if d > 0.0 { 1.0 / d } else { f32::INFINITY },
                scattering: Scattering::Albedo {
                    multiscatter: color.unwrap_or(Vec3::ONE),
                },
                phase: phase(Phase::Isotropic),
            }
        }
        (None, Some(s)) => {
            if color.is_some() {
                return Err("color goes with density, not with rayleigh".into());
            }
            Medium {
                attenuation_color: Vec3::ONE,
                attenuation_distance: f32::INFINITY,
                scattering: Scattering::Rayleigh { at_550: s },
                phase: phase(Phase::Rayleigh),
            }
        }
        (Some(_), Some(_)) => return Err("give density or rayleigh, not both".into()),
        (None, None) => return Err("give density=D or rayleigh=S".into()),
    };
    medium.check()?;
    Ok(medium)
}

/// The specification [`parse`] reads back as `m`, or `None` for a medium no specification
/// gives (an attenuation colour other than the one `density` sets, a scattering albedo with
/// Rayleigh, a phase function the keys cannot name). The density is the shortest number
/// whose reciprocal is `m`'s attenuation distance, so the medium comes back bit for bit.
pub fn spec(m: &Medium) -> Option<String> {
    let g = match (m.phase, m.scattering) {
        (Phase::HenyeyGreenstein { g }, _) if g != 0.0 => Some(g),
        (Phase::Isotropic, Scattering::Albedo { .. }) => None,
        (Phase::Rayleigh, Scattering::Rayleigh { .. }) => None,
        _ => return None,
    };
    let mut parts = match m.scattering {
        Scattering::Albedo { multiscatter } => {
            if m.attenuation_color != Vec3::splat((-1.0f32).exp()) {
                return None;
            }
            let mut parts = vec![format!("density={}", density_of(m.attenuation_distance)?)];
            if multiscatter != Vec3::ONE {
                let c = multiscatter;
                parts.push(format!("color={}:{}:{}", c.x, c.y, c.z));
            }
            parts
        }
        Scattering::Rayleigh { at_550 } => {
            if m.attenuation_color != Vec3::ONE || m.attenuation_distance != f32::INFINITY {
                return None;
            }
            vec![format!("rayleigh={at_550}")]
        }
    };
    if let Some(g) = g {
        parts.push(format!("g={g}"));
    }
    Some(parts.join(","))
}

/// The density `d` with `1/d` = `distance` in `f32` (0 for an infinite distance), or `None`.
fn density_of(distance: f32) -> Option<f32> {
    if distance == f32::INFINITY {
        return Some(0.0);
    }
    let d = 1.0 / distance;
    [d, d.next_up(), d.next_down()]
        .into_iter()
        .find(|&c| c.is_finite() && c > 0.0 && 1.0 / c == distance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_into_media() {
        let m = parse("0.5").unwrap();
        let c = m.coeffs::<Vec3>(&());
        assert!((c.sigma_t - Vec3::splat(0.5)).abs().max_element() < 1e-5);
        assert!((c.sigma_s - c.sigma_t).abs().max_element() < 1e-4);
        let m = parse("density=2,color=0.5:0.5:0.5,g=0.6").unwrap();
        assert_eq!(m.phase, Phase::HenyeyGreenstein { g: 0.6 });
        assert!(m.coeffs::<Vec3>(&()).sigma_s.x < 2.0);
        let m = parse("rayleigh=0.1").unwrap();
        assert_eq!(m.phase, Phase::Rayleigh);
        assert!(m.wants_spectral());
        for bad in [
            "",
            "density=-1",
            "density=1,rayleigh=1",
            "g=1,density=1",
            "density=nan",
            "rayleigh=1,color=1:1:1",
            "color=1:1,density=1",
            "color=2:1:1,density=1",
            "fog=1",
        ] {
            assert!(parse(bad).is_err(), "{bad:?} accepted");
        }
    }

    /// A repeated key is refused naming it, rather than the last value winning.
    #[test]
    fn repeated_keys_are_refused() {
        for (spec, key) in [
            ("density=1,density=2", "density"),
            ("0.5,0.6", "density"),
            ("0.5,density=0.6", "density"),
            ("rayleigh=1,rayleigh=1", "rayleigh"),
            ("density=1,g=0.2,g=0.3", "g"),
            ("density=1,color=1:1:1,colour=0.5:0.5:0.5", "color"),
        ] {
            let e = parse(spec).unwrap_err();
            assert!(e.contains(key) && e.contains("twice"), "{spec}: {e}");
        }
    }

    /// Every medium a specification gives comes back from its written specification.
    #[test]
    fn specs_are_written_back_exactly() {
        for text in [
            "density=0.3,g=0.3",
            "0.7",
            "density=0",
            "density=3,color=0.2:0.5:0.9",
            "rayleigh=0.05",
            "rayleigh=0.05,g=-0.4",
        ] {
            let m = parse(text).unwrap();
            let written = spec(&m).unwrap_or_default();
            assert_eq!(parse(&written), Ok(m), "{text} → {written}");
        }
        let mut odd = parse("1").unwrap();
        odd.attenuation_color = Vec3::new(0.5, 0.6, 0.7);
        assert_eq!(spec(&odd), None);
    }

    #[test]
    fn clip_keeps_the_part_inside_the_box() {
        let fog = Fog {
            medium: parse("1").unwrap(),
            bounds: (Vec3::splat(-1.0), Vec3::splat(1.0)),
        };
        let x = Vec3::X;
        assert_eq!(
            fog.clip(Vec3::new(-3.0, 0.0, 0.0), x, (0.0, 100.0)),
            Some((2.0, 4.0))
        );
        assert_eq!(fog.clip(Vec3::ZERO, x, (0.0, 0.5)), Some((0.0, 0.5)));
        assert_eq!(fog.clip(Vec3::ZERO, x, (-0.25, 0.5)), Some((-0.25, 0.5)));
        assert_eq!(fog.clip(Vec3::new(-3.0, 2.0, 0.0), x, (0.0, 100.0)), None);
        assert_eq!(fog.clip(Vec3::new(3.0, 0.0, 0.0), x, (0.0, 100.0)), None);
    }
}
