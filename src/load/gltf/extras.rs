//! Iris's own keys in an element's glTF `extras` (`iris_crystal`, `iris_polarizer`,
//! `iris_medium`, `iris_glass`, `cauchy`, `sellmeier`, `iris_priority`, `iris_spectrum`):
//! the one way they are read.
//!
//! The extras object is split into its keys without reading their values, and only the
//! key asked for is parsed. So another key's content (an exporter's custom property with a
//! number beyond f64, which JSON's grammar allows and serde_json refuses to read) cannot
//! hide Iris's keys, and an Iris key whose value cannot be read (`"optic_axis": [1e400,
//! 0, 0]`) is an `InvalidValue` error naming the file, the element and the key instead of
//! being dropped with the rest. Extras that are not a JSON object hold no Iris keys.

use super::Ctx;
use crate::error::{LoadError, LoadErrorKind};
use serde_json::value::RawValue;
use serde_json::Value;
use std::collections::HashMap;

/// The value of `key` in `extras`, or `None` when the extras are absent, not an object or
/// without the key; `element` names the element for the error (module docs).
pub(super) fn extras_key(
    ctx: &Ctx<'_>,
    extras: &gltf::json::Extras,
    element: &str,
    key: &str,
) -> Result<Option<Value>, LoadError> {
    let Some(raw) = extras else {
        return Ok(None);
    };
    let Ok(keys) = serde_json::from_str::<HashMap<String, Box<RawValue>>>(raw.get()) else {
        return Ok(None);
    };
    let Some(value) = keys.get(key) else {
        return Ok(None);
    };
    serde_json::from_str::<Value>(value.get())
        .map(Some)
        .map_err(|e| {
            let text: String = value.get().chars().take(80).collect();
            ctx.error(
                element,
                LoadErrorKind::InvalidValue,
                format!("extras.{key} cannot be read ({e}): {text}"),
            )
        })
}
