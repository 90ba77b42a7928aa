//! Between Iris's values and Python's: images as `numpy.ndarray`s (float32, height ×
//! width × 3, linear RGB), and the plan, summary and file description as dicts.

use crate::progress::Outcome;
use iris::image::ImageRgb;
use iris::scene::desc::{LightDesc, SceneDesc};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

/// An image as a float32 H×W×3 array.
pub fn array<'py>(py: Python<'py>, image: &ImageRgb) -> PyResult<Bound<'py, PyAny>> {
    let mut bytes = Vec::with_capacity(image.data.len() * 12);
    for p in &image.data {
        for c in p.to_array() {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    let shape = (image.height as usize, image.width as usize, 3usize);
    bytes_array(py, &bytes, "<f4", shape)
}

/// Little-endian `bytes` of `dtype` as an array of `shape` (a writable copy).
pub fn bytes_array<'py>(
    py: Python<'py>,
    bytes: &[u8],
    dtype: &str,
    shape: (usize, usize, usize),
) -> PyResult<Bound<'py, PyAny>> {
    let numpy = py.import("numpy")?;
    let flat = numpy.call_method1("frombuffer", (PyBytes::new(py, bytes), dtype))?;
    // A copy: the buffer's array is read-only.
    flat.call_method1("reshape", (shape,))?.call_method0("copy")
}

/// An array-like of height × width × 3 numbers (any dtype numpy converts to float32) as
/// a linear image; `ValueError` for another shape.
pub fn image(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<ImageRgb> {
    let numpy = py.import("numpy")?;
    let a = numpy.call_method1("ascontiguousarray", (value, "<f4"))?;
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    let (h, w) = match shape[..] {
        [h, w, 3] if h > 0 && w > 0 => (h, w),
        _ => {
            return Err(PyValueError::new_err(format!(
                "expected an image of height × width × 3 values, got shape {shape:?}"
            )))
        }
    };
    let (Ok(width), Ok(height)) = (u32::try_from(w), u32::try_from(h)) else {
        return Err(PyValueError::new_err("image too large"));
    };
    let bytes: Vec<u8> = a.call_method0("tobytes")?.extract()?;
    let mut img = ImageRgb::new(width, height);
    for (px, rgb) in img.data.iter_mut().zip(bytes.chunks_exact(12)) {
        let c = |i: usize| f32::from_le_bytes([rgb[i], rgb[i + 1], rgb[i + 2], rgb[i + 3]]);
        *px = glam::Vec3::new(c(0), c(4), c(8));
    }
    Ok(img)
}

/// The plan's stages as dicts.
pub fn stages<'py>(py: Python<'py>, plan: &iris::plan::Plan) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for s in &plan.stages {
        let d = PyDict::new(py);
        d.set_item("name", s.name)?;
        d.set_item("used", s.used)?;
        d.set_item("reason", &s.reason)?;
        list.append(d)?;
    }
    Ok(list)
}

/// A render job's plan as `plan()` returns it.
pub fn plan_dict<'py>(py: Python<'py>, job: &iris::app::RenderJob) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("method", job.plan.method.name())?;
    d.set_item("spectral", job.plan.spectral)?;
    d.set_item("size", job.prepared.size)?;
    d.set_item("stages", stages(py, &job.plan)?)?;
    let notes: Vec<String> = job.prepared.notes().iter().map(|n| n.to_string()).collect();
    d.set_item("notes", notes)?;
    Ok(d)
}

/// A finished render as `render_summary()` returns it.
pub fn summary_dict<'py>(py: Python<'py>, o: &Outcome) -> PyResult<Bound<'py, PyDict>> {
    let s = &o.summary;
    let d = PyDict::new(py);
    d.set_item("image", array(py, &s.image)?)?;
    if let Some(dn) = &s.denoised {
        d.set_item("denoised", array(py, dn)?)?;
    }
    d.set_item("method", s.method.name())?;
    d.set_item("spectral", s.plan.spectral)?;
    d.set_item("plan", stages(py, &s.plan)?)?;
    d.set_item("notes", &s.notes)?;
    d.set_item("units", s.stats.unit_span.1)?;
    d.set_item("seconds", s.stats.time.as_secs_f64())?;
    d.set_item("rays", s.stats.rays)?;
    d.set_item("estimate", o.estimate)?;
    d.set_item("end", o.end())?;
    Ok(d)
}

/// The lights of a file, as `iris info` lists them: its emissive meshes (kind `emissive
/// mesh`, name, material, emissive) and its punctual lights (kind `point`, `spot` or
/// `directional`, name, intensity and its unit, `cd` or `lx`).
fn lights<'py>(py: Python<'py>, desc: &SceneDesc) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for m in &desc.meshes {
        let Some(material) = m.material.and_then(|i| desc.materials.get(i)) else {
            continue;
        };
        if material.emissive.max_element() > 0.0 {
            let e = PyDict::new(py);
            e.set_item("kind", "emissive mesh")?;
            e.set_item("name", &m.name)?;
            e.set_item("material", m.material)?;
            e.set_item("emissive", material.emissive.to_array())?;
            list.append(e)?;
        }
    }
    for l in &desc.lights {
        let (kind, name, intensity, unit) = match l {
            LightDesc::Point {
                name, intensity, ..
            } => ("point", name, intensity, "cd"),
            LightDesc::Spot {
                name, intensity, ..
            } => ("spot", name, intensity, "cd"),
            LightDesc::Directional {
                name, intensity, ..
            } => ("directional", name, intensity, "lx"),
        };
        let e = PyDict::new(py);
        e.set_item("kind", kind)?;
        e.set_item("name", name)?;
        e.set_item("intensity", *intensity)?;
        e.set_item("unit", unit)?;
        list.append(e)?;
    }
    Ok(list)
}

/// What `info()` returns for the file at `path`, its description and `iris info`'s text.
pub fn info_dict<'py>(
    py: Python<'py>,
    path: &std::path::Path,
    desc: &SceneDesc,
    text: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let meshes = PyList::empty(py);
    for m in &desc.meshes {
        let e = PyDict::new(py);
        e.set_item("name", &m.name)?;
        e.set_item("triangles", m.indices.len())?;
        e.set_item("material", m.material)?;
        meshes.append(e)?;
    }
    let materials = PyList::empty(py);
    for m in &desc.materials {
        let e = PyDict::new(py);
        e.set_item("name", &m.name)?;
        e.set_item("base_color", m.base_color.to_array())?;
        e.set_item("metallic", m.metallic)?;
        e.set_item("roughness", m.roughness)?;
        e.set_item("transmission", m.transmission)?;
        e.set_item("ior", m.ior)?;
        e.set_item("dispersion", m.dispersion)?;
        e.set_item("emissive", m.emissive.to_array())?;
        materials.append(e)?;
    }
    let cameras: Vec<&str> = desc.cameras.iter().map(|c| c.name.as_str()).collect();
    d.set_item("file", path.to_string_lossy())?;
    d.set_item("meshes", meshes)?;
    d.set_item("materials", materials)?;
    d.set_item("lights", lights(py, desc)?)?;
    d.set_item("cameras", cameras)?;
    d.set_item("warnings", &desc.warnings)?;
    d.set_item("text", text)?;
    Ok(d)
}
