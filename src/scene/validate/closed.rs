//! A scattering medium must be enclosed: the triangles of every material that holds one
//! (a volume, thickness > 0, whose `scatter` scatters) must form closed surfaces, or paths
//! would enter a medium they never leave (or leave one they never entered). Closed means
//! every edge, after welding vertices at bit-identical positions across all meshes of the
//! material, is shared by an even number of its triangles (two for a manifold surface).
//! Also checks each medium's coefficients ([`crate::volume::Medium::check`]).

use super::{element, fail};
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::SceneDesc;
use std::collections::HashMap;

/// The checks of the module docs: an error names the material, the field or the open
/// edges and a mesh that has one.
pub(super) fn check_media(desc: &SceneDesc) -> Result<(), LoadError> {
    for (i, m) in desc.materials.iter().enumerate() {
        let Some(scatter) = m.scatter else { continue };
        let medium = scatter.medium(m.attenuation_color, m.attenuation_distance);
        let name = element(&m.name, "material", i);
        medium.check().map_err(|why| {
            fail(
                &desc.source,
                &name,
                LoadErrorKind::InvalidValue,
                format!("scattering medium: {why}"),
            )
        })?;
        if m.thickness <= 0.0 || !medium.scatters() {
            continue;
        }
        if let Some((open, mesh)) = open_edges(desc, i) {
            return Err(fail(
                &desc.source,
                &name,
                LoadErrorKind::InvalidValue,
                format!(
                    "holds a scattering medium but its surface is open ({open} edges bound a \
                     single triangle, e.g. in mesh {mesh:?}); a medium needs a closed mesh"
                ),
            ));
        }
    }
    Ok(())
}

/// The number of boundary edges of material `material`'s triangles and the name of a mesh
/// with one; `None` when they are closed.
fn open_edges(desc: &SceneDesc, material: usize) -> Option<(usize, String)> {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut edges: HashMap<(u32, u32), (u32, usize)> = HashMap::new();
    for (k, mesh) in desc.meshes.iter().enumerate() {
        if mesh.material != Some(material) {
            continue;
        }
        let welded: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                let n = ids.len() as u32;
                *ids.entry(p.to_array().map(f32::to_bits)).or_insert(n)
            })
            .collect();
        for t in &mesh.indices {
            let v = t.map(|i| welded[i as usize]);
            for (a, b) in [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])] {
                let e = edges.entry((a.min(b), a.max(b))).or_insert((0, k));
                e.0 += 1;
            }
        }
    }
    let open = edges.values().filter(|(n, _)| n % 2 == 1);
    let first = open.clone().next()?.1;
    Some((open.count(), desc.meshes[first].name.clone()))
}
