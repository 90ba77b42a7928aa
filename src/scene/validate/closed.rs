//! What must be enclosed is closed: a scattering medium (the material's volume,
//! thickness > 0, whose `scatter` scatters) and a birefringent crystal
//! (`MaterialDesc::crystal`, from `extras.iris_crystal` or `--stone`) need the triangles of
//! their material to form closed surfaces, or paths would enter a medium or a crystal they
//! never leave (or leave one they never entered). One rule for both: closed means every
//! edge, after welding the vertices of all meshes of the material within the tolerance of
//! [`crate::scene::weld`] (2⁻²⁰ of their size), is shared by an even number of its
//! triangles (two for a manifold surface). The error names the file, the material, the
//! number of open edges, a mesh with one and the tolerance.
//!
//! Also checks each medium's coefficients ([`crate::volume::Medium::check`]) and drops a
//! medium no path can enter: on a thin-walled material (no KHR_materials_volume thickness:
//! there is no volume) or an opaque one (no KHR_materials_transmission, or a metallic
//! factor of 1 that no metallic-roughness texture lowers: no ray crosses its surface); with a warning naming the file, the material and why when
//! it asked for scattering (a `multiscatterColor` or a Rayleigh coefficient above 0).

use super::{element, fail};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::MaterialDesc;
use crate::scene::desc::{MeshDesc, SceneDesc};
use crate::scene::weld::weld;
use crate::volume::Scattering;
use std::collections::HashMap;

/// The medium checks of the module docs: an error names the material, the field or the
/// open edges and a mesh that has one; an ignored medium is dropped with a warning.
pub(super) fn check_media(
    desc: &mut SceneDesc,
    warnings: &mut Vec<String>,
) -> Result<(), LoadError> {
    for i in 0..desc.materials.len() {
        let m = &desc.materials[i];
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
        if let Some(why) = unenterable(m) {
            let source = match scatter.scattering {
                Scattering::Rayleigh { at_550 } => (at_550 > 0.0).then_some("extras.iris_medium"),
                Scattering::Albedo { multiscatter } => (multiscatter.max_element() > 0.0)
                    .then_some("KHR_materials_scatter / KHR_materials_volume_scatter"),
            };
            if let Some(source) = source {
                warnings.push(format!(
                    "{}: {name}: its scattering medium ({source}) is ignored: {why}",
                    desc.source.display()
                ));
            }
            desc.materials[i].scatter = None;
            continue;
        }
        if !medium.scatters() {
            continue;
        }
        require_closed(desc, i, "holds a scattering medium", "a medium")?;
    }
    Ok(())
}

/// Every crystal material's surface is closed (module docs).
pub(super) fn check_crystals(desc: &SceneDesc) -> Result<(), LoadError> {
    for (i, m) in desc.materials.iter().enumerate() {
        if m.crystal.is_some() {
            require_closed(desc, i, "is a birefringent crystal", "a crystal")?;
        }
    }
    Ok(())
}

/// Whether material `material`'s triangles are closed (module docs).
pub(super) fn is_closed(desc: &SceneDesc, material: usize) -> bool {
    open_edges(desc, material).is_none()
}

/// Why no path can enter material `m`'s volume, if none can (module docs).
fn unenterable(m: &MaterialDesc) -> Option<&'static str> {
    if m.thickness <= 0.0 {
        Some(
            "the material is thin-walled (no KHR_materials_volume thicknessFactor > 0), so it \
             bounds no volume",
        )
    } else if m.transmission <= 0.0 || (m.metallic >= 1.0 && m.metallic_roughness_texture.is_none())
    {
        Some(
            "the material is opaque (no KHR_materials_transmission, or metallic 1 without a \
             metallic texture), so no ray enters its volume",
        )
    } else {
        None
    }
}

/// `Err` naming material `material` when its triangles are not closed; `what` says what
/// the material is, `needs` what needs a closed mesh.
fn require_closed(
    desc: &SceneDesc,
    material: usize,
    what: &str,
    needs: &str,
) -> Result<(), LoadError> {
    let Some(open) = open_edges(desc, material) else {
        return Ok(());
    };
    let m = &desc.materials[material];
    Err(fail(
        &desc.source,
        &element(&m.name, "material", material),
        LoadErrorKind::InvalidValue,
        format!(
            "{what} but its surface is open: {} edges bound a single triangle even after \
             welding vertices within {:.3e} (2^-20 of the mesh's size), e.g. in mesh {:?}; \
             {needs} needs a closed mesh",
            open.edges, open.tolerance, open.mesh
        ),
    ))
}

/// The open edges of a material's surface.
struct Open {
    /// Edges bounding an odd number of triangles.
    edges: usize,
    /// The name of a mesh with one.
    mesh: String,
    /// The weld tolerance used, world units.
    tolerance: f64,
}

/// The boundary edges of material `material`'s triangles, welded across its meshes;
/// `None` when they are closed.
fn open_edges(desc: &SceneDesc, material: usize) -> Option<Open> {
    let meshes: Vec<&MeshDesc> = desc
        .meshes
        .iter()
        .filter(|m| m.material == Some(material))
        .collect();
    open_edges_of(&meshes)
}

/// Whether `mesh`'s triangles alone form closed surfaces (module docs).
pub(super) fn mesh_is_closed(mesh: &MeshDesc) -> bool {
    open_edges_of(&[mesh]).is_none()
}

/// The boundary edges of the triangles of `meshes`, welded across them; `None` when they
/// are closed.
fn open_edges_of(meshes: &[&MeshDesc]) -> Option<Open> {
    let points: Vec<glam::Vec3> = meshes
        .iter()
        .flat_map(|m| m.positions.iter().copied())
        .collect();
    let welded = weld(&points);
    let mut edges: HashMap<(u32, u32), (u32, usize)> = HashMap::new();
    let mut base = 0usize;
    for (k, mesh) in meshes.iter().enumerate() {
        for t in &mesh.indices {
            let v = t.map(|i| welded.corner[base + i as usize]);
            for (a, b) in [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])] {
                // An edge welded to a point is no edge; the sliver's other two edges are
                // then one edge used twice, which leaves the parity unchanged.
                if a != b {
                    let e = edges.entry((a.min(b), a.max(b))).or_insert((0, k));
                    e.0 += 1;
                }
            }
        }
        base += mesh.positions.len();
    }
    let mut open: Vec<usize> = edges
        .values()
        .filter(|(n, _)| n % 2 == 1)
        .map(|&(_, k)| k)
        .collect();
    open.sort_unstable();
    let first = *open.first()?;
    Some(Open {
        edges: open.len(),
        mesh: meshes[first].name.clone(),
        tolerance: welded.tolerance,
    })
}
