//! `--adaptive auto|on|off`: whether a render lets converged tiles rest
//! ([`crate::render::adaptive`]), decided from the flag, the budget, `--shard` and the
//! method, with the reason the plan prints (`--explain`).
//!
//! - `auto` (default): on when the time limit or the error target ends the render (no
//!   `--spp` or `--passes`: a preview), off for a fixed count, which asks for that many
//!   units in every pixel.
//! - `on`: on whatever the budget; a usage error with `--shard`.
//! - `off`: never.
//!
//! Never for SPPM (every visible point takes part in every pass) or a shard (shards take the
//! same units in every pixel, so their partial images add up to one render bit for bit;
//! the per-tile counts of adaptive sampling come from the whole image, which a shard does
//! not see).

use crate::error::{parse_name, Error, Result};
use crate::integrator::Method;
use crate::plan::Stage;
use crate::render::Adaptive;

/// `--adaptive auto|on|off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AdaptiveMode {
    /// On for an open budget (time or error target), off for a fixed count.
    #[default]
    Auto,
    /// Always (not with `--shard`).
    On,
    /// Never.
    Off,
}

impl AdaptiveMode {
    /// Parses `--adaptive auto|on|off` ([`parse_name`]).
    pub fn parse(s: &str) -> Result<AdaptiveMode> {
        let names = [
            ("auto", AdaptiveMode::Auto),
            ("on", AdaptiveMode::On),
            ("off", AdaptiveMode::Off),
        ];
        parse_name("--adaptive", s, &names)
    }
}

/// What a render samples adaptively, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveChoice {
    /// The settings' adaptive sampling (`None`: every tile takes every unit).
    pub adaptive: Option<Adaptive>,
    /// One line for the plan.
    pub reason: String,
}

/// The render's flags that decide adaptive sampling.
#[derive(Debug, Clone, Copy)]
pub struct AdaptiveFlags {
    /// `--adaptive`.
    pub mode: AdaptiveMode,
    /// No `--spp` or `--passes`: the time limit or the error target ends the render.
    pub open: bool,
    /// The error target, if one stops the render.
    pub target: Option<f64>,
    /// `--shard` was given.
    pub shard: bool,
    /// The scene has scattering media ([`crate::scene::Scene::has_media`]).
    pub media: bool,
}

/// The choice for `flags` and the resolved `method`; a usage error for `--adaptive on` with
/// `--shard`.
pub fn choose(flags: AdaptiveFlags, method: Method) -> Result<AdaptiveChoice> {
    if flags.mode == AdaptiveMode::On && flags.shard {
        return Err(Error::Usage(
            "--adaptive on with --shard: shards take the same samples in every pixel so \
             that `iris merge` adds them up to one render bit for bit, and adaptive \
             sampling chooses per-tile counts from the whole image, which a shard does not \
             see (use --adaptive auto or off)"
                .into(),
        ));
    }
    let off = |reason: &str| AdaptiveChoice {
        adaptive: None,
        reason: reason.to_string(),
    };
    if flags.mode == AdaptiveMode::Off {
        return Ok(off("off (--adaptive off): every pixel takes every sample"));
    }
    let caps = method.caps();
    if let Some(why) = caps.adaptive.why_not() {
        return Ok(off(&format!("off for --method {}: {why}", caps.name)));
    }
    if flags.shard {
        return Ok(off(
            "off in a shard: shards take the same samples in every pixel, so they merge \
             into one render bit for bit",
        ));
    }
    if let (AdaptiveMode::Auto, true, Some(why)) =
        (flags.mode, flags.media, caps.estimate_in_media.why_not())
    {
        return Ok(off(&format!(
            "off for --method {} with scattering media: {why}, so tiles would rest too soon \
             (--adaptive on to let them)",
            caps.name
        )));
    }
    if flags.mode == AdaptiveMode::Auto && !flags.open {
        return Ok(off(
            "off for a fixed count (--spp/--passes: that many samples in every pixel; \
             --adaptive on to let converged tiles rest)",
        ));
    }
    let threshold = flags.target.map_or(String::new(), |t| {
        format!(
            ", or once its estimated error is below half the target ({:.4})",
            t / 2.0
        )
    });
    Ok(AdaptiveChoice {
        adaptive: Some(Adaptive {
            target: flags.target,
        }),
        reason: format!(
            "on: from {} samples per pixel, a 16×16 tile rests while it is ahead of its \
             share of the samples by Neyman's allocation (√(variance/cost) against the 90th \
             percentile tile's), never below a quarter of the image's samples{threshold}",
            crate::render::adaptive::MIN_UNITS
        ),
    })
}

impl AdaptiveChoice {
    /// The plan's `adaptive` stage.
    pub fn stage(&self) -> Stage {
        Stage {
            name: "adaptive",
            used: self.adaptive.is_some(),
            reason: self.reason.clone(),
            cost: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flags(mode: AdaptiveMode, open: bool, shard: bool) -> AdaptiveFlags {
        AdaptiveFlags {
            mode,
            open,
            target: Some(0.03),
            shard,
            media: false,
        }
    }

    #[test]
    fn auto_is_on_for_open_budgets_only() {
        let on = choose(flags(AdaptiveMode::Auto, true, false), Method::Path).unwrap();
        assert_eq!(on.adaptive, Some(Adaptive { target: Some(0.03) }));
        assert!(on.reason.contains("0.0150"), "{}", on.reason);
        let fixed = choose(flags(AdaptiveMode::Auto, false, false), Method::Hybrid).unwrap();
        assert_eq!(fixed.adaptive, None);
        let forced = choose(flags(AdaptiveMode::On, false, false), Method::Hybrid).unwrap();
        assert!(forced.adaptive.is_some());
    }

    #[test]
    fn never_for_sppm_shards_or_off() {
        for (mode, method, shard) in [
            (AdaptiveMode::Auto, Method::Sppm, false),
            (AdaptiveMode::On, Method::Sppm, false),
            (AdaptiveMode::Auto, Method::Path, true),
            (AdaptiveMode::Off, Method::Path, false),
        ] {
            let c = choose(flags(mode, true, shard), method).unwrap();
            assert_eq!(c.adaptive, None, "{mode:?} {method:?} {shard}");
            assert!(!c.stage().used);
        }
        let err = choose(flags(AdaptiveMode::On, true, true), Method::Path).unwrap_err();
        assert!(err.to_string().contains("--shard"), "{err}");
        assert!(AdaptiveMode::parse("sometimes").is_err());
        assert_eq!(AdaptiveMode::parse("on").unwrap(), AdaptiveMode::On);
    }

    /// Adaptive sampling is on exactly for the methods whose declaration says so, and off
    /// with the declared reason otherwise; in media under `auto`, the same for the error
    /// estimate's declaration.
    #[test]
    fn the_declarations_decide() {
        for m in Method::ALL {
            let caps = m.caps();
            let c = choose(flags(AdaptiveMode::On, true, false), m).unwrap();
            assert_eq!(
                c.adaptive.is_some(),
                caps.adaptive.is_yes(),
                "{}",
                caps.name
            );
            if let Some(why) = caps.adaptive.why_not() {
                assert!(c.reason.contains(why), "{}", c.reason);
            }
            let media = AdaptiveFlags {
                media: true,
                ..flags(AdaptiveMode::Auto, true, false)
            };
            let c = choose(media, m).unwrap();
            let expected = caps.adaptive.is_yes() && caps.estimate_in_media.is_yes();
            assert_eq!(
                c.adaptive.is_some(),
                expected,
                "{}: {}",
                caps.name,
                c.reason
            );
        }
    }
}
