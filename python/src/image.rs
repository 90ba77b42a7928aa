//! Images in and out: `read_exr`, `tonemap` (Iris's display transform, the one `iris
//! render -o x.png` applies: exposure, tone map, sRGB, 8 bits; [`iris::output::tonemap`])
//! and `save` (Iris's PNG and EXR writers, [`iris::output::write_image`]).

use crate::convert::{array, bytes_array, image};
use crate::py_err;
use iris::output::{DisplayOptions, Exposure, ToneMap};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyString;
use std::path::PathBuf;

/// `exposure=`: None or "auto", or stops in [-64, 64], as `--exposure`.
fn exposure(value: Option<&Bound<'_, PyAny>>) -> PyResult<Exposure> {
    let Some(value) = value else {
        return Ok(Exposure::Auto);
    };
    if let Ok(s) = value.downcast::<PyString>() {
        let s = s.to_cow()?;
        if s.eq_ignore_ascii_case("auto") {
            return Ok(Exposure::Auto);
        }
    }
    match value.extract::<f32>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 64.0 => Ok(Exposure::Ev(ev)),
        _ => Err(PyValueError::new_err(format!(
            "exposure: expected \"auto\" or stops in [-64, 64], got {}",
            value.repr()?
        ))),
    }
}

/// The display options of `exposure=` and `tonemap=`.
fn display(exposure_value: Option<&Bound<'_, PyAny>>, tonemap: &str) -> PyResult<DisplayOptions> {
    Ok(DisplayOptions {
        exposure: exposure(exposure_value)?,
        tonemap: ToneMap::parse(tonemap).map_err(py_err)?,
    })
}

/// read_exr(path) -> numpy.ndarray
///
/// An EXR image (its RGB channels) as Iris reads it: float32, height × width × 3.
#[pyfunction]
fn read_exr<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let image = iris::output::read_exr(&path).map_err(py_err)?;
    array(py, &image)
}

/// tonemap(image, exposure=None, tonemap="aces") -> numpy.ndarray
///
/// The 8-bit sRGB image `iris render -o x.png --exposure E --tonemap T` writes for a
/// linear `image` (height × width × 3): uint8, height × width × 3. `exposure` is None or
/// "auto" (log-average luminance to 0.18, the default) or stops; `tonemap` is aces, reinhard or clamp.
#[pyfunction]
#[pyo3(signature = (image, exposure=None, tonemap="aces"))]
fn tonemap<'py>(
    py: Python<'py>,
    image: &Bound<'py, PyAny>,
    exposure: Option<&Bound<'py, PyAny>>,
    tonemap: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let img = self::image(py, image)?;
    let d = display(exposure, tonemap)?;
    let bytes = py.allow_threads(|| iris::output::tonemap::to_srgb8(&img, d.exposure, d.tonemap));
    let shape = (img.height as usize, img.width as usize, 3usize);
    bytes_array(py, &bytes, "u1", shape)
}

/// save(image, path, exposure=None, tonemap="aces")
///
/// Writes a linear `image` (height × width × 3) as `iris render` writes its output, by
/// the extension: `.png` 8-bit sRGB after `exposure` and `tonemap` (as `tonemap()`),
/// `.exr` 32-bit float linear RGB; atomically. `path` is a str or os.PathLike.
#[pyfunction]
#[pyo3(signature = (image, path, exposure=None, tonemap="aces"))]
fn save(
    py: Python<'_>,
    image: &Bound<'_, PyAny>,
    path: PathBuf,
    exposure: Option<&Bound<'_, PyAny>>,
    tonemap: &str,
) -> PyResult<()> {
    let img = self::image(py, image)?;
    let d = display(exposure, tonemap)?;
    py.allow_threads(|| iris::output::write_image(&path, &img, &d))
        .map_err(py_err)
}

/// Adds the image functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_exr, m)?)?;
    m.add_function(wrap_pyfunction!(tonemap, m)?)?;
    m.add_function(wrap_pyfunction!(save, m)?)?;
    Ok(())
}
