//! The kernel specialised to the scene ([`Class`]): what a scene asks of the bounce loop
//! beyond Lambert surfaces, smooth clear glass and punctual lights is fixed at compile time
//! per instantiation, so the loop for the simplest scenes ([`Plain`]) contains no emitter,
//! environment, absorption, glossy or hand-over code; any other scene takes [`Full`], which has all
//! of it and decides per lane. [`Tables::plain`] says which a scene needs.

use super::features::{Shade, Tables};
use crate::light::LightId;

/// The features of a scene class, as constants the bounce loop branches on.
pub trait Class {
    /// Lights with an area or at infinity (emissive triangles, an environment): the
    /// emission paths meet, weighted by MIS.
    const LIT_BY_AREA: bool;
    /// Absorbing glass: Beer–Lambert on the segments inside.
    const ABSORBS: bool;
    /// Materials the kernel does not shade: lanes meeting them hand over to the scalar
    /// vertex.
    const HANDS_OVER: bool;
    /// Lobes the scalar BSDF shades per lane ([`super::glossy`]): glTF BRDFs with a
    /// specular or metal part, rough glass.
    const GLOSSY: bool;
}

/// Lambert surfaces and smooth clear glass under punctual lights.
pub struct Plain;

impl Class for Plain {
    const LIT_BY_AREA: bool = false;
    const ABSORBS: bool = false;
    const HANDS_OVER: bool = false;
    const GLOSSY: bool = false;
}

/// Everything the kernel takes.
pub struct Full;

impl Class for Full {
    const LIT_BY_AREA: bool = true;
    const ABSORBS: bool = true;
    const HANDS_OVER: bool = true;
    const GLOSSY: bool = true;
}

impl Tables {
    /// Whether the scene is [`Plain`]: punctual lights only, no absorbing glass, no glossy
    /// material or rough glass, no material on the scalar vertex.
    pub fn plain(&self) -> bool {
        self.sampled
            .iter()
            .all(|l| matches!(l, LightId::Punctual(_)))
            && self.absorption.iter().all(|s| *s == [0.0; 3])
            && self.scalar.is_empty()
            && !self
                .shades
                .iter()
                .any(|s| matches!(s, Shade::Glossy | Shade::RoughGlass { .. }))
    }
}
