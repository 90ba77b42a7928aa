//! The film's guards: what may enter an image, and when a render may stop early.
//!
//! - **Bad samples.** A sample whose linear RGB radiance has a NaN or infinite component
//!   (a numerical failure somewhere on its path) is not added to the image: it is counted
//!   ([`super::RenderStats::bad_samples`]) and replaced by zero, as pbrt-v4's film does
//!   (`RGBFilm::AddSample` drops non-finite values; Pharr, Jakob & Humphreys, "Physically
//!   Based Rendering", 4th ed., §5.4.2), so one failure costs one sample instead of painting
//!   a pixel. A component beyond the film's fixed-point range ([`LIMIT`],
//!   2⁴⁰ ≈ 1.1·10¹², far above any light Iris renders) is refused the same way. The CLI
//!   reports the count; the test suite asserts it is 0 on every asset. Negative components
//!   are legitimate (spectra outside the sRGB gamut) and pass.
//! - **Interruption.** [`request_stop`] is a process-wide stop request (SIGINT in the CLI):
//!   the per-sample methods finish the tiles already started and skip the rest of the
//!   round, SPPM ends after the current pass; the render returns the image so far with
//!   [`super::RenderStats::interrupted`] set. The first round (pass) always completes, so an
//!   interrupted render still has an image.
//! - **Cancellation.** A [`Cancel`] stops one render, not the process (the live view's
//!   restarts, [`crate::view`]): before each tile of any round, the first included, a
//!   cancelled render skips the rest; the tiles already started finish, so it ends within
//!   one tile per worker thread (per-sample methods; the hybrid's and SPPM's camera passes
//!   skip their remaining tiles too, after the pass's photons), or the pass in flight (VCM, BPT).
//!   Its image is incomplete and meant to be thrown away.

use crate::image::fixed::LIMIT;
use glam::DVec3;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The process-wide stop request.
static STOP: AtomicBool = AtomicBool::new(false);

/// Asks every running render to stop at its next safe point (async-signal-safe: one atomic
/// store).
pub fn request_stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// True once [`request_stop`] was called.
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// A stop request for one render, shared between the render and whoever may cancel it;
/// the default can never be cancelled.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Option<Arc<AtomicBool>>);

impl Cancel {
    /// A request that [`Cancel::cancel`] can set.
    pub fn new() -> Cancel {
        Cancel(Some(Arc::new(AtomicBool::new(false))))
    }

    /// Asks the render holding this request (or a clone) to stop before its next tile.
    pub fn cancel(&self) {
        if let Some(flag) = &self.0 {
            flag.store(true, Ordering::SeqCst);
        }
    }

    /// True once [`Cancel::cancel`] was called on this request or a clone of it.
    pub fn is_cancelled(&self) -> bool {
        self.0.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

/// `v` if all its components are finite and within ±[`LIMIT`], else zero
/// with `bad` incremented ([`super::FilmTile::add`] calls it for every value).
#[inline]
pub fn admit(v: DVec3, bad: &mut u64) -> DVec3 {
    // `max_element` skips NaN; `is_finite` catches it.
    if v.abs().max_element() <= LIMIT && v.is_finite() {
        v
    } else {
        *bad += 1;
        DVec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_samples_are_counted_and_zeroed() {
        let mut bad = 0;
        assert_eq!(
            admit(DVec3::new(1.0, -0.5, 2.0), &mut bad),
            DVec3::new(1.0, -0.5, 2.0)
        );
        assert_eq!(bad, 0);
        for v in [
            DVec3::new(f64::NAN, 0.0, 0.0),
            DVec3::new(0.0, f64::INFINITY, 0.0),
            DVec3::new(0.0, 0.0, f64::NEG_INFINITY),
        ] {
            assert_eq!(admit(v, &mut bad), DVec3::ZERO);
        }
        assert_eq!(bad, 3);
        // The film's largest value is a (very bright) sample, not a bad one; beyond it the
        // fixed-point sums could not hold it.
        let limit = LIMIT;
        assert_eq!(
            admit(DVec3::new(limit, -limit, 0.0), &mut bad),
            DVec3::new(limit, -limit, 0.0)
        );
        assert_eq!(bad, 3);
        assert_eq!(admit(DVec3::splat(f32::MAX as f64), &mut bad), DVec3::ZERO);
        assert_eq!(
            admit(DVec3::new(0.0, -2.0 * limit, 0.0), &mut bad),
            DVec3::ZERO
        );
        assert_eq!(bad, 5);
    }
}
