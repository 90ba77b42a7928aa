//! Polarizer sheets (`extras.iris_polarizer`): the transmission axis of a sheet lies in the
//! sheet. An axis along the sheet's normal gives light arriving along the normal no
//! transmission axis at all (the renderer would pick an arbitrary one) and light arriving
//! obliquely one set by its plane of incidence, not by the file; so an axis within
//! [`MIN_ANGLE_DEG`] of the geometric normal of any of the sheet's triangles is an error
//! naming the file, the material, the mesh and how many triangles. The axis is given in
//! the mesh's frame and compared in world space (turned by the mesh's orientation, which
//! keeps a direction in the sheet's plane in it); normals are the triangles' geometric
//! ones, after mesh repair (no degenerate triangle is left).

use super::{element, fail};
use crate::error::{LoadError, LoadErrorKind};
use crate::math::unit_direction;
use crate::scene::desc::SceneDesc;

/// The least angle, degrees, between a sheet's axis and its normal.
pub const MIN_ANGLE_DEG: f64 = 1.0;

/// The check of the module docs.
pub(super) fn check_sheets(desc: &SceneDesc) -> Result<(), LoadError> {
    let limit = MIN_ANGLE_DEG.to_radians().cos();
    for (k, mesh) in desc.meshes.iter().enumerate() {
        let Some(mi) = mesh.material else { continue };
        let Some(axis) = desc.materials.get(mi).and_then(|m| m.polarizer) else {
            continue;
        };
        let Ok(world) = unit_direction(mesh.orientation.as_dmat3() * axis.as_dvec3()) else {
            continue; // a collapsed transform: nothing to compare
        };
        let world = world.as_dvec3();
        let along: Vec<usize> = mesh
            .indices
            .iter()
            .enumerate()
            .filter(|(_, t)| {
                let [p0, p1, p2] = t.map(|i| mesh.positions[i as usize].as_dvec3());
                unit_direction((p1 - p0).cross(p2 - p0))
                    .is_ok_and(|n| n.as_dvec3().dot(world).abs() >= limit)
            })
            .map(|(t, _)| t)
            .collect();
        if let Some(&first) = along.first() {
            let m = &desc.materials[mi];
            return Err(fail(
                &desc.source,
                &element(&m.name, "material", mi),
                LoadErrorKind::InvalidValue,
                format!(
                    "extras.iris_polarizer.axis {axis} lies along the sheet's normal (within \
                     {MIN_ANGLE_DEG}°) on {} of the {} triangles of mesh {:?} (the first: \
                     triangle {first}); a sheet's transmission axis must lie in the sheet",
                    along.len(),
                    mesh.indices.len(),
                    element(&mesh.name, "mesh", k)
                ),
            ));
        }
    }
    Ok(())
}
