//! `--denoise auto|on|off`: whether a render's outputs are denoised, decided from the flag,
//! the output format and whether the build has the denoiser, with the reason the plan
//! (`iris info`, `--explain`) prints.
//!
//! - `auto` (default): a PNG (a preview for eyes) is denoised; an EXR (numbers for tools)
//!   is left raw; a build without the `denoise` feature denoises nothing and says so.
//! - `on`: a PNG is denoised; an EXR keeps the raw image as its main `R`, `G`, `B` channels
//!   and adds the denoised image as the extra layer [`EXR_LAYER`] (channels `denoised.R`,
//!   `denoised.G`, `denoised.B`); without the feature it is a usage error.
//! - `off`: never.

use super::{available, UNAVAILABLE};
use crate::error::{parse_name, Error, Result};
use crate::plan::Stage;
use std::path::Path;

/// The EXR layer (channel-name prefix) holding the denoised image under `--denoise on`.
pub const EXR_LAYER: &str = "denoised";

/// `--denoise auto|on|off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DenoiseMode {
    /// Denoise PNG previews, leave EXR raw (when the build has the denoiser).
    #[default]
    Auto,
    /// Denoise the PNG, or add a denoised layer to the EXR; an error without the denoiser.
    On,
    /// Never denoise.
    Off,
}

impl DenoiseMode {
    /// Parses `--denoise auto|on|off` ([`parse_name`]).
    pub fn parse(s: &str) -> Result<DenoiseMode> {
        let names = [
            ("auto", DenoiseMode::Auto),
            ("on", DenoiseMode::On),
            ("off", DenoiseMode::Off),
        ];
        parse_name("--denoise", s, &names)
    }
}

/// What a render denoises, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DenoiseChoice {
    /// The written image is the denoised one (PNG).
    pub image: bool,
    /// The EXR gets the denoised image as the extra layer [`EXR_LAYER`].
    pub exr_layer: bool,
    /// One line for the plan: what is done and why.
    pub reason: String,
}

impl DenoiseChoice {
    /// Whether the denoiser runs at all (auxiliary pass included).
    pub fn runs(&self) -> bool {
        self.image || self.exr_layer
    }

    /// The plan's `denoise` stage.
    pub fn stage(&self) -> Stage {
        Stage {
            name: "denoise",
            used: self.runs(),
            reason: self.reason.clone(),
            cost: None,
        }
    }
}

/// Whether `output` is written as EXR (by extension, case-insensitive; anything else that
/// passed [`crate::output::check_extension`] is PNG).
fn is_exr(output: &Path) -> bool {
    output
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// The decision for `mode` and the output file; [`Error::Usage`] for `--denoise on` in a
/// build without the denoiser.
pub fn choose(mode: DenoiseMode, output: &Path) -> Result<DenoiseChoice> {
    choose_with(mode, output, available())
}

/// [`choose`] with the build's capability given (`has_denoiser`), for tests of both builds.
pub fn choose_with(mode: DenoiseMode, output: &Path, has_denoiser: bool) -> Result<DenoiseChoice> {
    let exr = is_exr(output);
    let how = "Open Image Denoise RT filter, HDR, before tone mapping, with albedo and normals \
               of the first non-specular surface seen through glass";
    let (image, exr_layer, reason) = match (mode, has_denoiser, exr) {
        (DenoiseMode::Off, ..) => (false, false, "raw image (--denoise off)".to_string()),
        (DenoiseMode::On, false, _) => {
            return Err(Error::Usage(format!("--denoise on: {UNAVAILABLE}")));
        }
        (DenoiseMode::Auto, false, _) => (
            false,
            false,
            "raw image: this build has no denoiser (cargo feature `denoise` off)".to_string(),
        ),
        (DenoiseMode::Auto, true, true) => (
            false,
            false,
            "raw image: EXR output is for numbers (--denoise on adds a denoised layer)".to_string(),
        ),
        (_, true, false) => (
            true,
            false,
            format!("PNG preview denoised: {how} (--denoise off for the raw image)"),
        ),
        (DenoiseMode::On, true, true) => (
            false,
            true,
            format!("EXR keeps the raw image and adds layer `{EXR_LAYER}` (--denoise on): {how}"),
        ),
    };
    Ok(DenoiseChoice {
        image,
        exr_layer,
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_decision_table() {
        let png = Path::new("a.png");
        let exr = Path::new("a.EXR");
        let c = |m, p, f| choose_with(m, p, f).unwrap();
        assert!(c(DenoiseMode::Auto, png, true).image);
        assert!(!c(DenoiseMode::Auto, exr, true).runs());
        assert!(c(DenoiseMode::Auto, exr, true).reason.contains("EXR"));
        assert!(!c(DenoiseMode::Auto, png, false).runs());
        assert!(c(DenoiseMode::Auto, png, false).reason.contains("feature"));
        let on_exr = c(DenoiseMode::On, exr, true);
        assert!(on_exr.exr_layer && !on_exr.image);
        assert!(c(DenoiseMode::On, png, true).image);
        assert!(!c(DenoiseMode::Off, png, true).runs());
        let e = choose_with(DenoiseMode::On, png, false)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--denoise on") && e.contains("--features denoise"),
            "{e}"
        );
        assert_eq!(DenoiseMode::parse(" ON ").unwrap(), DenoiseMode::On);
        assert!(DenoiseMode::parse("yes").is_err());
    }
}
