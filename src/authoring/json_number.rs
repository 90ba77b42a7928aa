//! Numbers in the generator's glTF JSON: each `f32` prints as the shortest decimal that
//! reads back as the same `f32`, so a file reads back exactly and is the same on every
//! platform.

use glam::Vec3;
use serde_json::Value;

/// A JSON number that prints as the shortest decimal reading back as the same `f32`.
pub(super) fn num(x: f32) -> Value {
    let short: f64 = format!("{x}").parse().unwrap_or(f64::from(x));
    // Double rounding (decimal → f64 → f32) could in principle differ; fall back if so.
    let v = if short as f32 == x {
        short
    } else {
        f64::from(x)
    };
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// A 3-vector as a JSON array of [`num`]s.
pub(super) fn vec3(v: Vec3) -> Value {
    Value::Array(v.to_array().map(num).to_vec())
}
