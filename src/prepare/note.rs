//! What the preparation decided for the user, as data ([`Note`]): the render notes of
//! `iris render` and `iris converge` are these values printed, so no code reads a note's
//! text to learn what was decided. The wording (the [`std::fmt::Display`] impl) is the
//! only place each note is written.

use super::Authored;
use crate::prepare::camera_choice::AutoCamera;
use crate::studio::ground::Floor;
use crate::studio::Studio;
use std::fmt;

/// A decision taken for the user while preparing a scene, in the order
/// [`super::Prepared::notes`] lists them: lights, touching volumes, studio, floor, the
/// authored file's note, turntable, camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Note {
    /// Nothing lights the file: the default key and fill lights were added.
    KeyFill,
    /// This many triangles lie on another object's faces.
    Touching {
        /// Triangles marked [`crate::scene::Triangle::TOUCHES`].
        triangles: usize,
    },
    /// Nothing lights the file: a studio preset lights it.
    Studio {
        /// The preset.
        preset: Studio,
        /// Its number of spot key lights.
        keys: usize,
    },
    /// `--studio NAME` asked for a studio although the file brings its own light: the
    /// studio's keys were added to the file's lights and its environment replaces the
    /// file's.
    StudioAdded {
        /// The preset.
        preset: Studio,
        /// Its number of spot key lights.
        keys: usize,
    },
    /// Whether a floor was added, and why (never [`Floor::NotTransmissive`], which goes
    /// without saying, nor [`Floor::Authored`], which [`Note::Authored`] says).
    Floor(Floor),
    /// The file brings its own light: the drop-in additions the defaults would have made
    /// (the studio, and with `--ground auto` a floor) were left out.
    Authored {
        /// What light the file brings.
        evidence: Authored,
        /// Whether `--ground auto` left the floor out for this reason.
        no_floor: bool,
        /// Whether the default studio was left out (no `--studio NAME` given).
        no_studio: bool,
    },
    /// A turntable frame ([`super::turntable`]): the file's meshes that do not emit turned
    /// about the vertical axis.
    Turntable {
        /// The frame, from 0.
        frame: u32,
        /// Frames in the whole turn.
        frames: u32,
        /// Meshes turned.
        turned: usize,
        /// Emissive meshes left in place (lights stay).
        fixed: usize,
        /// Whether the automatic camera framed the turn's bounding cylinder.
        framed: bool,
    },
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
                "no light in the file: studio `{}` (studio environment and {keys} key light(s); \
                 --studio none for the plain key and fill)",
                preset.name()
            ),
            Note::StudioAdded { preset, keys } => write!(
                f,
                "--studio {}: studio environment and {keys} key light(s) added to the file's \
                 own lights",
                preset.name()
            ),
            Note::Floor(floor) => f.write_str(floor_text(floor)),
            Note::Authored {
                evidence,
                no_floor,
                no_studio,
            } => {
                let (what, flags) = match (no_studio, no_floor) {
                    (true, true) => ("no studio or floor", "--studio NAME, --ground on"),
                    (true, false) => ("no studio", "--studio NAME"),
                    (false, _) => ("no floor", "--ground on"),
                };
                write!(
                    f,
                    "the file brings its own light ({}): rendered as authored, {what} added \
                     ({flags} to add)",
                    evidence.evidence()
                )
            }
            Note::Turntable {
                frame,
                frames,
                turned,
                fixed,
                framed,
            } => {
                let degrees =
                    super::turntable::Spin::new(frame, frames).map_or(f64::NAN, |s| s.degrees());
                write!(
                    f,
                    "turntable frame {frame} of {frames} (0–{}): the model ({turned} mesh{}) turned {}° \
                     about the vertical axis through its centre; camera, lights, floor and \
                     studio fixed",
                    frames.saturating_sub(1),
                    if turned == 1 { "" } else { "es" },
                    format_degrees(degrees)
                )?;
                if fixed > 0 {
                    write!(f, "; {fixed} emissive mesh(es) stay with the lights")?;
                }
                if framed {
                    f.write_str("; framed on the bounding cylinder of the whole turn")?;
                }
                Ok(())
            }
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

/// `90`, `51.43`: whole degrees without decimals, others to two.
fn format_degrees(d: f64) -> String {
    if d.fract() == 0.0 {
        format!("{d:.0}")
    } else {
        format!("{d:.2}")
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
        Floor::Authored => {
            "--ground auto: the file brings its own light, no floor added (--ground on to add \
             one)"
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
            "no light in the file: studio `jeweller` (studio environment and 2 key light(s); \
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
            Note::Authored {
                evidence: Authored {
                    punctual: 2,
                    emissive: true,
                    environment: false
                },
                no_floor: true,
                no_studio: true
            }
            .to_string(),
            "the file brings its own light (2 punctual lights, emissive surfaces): rendered as \
             authored, no studio or floor added (--studio NAME, --ground on to add)"
        );
        assert_eq!(
            Note::Turntable {
                frame: 1,
                frames: 7,
                turned: 2,
                fixed: 1,
                framed: true
            }
            .to_string(),
            "turntable frame 1 of 7 (0–6): the model (2 meshes) turned 51.43° about the vertical \
             axis through its centre; camera, lights, floor and studio fixed; 1 emissive \
             mesh(es) stay with the lights; framed on the bounding cylinder of the whole turn"
        );
        assert_eq!(
            Note::Floor(Floor::CoversBackground).to_string(),
            "--ground auto: no floor, since it would cover the --background (--ground on to add it)"
        );
    }
}
