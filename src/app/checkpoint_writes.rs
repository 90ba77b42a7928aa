//! When `iris render` rewrites its output during a render: every `--checkpoint K` units, or
//! for an open budget ("watch", [`super::budget::Budget::open`]) at the driver's checkpoints,
//! throttled so that writing takes a small share of the render. Times are wall-clock.

use crate::render::Progress;
use std::time::{Duration, Instant};

/// While watching (an open budget), the output is rewritten at most this often.
pub const WATCH_INTERVAL: Duration = Duration::from_secs(2);

/// While watching, the time between two writes is also at least this many times the last
/// write's cost, so writing takes at most 1/20 of the render's time.
pub const WATCH_COST_FACTOR: u32 = 20;

/// When the output is rewritten during a render: every `--checkpoint K` units, or, for an
/// open budget ("watch"), at the driver's checkpoints with the first one written at once
/// and later ones at least [`WATCH_INTERVAL`] and [`WATCH_COST_FACTOR`] × the last write's
/// cost apart. Never at the end (`done`): the final image is written by the caller.
#[derive(Debug, Clone)]
pub struct CheckpointWrites {
    every: Option<u32>,
    watch: bool,
    last_units: u64,
    last_write: Option<(Instant, Duration)>,
}

impl CheckpointWrites {
    /// `--checkpoint K` (`every`), else watching when `watch`, else no writes before the end.
    pub fn new(every: Option<u32>, watch: bool) -> Self {
        CheckpointWrites {
            every,
            watch,
            last_units: 0,
            last_write: None,
        }
    }

    /// Whether to write the image of checkpoint `p` at time `now`.
    pub fn due(&self, p: &Progress, now: Instant) -> bool {
        if p.done {
            return false;
        }
        if let Some(k) = self.every {
            return p.samples >= self.last_units + u64::from(k);
        }
        self.watch
            && self.last_write.is_none_or(|(end, cost)| {
                now.saturating_duration_since(end) >= WATCH_INTERVAL.max(cost * WATCH_COST_FACTOR)
            })
    }

    /// Records a write of checkpoint `p` that took `cost` and ended at `end`.
    pub fn wrote(&mut self, p: &Progress, cost: Duration, end: Instant) {
        self.last_units = p.samples;
        self.last_write = Some((end, cost));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::ImageRgb;
    use glam::Vec3;

    fn progress(m: &ImageRgb, samples: u64, done: bool) -> Progress<'_> {
        Progress::at(m, (m, m), samples, done)
    }

    #[test]
    fn watching_writes_at_once_then_throttles() {
        let m = ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::ONE; 2],
        };
        let t0 = Instant::now();
        let mut w = CheckpointWrites::new(None, true);
        let p1 = progress(&m, 1, false);
        assert!(w.due(&p1, t0), "the first checkpoint is written at once");
        w.wrote(&p1, Duration::from_millis(10), t0);
        let p2 = progress(&m, 2, false);
        assert!(!w.due(&p2, t0 + Duration::from_millis(1999)));
        assert!(w.due(&p2, t0 + WATCH_INTERVAL));
        // A slow write (200 ms) spaces writes by 20 × 200 ms = 4 s.
        w.wrote(&p2, Duration::from_millis(200), t0);
        assert!(!w.due(&p2, t0 + Duration::from_millis(3999)));
        assert!(w.due(&p2, t0 + Duration::from_secs(4)));
        assert!(
            !w.due(&progress(&m, 4, true), t0 + Duration::from_secs(60)),
            "not at the end"
        );
        assert!(!CheckpointWrites::new(None, false).due(&p1, t0));
        // `--checkpoint 2`: every 2 units, whatever the time.
        let mut k = CheckpointWrites::new(Some(2), true);
        assert!(!k.due(&p1, t0));
        assert!(k.due(&p2, t0));
        k.wrote(&p2, Duration::from_secs(5), t0);
        assert!(!k.due(&progress(&m, 3, false), t0));
        assert!(k.due(&progress(&m, 4, false), t0));
    }
}
