//! `import iris`: Iris as a Python module (PyO3, the stable ABI of CPython 3.11+).
//!
//! Every render function takes the scene's path (`str` or `os.PathLike`) and the `iris
//! render` flags as keyword arguments named like the flags (`spp=64`, `method="path"`,
//! `camera_look_at="0,0,1:0,0,0:35"`): `key=value` becomes `--key=value` with `_` as `-`
//! (so `spp=-1` gets the flag's own message); `True` is a bare flag, `False` and `None`
//! leave it out; a list repeats it (`stone=["diamond=Table", "ruby"]`); `size` may be a
//! `(width, height)` tuple; an `os.PathLike` value is its `os.fspath`. A keyword that
//! names no flag raises `TypeError` ([`args`]). The arguments are parsed by the command
//! line's own parser ([`iris::cli::parse_render`]) and rendered by the library functions
//! the command calls ([`iris::app::RenderJob`]), so a render here equals `iris render` with
//! the same flags. Unlike the command, the module writes no image unless `output=` is
//! given, denoises only when asked (`denoise="on"`), and shows no progress bar unless
//! `quiet=False`.
//!
//! A render runs on a worker thread while the calling thread checks for Ctrl-C and calls
//! the progress callback ([`progress`]): Ctrl-C cancels the render and raises
//! `KeyboardInterrupt` within a fraction of a second of rendering; `progress(info)` runs
//! on the calling thread at every checkpoint (1, 2, 4, … samples, the end) and at least
//! every second in between. `iris.load(path, **flags)` keeps a loaded [`scene::Scene`]
//! to render many times with other flags. `tonemap` and `save` apply Iris's display
//! transform and writers to an image ([`image`]).
//!
//! Images are `numpy.ndarray`s of float32, height × width × 3, linear RGB (radiance)
//! ([`convert`]). Iris's usage errors (a bad flag or value, naming it) raise `ValueError`;
//! every other error (a bad file, naming it and the element) raises `iris.IrisError`, with
//! the text the command prints.

mod args;
mod convert;
mod image;
mod progress;
mod scene;

use args::render_args;
use convert::{array, info_dict, plan_dict, summary_dict};
use iris::app::RenderJob;
use progress::{run, Outcome};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

pyo3::create_exception!(
    iris,
    IrisError,
    PyRuntimeError,
    "An error Iris reports about a file or the machine (the text names the file and element)."
);

/// An Iris error as the Python exception of the module docs.
pub(crate) fn py_err(e: iris::Error) -> PyErr {
    match e {
        iris::Error::Usage(_) => PyValueError::new_err(e.to_string()),
        _ => IrisError::new_err(e.to_string()),
    }
}

/// Renders the scene at `path` with the keyword `options` of `func`.
fn render_file(
    py: Python<'_>,
    func: &str,
    path: &Path,
    progress: Option<PyObject>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Outcome> {
    progress::check_callback(py, progress.as_ref())?;
    let opts = iris::cli::parse_render(&render_args(func, path, options)?).map_err(py_err)?;
    let write_image = opts.output.is_some();
    run(py, || RenderJob::new(&opts), progress, write_image)
}

/// render(path, progress=None, **options) -> numpy.ndarray
///
/// Renders the scene at `path` with the `iris render` flags given as keyword arguments
/// (module docs) and returns the linear image, float32, height × width × 3.
/// `progress(info)` is called at 1, 2, 4, 8, … samples (passes) and at the end with a dict
/// (units, passes, seconds, rays, photons, estimate, done, checkpoint: True), and at least
/// every second in between (checkpoint: False; the last checkpoint's figures with the time
/// now, estimate None); returning False stops the render (between checkpoints: with the
/// samples taken so far). Ctrl-C stops it and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (path, progress=None, **options))]
fn render<'py>(
    py: Python<'py>,
    path: PathBuf,
    progress: Option<PyObject>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let o = render_file(py, "render", &path, progress, options)?;
    array(py, &o.summary.image)
}

/// render_summary(path, progress=None, **options) -> dict
///
/// As `render`, with what the command prints: `image`, `denoised` (with denoise="on"),
/// `method`, `spectral`, `plan` (stages: name, used, reason), `notes`, `units`, `seconds`,
/// `rays`, `estimate` (the half-buffer error estimate of the image, also when the render
/// was stopped), `end` (samples, target, time limit, interrupted, or progress when the
/// callback stopped it).
#[pyfunction]
#[pyo3(signature = (path, progress=None, **options))]
fn render_summary<'py>(
    py: Python<'py>,
    path: PathBuf,
    progress: Option<PyObject>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let o = render_file(py, "render_summary", &path, progress, options)?;
    summary_dict(py, &o)
}

/// plan(path, **options) -> dict
///
/// The render plan `iris render` would follow with these flags, without rendering:
/// `method`, `spectral`, `size`, `stages` (name, used, reason), `notes`.
#[pyfunction]
#[pyo3(signature = (path, **options))]
fn plan<'py>(
    py: Python<'py>,
    path: PathBuf,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let args = render_args("plan", &path, options)?;
    let opts = iris::cli::parse_render(&args).map_err(py_err)?;
    let job = py.allow_threads(|| RenderJob::new(&opts)).map_err(py_err)?;
    plan_dict(py, &job)
}

/// info(path) -> dict
///
/// What Iris reads from the file: `meshes` (name, triangles, material), `materials` (name,
/// base_color, metallic, roughness, transmission, ior, dispersion, emissive), `lights`
/// (emissive meshes: kind "emissive mesh", name, material, emissive; punctual lights: kind
/// "point", "spot" or "directional", name, intensity, unit), `cameras` (names),
/// `warnings`, and `text`, what `iris info` prints.
#[pyfunction]
fn info<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let (desc, text) = py
        .allow_threads(|| {
            let desc = iris::load::load_scene(&path)?;
            Ok::<_, iris::Error>((desc, iris::app::info_command(&path)?))
        })
        .map_err(py_err)?;
    info_dict(py, &path, &desc, &text)
}

/// load(path, **flags) -> iris.Scene
///
/// The scene file at `path`, loaded once, to render many times: `scene.render(**flags)`,
/// `scene.render_summary(…)`, `scene.plan(…)`, `scene.info()`; `flags` here are the
/// defaults of every render of it.
#[pyfunction]
#[pyo3(signature = (path, **flags))]
fn load(
    py: Python<'_>,
    path: PathBuf,
    flags: Option<&Bound<'_, PyDict>>,
) -> PyResult<scene::Scene> {
    scene::Scene::new(py, path, flags)
}

/// Iris, a spectral renderer for glass, gems and caustics.
///
/// render(path, progress=None, **flags), render_summary(…), plan(path, **flags) and
/// info(path) take a scene file (str or os.PathLike) and the `iris render` flags as
/// keyword arguments (spp=64, size=(640, 360), stone="sapphire", camera_look_at=…;
/// `_` for `-`, True for a bare flag, a list repeats it); an unknown keyword raises
/// TypeError, a bad value ValueError naming the flag, a bad file iris.IrisError.
/// load(path, **flags) -> Scene reads a file once to render it many times
/// (scene.render(**flags) with other stones, cameras, sizes …). tonemap(image, exposure,
/// tonemap) and save(image, path, …) apply the command's PNG transform and writers;
/// read_exr(path) reads an EXR. Images are float32 height × width × 3 linear RGB arrays.
/// progress(info) runs on the calling thread at each checkpoint and every second;
/// returning False stops the render; Ctrl-C raises KeyboardInterrupt.
#[pymodule]
#[pyo3(name = "iris")]
fn iris_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(render_summary, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(info, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_class::<scene::Scene>()?;
    image::register(m)?;
    m.add("IrisError", m.py().get_type::<IrisError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
