//! Material axes into world space: a crystal material's principal axes
//! ([`crate::material::CrystalDesc`]) and a polarizer sheet's transmission axis are given
//! in the frame of the mesh they are on; each mesh orientation
//! ([`MeshDesc::orientation`](super::desc::MeshDesc)) gets its own copy of the material
//! with the axes turned into world space, so a stone's orientation in its file (and on a
//! turntable) sets its optics. The first orientation met keeps the material's index.

use super::desc::SceneDesc;
use glam::Mat3;

/// Turns every crystal's and polarizer's axes into world space, one material per
/// orientation.
pub(super) fn orient(desc: &mut SceneDesc) {
    // (material as loaded, orientation bits, index of the oriented copy)
    let mut made: Vec<(usize, [u32; 9], usize)> = Vec::new();
    let local: Vec<_> = desc
        .materials
        .iter()
        .map(|m| (m.crystal, m.polarizer))
        .collect();
    for mesh in &mut desc.meshes {
        let Some(mi) = mesh.material else { continue };
        let Some(&(crystal, polarizer)) = local.get(mi) else {
            continue;
        };
        if crystal.is_none() && polarizer.is_none() {
            continue;
        }
        let key = mesh.orientation.to_cols_array().map(f32::to_bits);
        if let Some(&(_, _, to)) = made.iter().find(|(m, k, _)| *m == mi && *k == key) {
            mesh.material = Some(to);
            continue;
        }
        let crystal = crystal.map(|c| crate::material::CrystalDesc {
            axes: world_axes(c.axes, mesh.orientation),
            ..c
        });
        let polarizer = polarizer.map(|p| (mesh.orientation * p).normalize_or_zero());
        let to = if made.iter().any(|(m, _, _)| *m == mi) {
            desc.materials.push(desc.materials[mi].clone());
            desc.materials.len() - 1
        } else {
            mi
        };
        desc.materials[to].crystal = crystal;
        desc.materials[to].polarizer = polarizer;
        made.push((mi, key, to));
        mesh.material = Some(to);
    }
}

/// The principal axes `local` (orthonormal columns in the mesh's frame) under the mesh's
/// linear transform `m`: z mapped and normalized, x mapped and made ⊥ z, y = z × x. A
/// degenerate transform keeps the local axes.
fn world_axes(local: Mat3, m: Mat3) -> Mat3 {
    let z = m * local.z_axis;
    let x = m * local.x_axis;
    if z.length_squared() < 1e-30 {
        return local;
    }
    let z = z.normalize();
    let x = x - z * x.dot(z);
    let x = if x.length_squared() < 1e-30 {
        z.any_orthonormal_vector()
    } else {
        x.normalize()
    };
    Mat3::from_cols(x, z.cross(x), z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{CrystalDesc, CrystalOptics, MaterialDesc};
    use crate::scene::desc::MeshDesc;
    use glam::Vec3;

    #[test]
    fn each_orientation_gets_its_own_world_axes() {
        let crystal =
            CrystalDesc::oriented(CrystalOptics::Indices([1.6, 1.6, 1.5]), Vec3::Z, None).unwrap();
        let mut desc = SceneDesc {
            materials: vec![MaterialDesc {
                crystal: Some(crystal),
                ..Default::default()
            }],
            ..Default::default()
        };
        let turned = Mat3::from_rotation_x(std::f32::consts::FRAC_PI_2) * 2.0;
        for orientation in [Mat3::IDENTITY, turned, Mat3::IDENTITY] {
            desc.meshes.push(MeshDesc {
                material: Some(0),
                orientation,
                ..Default::default()
            });
        }
        orient(&mut desc);
        let ids: Vec<_> = desc.meshes.iter().map(|m| m.material).collect();
        assert_eq!(ids, [Some(0), Some(1), Some(0)]);
        let z = |i: usize| desc.materials[i].crystal.unwrap().axes.z_axis;
        assert!((z(0) - Vec3::Z).length() < 1e-6);
        // Rotating 90° about x takes the optic axis z to −y; the scale is removed.
        assert!((z(1) + Vec3::Y).length() < 1e-6, "{}", z(1));
    }
}
