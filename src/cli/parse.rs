//! Value parsers of the command line: each checks its documented bound and says, in its
//! error, the flag's rule (clap prefixes the flag and the value).

use crate::output::Exposure;

pub(crate) fn parse_unit(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a value from 0 to 1, got {s:?}")),
    }
}

pub(crate) fn parse_shard(s: &str) -> Result<crate::app::shard::Shard, String> {
    crate::app::shard::Shard::parse(s).map_err(|e| e.to_string())
}

pub(crate) fn parse_target(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "expected a relative error > 0, e.g. 0.05, got {s:?}"
        )),
    }
}

/// Largest `--time`, seconds (about 116 days).
pub(crate) const MAX_SECONDS: f64 = 1e7;

pub(crate) fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= MAX_SECONDS => Ok(v),
        _ => Err(format!(
            "expected seconds > 0 and at most {MAX_SECONDS}, got {s:?}"
        )),
    }
}

/// `--threads`: 0 to [`crate::render::MAX_THREADS`], checked before any thread is spawned.
pub(crate) fn parse_threads() -> clap::builder::RangedU64ValueParser<usize> {
    clap::builder::RangedU64ValueParser::new().range(0..=crate::render::MAX_THREADS as u64)
}

/// `gem --size`: millimetres in [0.1, 1000] ([`crate::authoring::cuts::size_metres`]).
pub(crate) fn parse_gem_size(s: &str) -> Result<f64, String> {
    use crate::authoring::cuts::{size_metres, MAX_SIZE_MM, MIN_SIZE_MM};
    match s.parse::<f64>() {
        Ok(v) if size_metres(v).is_ok() => Ok(v),
        _ => Err(format!(
            "expected millimetres from {MIN_SIZE_MM} to {MAX_SIZE_MM}, got {s:?}"
        )),
    }
}

pub(crate) fn parse_radius(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a finite radius > 0, got {s:?}")),
    }
}

pub(crate) fn parse_alpha(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err(format!("expected α strictly between 0 and 1, got {s:?}")),
    }
}

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH, e.g. 800x600, got {s:?}"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in {s:?}"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in {s:?}"))?;
    crate::app::check_size(w, h).map_err(|e| e.to_string())?;
    Ok((w, h))
}

pub(crate) fn parse_exposure(s: &str) -> Result<Exposure, String> {
    if s.eq_ignore_ascii_case("auto") {
        return Ok(Exposure::Auto);
    }
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v.abs() <= 64.0 => Ok(Exposure::Ev(v)),
        _ => Err(format!("expected `auto` or stops in [-64, 64], got {s:?}")),
    }
}

pub(crate) fn parse_look_at(s: &str) -> Result<crate::prepare::look_at::LookAt, String> {
    crate::prepare::look_at::LookAt::parse(s)
}

/// `--turn F/N`: frame F of a turn of N frames, 0 ≤ F < N.
pub(crate) fn parse_turn(s: &str) -> Result<crate::prepare::turntable::Spin, String> {
    let bad = || {
        format!(
            "expected F/N with 0 ≤ F < N ≤ {}, e.g. 90/360, got {s:?}",
            crate::prepare::turntable::MAX_FRAMES
        )
    };
    let (f, n) = s.split_once('/').ok_or_else(bad)?;
    let (f, n) = (
        f.trim().parse::<u32>().map_err(|_| bad())?,
        n.trim().parse::<u32>().map_err(|_| bad())?,
    );
    if f >= n {
        return Err(bad());
    }
    crate::prepare::turntable::Spin::new(f, n).map_err(|_| bad())
}

/// `--polarizer ANGLE`: degrees, finite, within ±360.
pub(crate) fn parse_polarizer(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(a) if a.is_finite() && a.abs() <= 360.0 => Ok(a),
        _ => Err(format!(
            "{s:?} is not an angle in degrees from -360 to 360 (e.g. 0 or 90)"
        )),
    }
}
