//! Material axes into world space: a crystal material's principal axes
//! ([`crate::material::CrystalDesc`]) and a polarizer sheet's transmission axis are given
//! in the frame of the mesh they are on; each mesh orientation
//! ([`MeshDesc::orientation`](super::desc::MeshDesc)) gets its own copy of the material
//! with the axes turned into world space, so a stone's orientation in its file (and on a
//! turntable) sets its optics. The first orientation met keeps the material's index.

use super::desc::SceneDesc;
use crate::math::unit_direction;
use glam::{Mat3, Vec3};

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
        let polarizer = polarizer.map(|p| world_direction(p, mesh.orientation));
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

/// The unit direction of the mesh-frame direction `v` under the mesh's linear transform
/// `m`, mapped in f64 and normalised safely ([`unit_direction`]), so a node scaled by 1e30
/// or 1e-30 turns the direction as one scaled by 1; `v` itself when the transform
/// collapses it (a zero scale).
fn world_direction(v: Vec3, m: Mat3) -> Vec3 {
    unit_direction(m.as_dmat3() * v.as_dvec3()).unwrap_or(v)
}

/// The principal axes `local` (orthonormal columns in the mesh's frame) under the mesh's
/// linear transform `m`: z mapped and normalized, x mapped and made ⊥ z, y = z × x. A
/// transform that collapses z keeps the local axes.
fn world_axes(local: Mat3, m: Mat3) -> Mat3 {
    let m = m.as_dmat3();
    let Ok(z) = unit_direction(m * local.z_axis.as_dvec3()) else {
        return local;
    };
    let x = unit_direction(m * local.x_axis.as_dvec3()).unwrap_or(Vec3::ZERO);
    let t = x - z * x.dot(z); // x and z are unit: |t| ≤ 1, no overflow
    let x = if t.length() < 1e-3 {
        z.any_orthonormal_vector()
    } else {
        t.normalize()
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

    /// A node scaled by 1e30 or 1e-30 turns a crystal's axes and a polarizer's axis as
    /// one scaled by 1 (their f32 lengths would overflow or underflow).
    #[test]
    fn extreme_node_scales_turn_axes_as_unit_scale() {
        let crystal =
            CrystalDesc::oriented(CrystalOptics::Indices([1.6, 1.6, 1.5]), Vec3::Z, None).unwrap();
        for scale in [1e30f32, 1e-30] {
            let mut desc = SceneDesc {
                materials: vec![
                    MaterialDesc {
                        crystal: Some(crystal),
                        ..Default::default()
                    },
                    MaterialDesc {
                        polarizer: Some(Vec3::X),
                        ..Default::default()
                    },
                ],
                ..Default::default()
            };
            let turned = Mat3::from_rotation_x(std::f32::consts::FRAC_PI_2)
                * Mat3::from_rotation_z(std::f32::consts::FRAC_PI_2)
                * scale;
            for material in [0, 1] {
                desc.meshes.push(MeshDesc {
                    material: Some(material),
                    orientation: turned,
                    ..Default::default()
                });
            }
            orient(&mut desc);
            let axes = desc.materials[0].crystal.unwrap().axes;
            assert!((axes.z_axis + Vec3::Y).length() < 1e-6, "{scale}: {axes}");
            assert!((axes.determinant() - 1.0).abs() < 1e-5, "{scale}: {axes}");
            // Rz(90°) takes x to y, then Rx(90°) takes y to z.
            let p = desc.materials[1].polarizer.unwrap();
            assert!((p - Vec3::Z).length() < 1e-6, "{scale}: {p}");
        }
    }
}
