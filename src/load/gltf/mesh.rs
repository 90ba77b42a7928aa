//! Mesh primitives (glTF 2.0 §3.7.2): read once in mesh-local space, then instanced into
//! world space per node.
//!
//! - Modes: TRIANGLES; TRIANGLE_STRIP and TRIANGLE_FAN are converted with the spec's
//!   formulas (§3.7.2.1); POINTS and LINE* are skipped (reported by the caller).
//! - Attributes read: POSITION (required to render), NORMAL, TEXCOORD_0, TANGENT (only with
//!   NORMAL, as the spec requires; non-finite components are an error, w keeps only its
//!   sign ±1); missing indices mean `0..count`. Every index is checked against the vertex
//!   count here.
//! - Tangents transform with `M` (they are surface directions); the bitangent sign w is
//!   recomputed so that w·(n′ × t′) still points along `M·(w·(n × t))` (a mirroring
//!   transform flips it).
//! - KHR_draco_mesh_compression: the attributes the extension lists and the indices come
//!   from the decoded Draco mesh ([`super::draco`]); the others are read as usual.
//! - World transform `M`: positions `M·p`; normals by the inverse transpose of the upper
//!   3×3, `M⁻ᵀ = cof(M)/det(M)`, computed as `sign(det)·cof(M)` and normalised so a
//!   singular matrix cannot produce infinities. When `det(M) < 0` each triangle's last two
//!   indices are swapped, keeping counter-clockwise winding seen from outside.

use super::accessor::{read_floats, read_indices, AccessorError};
use super::draco::{read_draco, DracoPrimitive};
use super::Ctx;
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::MeshDesc;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use gltf::mesh::Mode;
use gltf::Semantic;
use std::borrow::Cow;

/// A triangle primitive in mesh-local space, shared by all nodes that instance it.
#[derive(Debug)]
pub(super) struct LocalPrimitive {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    /// TEXCOORD_1, or empty.
    uvs1: Vec<Vec2>,
    tangents: Vec<Vec4>,
    triangles: Vec<[u32; 3]>,
    material: Option<usize>,
    /// Draco only: `(decoded, declared)` point counts when the decoder made more points.
    pub(super) extra_points: Option<(usize, usize)>,
}

impl LocalPrimitive {
    /// Number of triangles.
    pub(super) fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    pub(super) fn vertex_count(&self) -> usize {
        self.positions.len()
    }
}

/// What reading a primitive gave.
#[derive(Debug)]
pub(super) enum Primitive {
    /// Triangles ready to instance.
    Triangles(LocalPrimitive),
    /// A point or line primitive, with the mode's glTF name.
    Skipped(&'static str),
    /// No POSITION attribute: nothing to render.
    NoPosition,
}

/// Reads `prim`; `element` names it in errors (`node 3 "Gem" mesh 1 "Cut" primitive 0`).
pub(super) fn read_primitive(
    ctx: &Ctx<'_>,
    prim: &gltf::Primitive<'_>,
    element: &str,
) -> Result<Primitive, LoadError> {
    let mode = prim.mode();
    if let Some(name) = skipped_mode(mode) {
        return Ok(Primitive::Skipped(name));
    }
    let Some(position_acc) = prim.get(&Semantic::Positions) else {
        return Ok(Primitive::NoPosition);
    };
    let draco = read_draco(ctx, prim, element)?;
    let reader = AttributeReader {
        ctx,
        prim,
        element,
        draco: draco.as_ref(),
    };
    let positions: Vec<Vec3> = reader
        .values::<3>("POSITION", Some(position_acc))?
        .into_iter()
        .map(Vec3::from)
        .collect();
    let n = positions.len();
    let vertex_count = u32::try_from(n).map_err(|_| {
        ctx.error(
            element,
            LoadErrorKind::TooLarge,
            format!("{n} vertices exceed 32-bit indices"),
        )
    })?;
    let normals: Vec<Vec3> = reader
        .per_vertex::<3>("NORMAL", Semantic::Normals, n)?
        .into_iter()
        .map(Vec3::from)
        .collect();
    let uv_set = |set: u32| -> Result<Vec<Vec2>, LoadError> {
        let name = format!("TEXCOORD_{set}");
        Ok(reader
            .per_vertex::<2>(&name, Semantic::TexCoords(set), n)?
            .into_iter()
            .map(Vec2::from)
            .collect())
    };
    let uvs = uv_set(0)?;
    let uvs1 = uv_set(1)?;
    // The spec: without normals, provided tangents must be ignored.
    let tangents = if normals.is_empty() {
        Vec::new()
    } else {
        reader.tangents(n)?
    };
    let extra_points = draco.as_ref().and_then(|d| d.extra_points);
    let indices = reader.indices(vertex_count)?;
    Ok(Primitive::Triangles(LocalPrimitive {
        positions,
        normals,
        uvs,
        uvs1,
        tangents,
        triangles: assemble(mode, &indices),
        material: prim.material().index(),
        extra_points,
    }))
}

/// The glTF name of a point or line mode (read as nothing), `None` for triangle modes.
fn skipped_mode(mode: Mode) -> Option<&'static str> {
    match mode {
        Mode::Points => Some("POINTS"),
        Mode::Lines => Some("LINES"),
        Mode::LineLoop => Some("LINE_LOOP"),
        Mode::LineStrip => Some("LINE_STRIP"),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
    }
}

/// Reads one primitive's vertex attributes and indices, from the decoded Draco mesh where
/// it holds them and from the accessors otherwise; errors name `element`.
struct AttributeReader<'r, 'a> {
    ctx: &'r Ctx<'a>,
    prim: &'r gltf::Primitive<'a>,
    element: &'r str,
    draco: Option<&'r DracoPrimitive>,
}

impl<'r> AttributeReader<'r, '_> {
    /// An accessor error, prefixed with the attribute's name.
    fn wrap(&self, what: &str, e: AccessorError) -> LoadError {
        self.ctx
            .error(self.element, e.kind, format!("{what}: {}", e.detail))
    }

    /// The values of attribute `name`: the Draco mesh's if it holds them, else those of
    /// `acc`, else none.
    fn values<const N: usize>(
        &self,
        name: &str,
        acc: Option<gltf::Accessor<'_>>,
    ) -> Result<Vec<[f32; N]>, LoadError> {
        match (acc, self.draco.and_then(|d| d.get::<N>(name))) {
            (_, Some(values)) => Ok(values),
            (Some(acc), None) => read_floats::<N>(self.ctx, &acc).map_err(|e| self.wrap(name, e)),
            (None, None) => Ok(Vec::new()),
        }
    }

    /// An optional per-vertex attribute: none, or exactly one value per position (`n`).
    fn per_vertex<const N: usize>(
        &self,
        name: &str,
        semantic: Semantic,
        n: usize,
    ) -> Result<Vec<[f32; N]>, LoadError> {
        let values = self.values::<N>(name, self.prim.get(&semantic))?;
        if !values.is_empty() {
            self.same_length(name, values.len(), n)?;
        }
        Ok(values)
    }

    fn same_length(&self, what: &str, len: usize, n: usize) -> Result<(), LoadError> {
        if len == n {
            Ok(())
        } else {
            Err(self.ctx.error(
                self.element,
                LoadErrorKind::Parse,
                format!("{what} has {len} elements but POSITION has {n}"),
            ))
        }
    }

    /// TANGENT (from its accessor only): one per position, finite, w reduced to its sign ±1.
    fn tangents(&self, n: usize) -> Result<Vec<Vec4>, LoadError> {
        let Some(acc) = self.prim.get(&Semantic::Tangents) else {
            return Ok(Vec::new());
        };
        let tangents: Vec<Vec4> = read_floats::<4>(self.ctx, &acc)
            .map_err(|e| self.wrap("TANGENT", e))?
            .into_iter()
            .map(Vec4::from)
            .collect();
        if !tangents.is_empty() {
            self.same_length("TANGENT", tangents.len(), n)?;
            if let Some((i, t)) = tangents.iter().enumerate().find(|(_, t)| !t.is_finite()) {
                return Err(self.ctx.error(
                    self.element,
                    LoadErrorKind::InvalidValue,
                    format!("TANGENT {i} = {t} is not finite"),
                ));
            }
        }
        Ok(tangents
            .into_iter()
            .map(|t| t.truncate().extend(if t.w < 0.0 { -1.0 } else { 1.0 }))
            .collect())
    }

    /// The index list: Draco's decoded indices, the indices accessor, or `0..vertex_count`;
    /// every index below `vertex_count`.
    fn indices(&self, vertex_count: u32) -> Result<Cow<'r, [u32]>, LoadError> {
        let indices = match (self.prim.indices(), self.draco) {
            (_, Some(d)) => Cow::Borrowed(d.indices.as_slice()),
            (Some(acc), None) => {
                Cow::Owned(read_indices(self.ctx, &acc).map_err(|e| self.wrap("indices", e))?)
            }
            (None, None) => Cow::Owned((0..vertex_count).collect()),
        };
        if let Some((i, &bad)) = indices.iter().enumerate().find(|(_, &v)| v >= vertex_count) {
            return Err(self.ctx.error(
                self.element,
                LoadErrorKind::IndexOutOfRange,
                format!(
                    "index {bad} (position {i} in the index list) is not below the vertex count {vertex_count}"
                ),
            ));
        }
        Ok(indices)
    }
}

/// Triangles from an index list (§3.7.2.1). Strips/fans drop degenerate joins.
fn assemble(mode: Mode, idx: &[u32]) -> Vec<[u32; 3]> {
    let at = |i: usize| idx.get(i).copied().unwrap_or(0);
    let n = idx.len();
    match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            // p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}
            .map(|i| [at(i), at(i + 1 + i % 2), at(i + 2 - i % 2)])
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
        Mode::TriangleFan => (0..n.saturating_sub(2))
            // p_i = {v_{i+1}, v_{i+2}, v_0}
            .map(|i| [at(i + 1), at(i + 2), at(0)])
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
        // TRIANGLES: trailing indices that do not make a whole triangle are ignored.
        _ => idx
            .chunks_exact(3)
            .filter_map(|c| <[u32; 3]>::try_from(c).ok())
            .collect(),
    }
}

/// The world-space instance of `local` under `world`.
pub(super) fn instantiate(local: &LocalPrimitive, world: &Mat4, name: String) -> MeshDesc {
    let linear = Mat3::from_mat4(*world);
    let det = linear.determinant();
    let normal_matrix = if det < 0.0 {
        -cofactor(&linear)
    } else {
        cofactor(&linear)
    };
    let positions = local
        .positions
        .iter()
        .map(|&p| world.transform_point3(p))
        .collect();
    let normals: Vec<Vec3> = local
        .normals
        .iter()
        .map(|&n| {
            let t = normal_matrix * n;
            let len = t.length();
            if len > 0.0 && len.is_finite() {
                t / len
            } else {
                t
            }
        })
        .collect();
    let tangents = local
        .tangents
        .iter()
        .zip(&local.normals)
        .zip(&normals)
        .map(|((&t, &n), &n_world)| {
            let t3 = t.truncate();
            let b_world = linear * (n.cross(t3) * t.w);
            let t_world = linear * t3;
            let w = if n_world.cross(t_world).dot(b_world) < 0.0 {
                -1.0
            } else {
                1.0
            };
            t_world.normalize_or_zero().extend(w)
        })
        .collect();
    let indices = if det < 0.0 {
        local.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect()
    } else {
        local.triangles.clone()
    };
    MeshDesc {
        name,
        positions,
        normals,
        uvs: local.uvs.clone(),
        uvs1: local.uvs1.clone(),
        tangents,
        indices,
        material: local.material,
        orientation: linear,
    }
}

/// Cofactor matrix `det(M)·M⁻ᵀ`: columns `(b×c, c×a, a×b)` for `M = [a b c]`.
fn cofactor(m: &Mat3) -> Mat3 {
    Mat3::from_cols(
        m.y_axis.cross(m.z_axis),
        m.z_axis.cross(m.x_axis),
        m.x_axis.cross(m.y_axis),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_and_fan_follow_the_spec() {
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 3]),
            vec![[0, 1, 2], [1, 3, 2]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(assemble(Mode::Triangles, &[0, 1, 2, 3]), vec![[0, 1, 2]]);
        assert!(assemble(Mode::TriangleStrip, &[0, 1]).is_empty());
    }

    #[test]
    fn cofactor_is_scaled_inverse_transpose() {
        let m = Mat3::from_cols_array(&[2.0, 0.0, 1.0, 0.5, 3.0, 0.0, 0.0, 1.0, -1.0]);
        let expected = m.inverse().transpose() * m.determinant();
        assert!(cofactor(&m).abs_diff_eq(expected, 1e-5));
    }

    #[test]
    fn mirrored_instance_flips_winding_and_normals() {
        let local = LocalPrimitive {
            positions: vec![Vec3::X, Vec3::Y, Vec3::Z],
            normals: vec![Vec3::ONE; 3],
            uvs: Vec::new(),
            uvs1: Vec::new(),
            tangents: Vec::new(),
            triangles: vec![[0, 1, 2]],
            material: None,
            extra_points: None,
        };
        let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        let mesh = instantiate(&local, &mirror, "m".into());
        assert_eq!(mesh.indices, vec![[0, 2, 1]]);
        assert!(mesh.normals[0].abs_diff_eq(Vec3::new(-1.0, 1.0, 1.0).normalize(), 1e-6));
    }
}
