//! The stone's frame on the gem stage ([`super`]'s module docs, "Frames"): its scale to
//! stage units (a power of two, [`normalised`]), the table facet ([`up_facet`]), its turns
//! and its extent at a tilt. Units: the file's, or stage units where said (the file's
//! times the stage's scale); angles in degrees at the API.

use crate::error::{LoadError, LoadErrorKind, Result};
use crate::material::MaterialDesc;
use crate::scene::desc::MeshDesc;
use glam::{Quat, Vec3};
use std::collections::BTreeMap;
use std::path::Path;

/// The extents (largest |coordinate| from the centre of the bounding box, file units) of
/// the stones the stage takes, 2⁻¹²⁰ to 2¹²⁰: below, f32 coordinates near the stone's
/// centre are subnormal and lose the precision of its facets; above, its bounding box and
/// the lengths the report gives in file units come near f32's largest value.
pub const EXTENTS: (f32, f32) = (7.523_164e-37, 1.329_228e36);

/// The stone centred on its bounding box and scaled by a power of two to an extent (the
/// largest |coordinate|) in [2^-½, 2^½), with that scale (module docs); an error naming
/// the file when its extent is outside [`EXTENTS`].
pub(super) fn normalised(path: &Path, mut meshes: Vec<MeshDesc>) -> Result<(Vec<MeshDesc>, f32)> {
    let (lo, hi) = bounds(&meshes);
    let centre = 0.5 * lo + 0.5 * hi;
    let extent = meshes
        .iter()
        .flat_map(|m| m.positions.iter())
        .map(|&p| (p - centre).abs().max_element())
        .fold(0.0f32, f32::max);
    let (min, max) = EXTENTS;
    if !(centre.is_finite() && (min..=max).contains(&extent)) {
        let reason = format!(
            "the stone's extent, {extent:e} file units from the centre of its bounding box, \
             is outside {min:e} to {max:e}: its facets cannot be traced in f32 geometry; \
             scale the model"
        );
        return Err(LoadError::new(path, "", LoadErrorKind::InvalidValue, reason).into());
    }
    let scale = (-extent.log2().round()).exp2();
    for m in &mut meshes {
        m.positions
            .iter_mut()
            .for_each(|p| *p = (*p - centre) * scale);
    }
    Ok((meshes, scale))
}

/// A material's lengths in stage units (`scale` stage units per file unit): the
/// attenuation distance and volume thickness times `scale`, Rayleigh's σ_s over it.
pub(super) fn scale_lengths(m: &mut MaterialDesc, scale: f32) {
    m.attenuation_distance *= scale;
    m.thickness *= scale;
    if let Some(crate::volume::VolumeScatter {
        scattering: crate::volume::Scattering::Rayleigh { at_550 },
        ..
    }) = &mut m.scatter
    {
        *at_550 /= scale;
    }
}

/// The outward normal of the largest flat facet within 45° of +Y, if any.
pub(super) fn up_facet(meshes: &[MeshDesc]) -> Option<Vec3> {
    let mut areas: BTreeMap<[i32; 3], (f64, Vec3)> = BTreeMap::new();
    for m in meshes {
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions.get(i as usize).copied().unwrap_or(Vec3::ZERO));
            let cross = (b - a).cross(c - a);
            let area = 0.5 * f64::from(cross.length());
            let n = cross.normalize_or_zero();
            if area <= 0.0 || n.y < std::f32::consts::FRAC_1_SQRT_2 {
                continue;
            }
            let key = (n * 1000.0).round().as_ivec3().to_array();
            let e = areas.entry(key).or_insert((0.0, Vec3::ZERO));
            e.0 += area;
            e.1 += n * area as f32;
        }
    }
    areas
        .values()
        .max_by(|x, y| x.0.total_cmp(&y.0))
        .map(|(_, n)| n.normalize())
}

/// A mesh turned by `q` about the origin (positions, normals, tangents).
pub(super) fn turned(mut m: MeshDesc, q: Quat) -> MeshDesc {
    m.positions.iter_mut().for_each(|p| *p = q * *p);
    m.normals.iter_mut().for_each(|n| *n = q * *n);
    m.tangents
        .iter_mut()
        .for_each(|t| *t = (q * t.truncate()).extend(t.w));
    m
}

/// Bounding box of every vertex.
pub(super) fn bounds(meshes: &[MeshDesc]) -> (Vec3, Vec3) {
    meshes.iter().flat_map(|m| m.positions.iter()).fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// The largest |x| or |z| of a vertex after a tilt of `tilt` degrees.
pub(super) fn reach(meshes: &[MeshDesc], tilt: f32) -> f32 {
    let q = Quat::from_rotation_x(tilt.to_radians());
    meshes
        .iter()
        .flat_map(|m| m.positions.iter())
        .map(|&p| {
            let r = q * p;
            r.x.abs().max(r.z.abs())
        })
        .fold(0.0f32, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brilliant_mesh(turn: Quat) -> MeshDesc {
        let mesh = crate::authoring::gem::Brilliant::tolkowsky(0.0065).build();
        turned(mesh.into_mesh_desc("stone", 0), turn)
    }

    #[test]
    fn auto_table_is_the_brilliants_table() {
        let n = up_facet(&[brilliant_mesh(Quat::IDENTITY)]).unwrap();
        assert!((n - Vec3::Y).length() < 1e-5, "{n}");
        // Tipped by 30°: still found, and the direction follows the stone.
        let q = Quat::from_rotation_z(30f32.to_radians());
        let n = up_facet(&[brilliant_mesh(q)]).unwrap();
        assert!((n - q * Vec3::Y).length() < 1e-4, "{n}");
        // Upside down: no facet faces up by 45°, except the pavilion's, which is smaller
        // than a table would be but still a facet: the rule takes it (documented).
        let down = up_facet(&[brilliant_mesh(Quat::from_rotation_x(std::f32::consts::PI))]);
        assert!(down.is_some_and(|n| n.y > std::f32::consts::FRAC_1_SQRT_2));
    }

    #[test]
    fn reach_grows_with_tilt_for_a_tall_stone() {
        let mut m = brilliant_mesh(Quat::IDENTITY);
        let (lo, hi) = bounds(std::slice::from_ref(&m));
        let c = 0.5 * (lo + hi);
        m.positions.iter_mut().for_each(|p| *p -= c);
        let r0 = reach(std::slice::from_ref(&m), 0.0);
        assert!((r0 - 0.00325).abs() < 2e-5, "{r0}");
        assert!(reach(std::slice::from_ref(&m), 30.0) > r0);
    }
}
