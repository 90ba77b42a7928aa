//! What Iris adds to a file's description before the build, so that the built
//! [`crate::scene::Scene`] is never changed afterwards: lights for a file that
//! has none of its own ([`AddedLights`]). The other additions are plain fields of
//! [`super::SceneDesc`]: the environment light to render with and the bounds of the file's
//! own geometry when a floor is added.
//!
//! Units: candela (spot keys), lux (the key and fill); frames: world space, +Y up.
//! Invariant: loaders add nothing ([`AddedLights::None`]); [`crate::scene::lighting`] adds
//! the key and fill to a description with no light, and [`crate::studio`] the studio keys.

use glam::Vec3;

/// Lights Iris adds to a description whose file has no light, no emitter and no
/// environment.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum AddedLights {
    /// Nothing added: the file's own lights, emitters and environment light it.
    #[default]
    None,
    /// The directional key and fill lights of [`crate::light::default_lights`].
    KeyFill,
    /// A studio preset's spot key lights ([`crate::studio`]); its soft environment is the
    /// description's `environment_light`.
    Studio(Vec<SpotKey>),
}

/// A white spot light in render terms: built as it is, without the unit conversions of
/// [`super::LightDesc`] (the studio places it directly in candela and cone cosines).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotKey {
    /// World position.
    pub position: Vec3,
    /// Direction the light points to (towards the model's centre), unit length up to
    /// rounding.
    pub direction: Vec3,
    /// Luminous intensity on the axis, candela (white).
    pub intensity: f32,
    /// Cosine of the half-angle within which the light is at full intensity.
    pub cos_inner: f32,
    /// Cosine of the half-angle beyond which it is dark.
    pub cos_outer: f32,
}
