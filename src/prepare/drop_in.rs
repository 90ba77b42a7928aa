//! The drop-in preview's options ([`PreviewOptions`]: `--view`, `--studio`, `--ground`,
//! `--background`): what `iris render` does for a file that lacks a camera, lights or a
//! floor. [`crate::prepare::prepare`] applies them to the scene description (camera:
//! [`super::camera_choice`]).

use crate::framing::View;
use crate::output::Background;

/// `iris render` options for drop-in previews ([`crate::studio`], [`crate::framing`],
/// [`crate::output::background`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PreviewOptions {
    /// `--studio NAME`: `None` (not given) lights a file that has no light of its own with
    /// the default preset ([`crate::studio::Studio::Soft`]); `Some(preset)` also lights a
    /// file that has its own (added to its lights, [`crate::prepare`]). Either way only
    /// without `--env`.
    pub studio: Option<crate::studio::Studio>,
    /// Whether to add a white floor under the model.
    pub ground: crate::studio::GroundMode,
    /// `--view`: frame the model automatically from this view (else the file's first
    /// camera, or the three-quarter view when it has none).
    pub view: Option<View>,
    /// `--background`: what escaped camera rays show ([`crate::output::background`]).
    pub background: Background,
}

impl PreviewOptions {
    /// The floor rule in effect: `--ground auto` adds none when `--background` is not the
    /// environment (a floor filling the frame would hide the background asked for).
    pub fn ground_mode(&self) -> crate::studio::GroundMode {
        use crate::studio::GroundMode;
        match (self.ground, self.background) {
            (GroundMode::Auto, Background::Environment) => GroundMode::Auto,
            (GroundMode::Auto, _) => GroundMode::Off,
            (g, _) => g,
        }
    }
}
