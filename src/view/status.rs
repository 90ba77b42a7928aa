//! What the live view's page says about a render, in an artist's words first: the method
//! and what it is for ([`Method::purpose`]), what the stone and metal choices changed, the time the
//! preview needs to come clean ([`time_to_clean`]); the render plan's stages with their
//! reasons (the developer's details, folded on the page) after.

use crate::app::RenderJob;
use serde_json::{json, Value};
use std::time::Duration;

/// The status of a preview that has started: the method, its purpose, what each look
/// changed, the notes, and the plan's stages (`plan`, the details).
pub fn rendering(job: &RenderJob, prepare_ms: u64) -> Value {
    let plan: Vec<Value> = job
        .plan
        .stages
        .iter()
        .map(|s| match s.name {
            // The live render refines every tile (crate::app::live).
            "adaptive" => json!({"name": s.name, "used": false,
                                 "reason": "off while viewing: every tile refines"}),
            _ => json!({"name": s.name, "used": s.used, "reason": s.reason}),
        })
        .collect();
    let notes: Vec<String> = job.prepared.notes().iter().map(|n| n.to_string()).collect();
    let looks: Vec<Value> = job
        .prepared
        .looks
        .iter()
        .map(|a| {
            json!({"flag": a.flag, "materials": a.materials, "meshes": a.meshes,
                        "text": a.to_string()})
        })
        .collect();
    let method = job.plan.method;
    json!({"state": "rendering", "method": method.name(), "purpose": method.purpose(),
           "spectral": job.plan.spectral, "plan": plan, "notes": notes, "looks": looks,
           "unit": crate::app::render_options::unit_name(method),
           "prepare_ms": prepare_ms})
}

/// The time the preview still needs to reach relative error `target`, from its estimate
/// `error` after `elapsed`: the error of a Monte Carlo render falls as 1/√time, so it
/// reaches `target` after `elapsed · (error / target)²`. `None` without an estimate;
/// zero once it is there.
pub fn time_to_clean(error: Option<f64>, elapsed: Duration, target: f64) -> Option<Duration> {
    let e = error.filter(|e| e.is_finite() && *e >= 0.0)?;
    if e <= target {
        return Some(Duration::ZERO);
    }
    let total = elapsed.as_secs_f64() * (e / target).powi(2);
    Duration::try_from_secs_f64(total - elapsed.as_secs_f64()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Method;

    #[test]
    fn the_time_to_clean_follows_one_over_the_square_root_of_time() {
        let t = Duration::from_secs(2);
        // Twice the target error: four times the time, so three times more.
        let left = time_to_clean(Some(0.01), t, 0.005).unwrap();
        assert!((left.as_secs_f64() - 6.0).abs() < 1e-9, "{left:?}");
        assert_eq!(time_to_clean(Some(0.004), t, 0.005), Some(Duration::ZERO));
        assert_eq!(time_to_clean(None, t, 0.005), None);
        assert_eq!(time_to_clean(Some(f64::NAN), t, 0.005), None);
    }

    #[test]
    fn every_method_says_what_it_is_for() {
        for m in Method::ALL {
            assert!(!m.purpose().is_empty());
        }
    }
}
