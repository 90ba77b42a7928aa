//! What the preparation decided for the user, as data ([`Note`]): the render notes of
//! `iris render` and `iris converge` are these values printed, so no code reads a note's
//! text to learn what was decided. The wording (the [`std::fmt::Display`] impl) is the
//! only place each note is written.

use crate::preview::AutoCamera;
use crate::studio::ground::Floor;
use crate::studio::Studio;
use std::fmt;

/// A decision taken for the user while preparing a scene, in the order
/// [`super::Prepared::notes`] lists them: lights, touching volumes, studio, floor, camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Note {
    /// Nothing lights the file: the default key and fill lights were added.
    KeyFill,
    /// This many triangles lie on another object's faces.
    Touching {
        /// Triangles marked [`crate::scene::TriangleData::TOUCHES`].
        triangles: usize,
    },
    /// Nothing lights the file: a studio preset lights it.
    Studio {
        /// The preset.
        preset: Studio,
        /// Its number of spot key lights.
        keys: usize,
    },
    /// Whether a floor was added, and why (never [`Floor::NotTransmissive`], which goes
    /// without saying).
    Floor(Floor),
    /// How Iris chose the camera.
    Camera(AutoCamera),
}

impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Note::KeyFill => {
                f.write_str("no light in the file: using the default key and fill lights")
            }
            Note::Touching { triangles } => write!(
                f,
                "{triangles} triangles lie on another object's faces (touching volumes are \
                 crossed as one interface there)"
            ),
            Note::Studio { preset, keys } => write!(
                f,
                "no light in the file: studio `{}` (soft environment and {keys} key light(s); \
                 --studio none for the plain key and fill)",
                preset.name()
            ),
            Note::Floor(floor) => f.write_str(floor_text(floor)),
            Note::Camera(AutoCamera::View {
                view,
                over_file_camera,
            }) => write!(
                f,
                "--view {}: framing the model automatically{}",
                view.name(),
                if over_file_camera {
                    " instead of the file's camera"
                } else {
                    ""
                }
            ),
            Note::Camera(AutoCamera::NoCamera) => f.write_str(
                "no camera in the file: framing the model from the front-right, 35° above \
                 (--view front|top|side|threequarter)",
            ),
        }
    }
}

/// The floor note's words.
fn floor_text(floor: Floor) -> &'static str {
    match floor {
        Floor::On => "--ground on: white floor under the model",
        Floor::Off => "--ground off: no floor added",
        Floor::NotTransmissive => "--ground auto: no transmissive material, no floor added",
        Floor::OwnSurface => {
            "--ground auto: the model stands on a surface of its own, no floor added"
        }
        Floor::UnderGlass => {
            "--ground auto: transmissive model with nothing under it: white floor added for \
             caustics (--ground off to remove)"
        }
        Floor::CoversBackground => {
            "--ground auto: no floor, since it would cover the --background (--ground on to \
             add it)"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::framing::View;

    #[test]
    fn notes_keep_their_words() {
        // The exact wording `iris render` printed before notes were data.
        assert_eq!(
            Note::KeyFill.to_string(),
            "no light in the file: using the default key and fill lights"
        );
        assert_eq!(
            Note::Studio {
                preset: Studio::Jeweller,
                keys: 2
            }
            .to_string(),
            "no light in the file: studio `jeweller` (soft environment and 2 key light(s); \
             --studio none for the plain key and fill)"
        );
        assert_eq!(
            Note::Touching { triangles: 12 }.to_string(),
            "12 triangles lie on another object's faces (touching volumes are crossed as one \
             interface there)"
        );
        assert_eq!(
            Note::Camera(AutoCamera::View {
                view: View::Top,
                over_file_camera: true
            })
            .to_string(),
            "--view top: framing the model automatically instead of the file's camera"
        );
        assert_eq!(
            Note::Floor(Floor::CoversBackground).to_string(),
            "--ground auto: no floor, since it would cover the --background (--ground on to add it)"
        );
    }
}
