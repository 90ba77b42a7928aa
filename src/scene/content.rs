//! The render scene's content as a byte stream ([`Scene::write_content`]), the part of a
//! render's identity that says which scene was rendered (`iris merge` compares its hash,
//! [`crate::app::shard_id`]).
//!
//! Every field of [`Scene`] is either written or named as derived or as not affecting the
//! image, in one exhaustive destructuring: a field added to `Scene` does not compile here
//! until it is classified. Geometry goes in as little-endian bits; materials, images,
//! lights, the environment, the fog and the cameras as their `Debug` text, which holds
//! every value (no hash maps are involved, so the text is deterministic for a given build).

use super::Scene;
use std::fmt::Write as _;

/// A `fmt::Write` adaptor that hands the text to a byte sink without building it.
struct Sink<'a>(&'a mut dyn FnMut(&[u8]));

impl std::fmt::Write for Sink<'_> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        (self.0)(s.as_bytes());
        Ok(())
    }
}

impl Scene {
    /// Writes what the scene renders to `out` (see the module docs): the same bytes for
    /// scenes that render the same image with the same Iris build.
    pub fn write_content(&self, out: &mut dyn FnMut(&[u8])) {
        let Scene {
            // The file's bytes are a separate identity entry (`scene_sha256`).
            source: _,
            vertices,
            triangles,
            // Names and counts for messages.
            meshes: _,
            materials,
            images,
            // A count for the notes; the images used are in `images`.
            skipped_textures: _,
            lights,
            // Derived from the triangles and materials.
            area_lights: _,
            environment,
            fog,
            // Derived from the materials and the fog.
            has_media: _,
            // Derived from the lights.
            light_sampler: _,
            // Lights the preparation added are in `lights` and the materials.
            default_lights: _,
            cameras,
            // Derived from the positions.
            bounds: _,
            subject_bounds: _,
            // Messages.
            warnings: _,
            // Derived from the geometry (the contact probe).
            touching_triangles: _,
            has_cutouts: _,
            // The backend is its own identity entry (`accel`); the time is a measurement.
            accel_build_time: _,
            accel: _,
        } = self;
        let mut bytes = Vec::new();
        let floats = |values: &[f32], bytes: &mut Vec<u8>| {
            bytes.extend(values.iter().flat_map(|c| c.to_bits().to_le_bytes()));
        };
        for p in vertices.positions.iter().chain(&vertices.normals) {
            floats(&p.to_array(), &mut bytes);
        }
        for uv in vertices.uvs.iter().chain(&vertices.uvs1) {
            floats(&uv.to_array(), &mut bytes);
        }
        for t in &vertices.tangents {
            floats(&t.to_array(), &mut bytes);
        }
        for t in triangles {
            let m = t.material();
            bytes.extend(t.vertices.iter().chain([&m]).flat_map(|i| i.to_le_bytes()));
        }
        out(&bytes);
        let _ = write!(
            Sink(out),
            "{materials:?}{images:?}{lights:?}{environment:?}{fog:?}{cameras:?}"
        );
    }
}
