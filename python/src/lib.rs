//! `import iris`: Iris as a Python module (PyO3, the stable ABI of CPython 3.11+).
//!
//! Every function takes the scene's path and the `iris render` flags as keyword arguments
//! named like the flags (`spp=64`, `method="path"`, `camera_look_at="0,0,1:0,0,0:35"`):
//! `key=value` becomes `--key value` with `_` as `-`; `True` is a bare flag, `False` and
//! `None` leave it out; a list repeats it (`stone=["diamond=Table", "ruby"]`); `size` may
//! be a `(width, height)` tuple. The arguments are parsed by the command line's own parser
//! ([`iris::cli::parse_render`]) and rendered by the library functions the command calls
//! ([`iris::app::RenderJob`]), so a render here equals `iris render` with the same flags.
//! Unlike the command, the module writes no image unless `output=` is given, denoises only
//! when asked (`denoise="on"`), and shows no progress bar unless `quiet=False`.
//!
//! Images are `numpy.ndarray`s of float32, height × width × 3, linear RGB (radiance).
//! Iris's usage errors (a bad flag or value, naming it) raise `ValueError`; every other
//! error (a bad file, naming it and the element) raises `iris.IrisError`, with the text
//! the command prints.

use iris::app::{RenderJob, RunHooks};
use iris::image::ImageRgb;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyTuple};

pyo3::create_exception!(
    iris,
    IrisError,
    PyRuntimeError,
    "An error Iris reports about a file or the machine (the text names the file and element)."
);

/// An Iris error as the Python exception of the module docs.
fn py_err(e: iris::Error) -> PyErr {
    match e {
        iris::Error::Usage(_) => PyValueError::new_err(e.to_string()),
        _ => IrisError::new_err(e.to_string()),
    }
}

/// The `iris render` arguments for `path` and the keyword options (module docs).
fn render_args(path: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let mut args = vec![path.to_string()];
    let (mut quiet, mut denoise) = (false, false);
    for (key, value) in options.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        let flag = format!("--{}", key.replace('_', "-"));
        quiet |= key == "quiet";
        denoise |= key == "denoise";
        if value.is_none() {
            continue;
        }
        if let Ok(b) = value.downcast::<pyo3::types::PyBool>() {
            if b.is_true() {
                args.push(flag);
            }
            continue;
        }
        if key == "size" {
            if let Ok((w, h)) = value.extract::<(u32, u32)>() {
                args.extend([flag, format!("{w}x{h}")]);
                continue;
            }
        }
        if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
            for item in value.try_iter()? {
                args.extend([flag.clone(), item?.str()?.to_string()]);
            }
            continue;
        }
        args.extend([flag, value.str()?.to_string()]);
    }
    if !quiet {
        args.push("--quiet".into());
    }
    if !denoise {
        args.extend(["--denoise".into(), "off".into()]);
    }
    Ok(args)
}

/// An image as a float32 H×W×3 array.
fn array<'py>(py: Python<'py>, image: &ImageRgb) -> PyResult<Bound<'py, PyAny>> {
    let mut bytes = Vec::with_capacity(image.data.len() * 12);
    for p in &image.data {
        for c in p.to_array() {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    let numpy = py.import("numpy")?;
    let flat = numpy.call_method1("frombuffer", (PyBytes::new(py, &bytes), "<f4"))?;
    let shape = (image.height as usize, image.width as usize, 3usize);
    // A copy: the buffer's array is read-only.
    flat.call_method1("reshape", (shape,))?.call_method0("copy")
}

/// The plan's stages as dicts.
fn stages<'py>(py: Python<'py>, plan: &iris::plan::Plan) -> PyResult<Bound<'py, PyList>> {
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

/// A render's checkpoint as the dict a progress callback gets.
fn progress_dict<'py>(py: Python<'py>, p: &iris::render::Progress) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("units", p.samples)?;
    d.set_item("passes", p.passes)?;
    d.set_item("seconds", p.elapsed.as_secs_f64())?;
    d.set_item("rays", p.rays)?;
    d.set_item("photons", p.photons)?;
    d.set_item("done", p.done)?;
    let estimate = (p.samples >= 2)
        .then(|| iris::render::relative_error_estimate(p.halves.0, p.halves.1))
        .flatten();
    d.set_item("estimate", estimate)?;
    Ok(d)
}

/// Runs the render the arguments describe; the summary, and whether the callback stopped it.
fn run(
    py: Python<'_>,
    path: &str,
    progress: Option<PyObject>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<(iris::app::RenderSummary, bool)> {
    let args = render_args(path, options)?;
    let opts = iris::cli::parse_render(&args).map_err(py_err)?;
    let write_image = opts.output.is_some();
    let mut failure: Option<PyErr> = None;
    let mut stopped = false;
    let summary = py.allow_threads(|| {
        let job = RenderJob::new(&opts)?;
        let mut hook = |p: &iris::render::Progress| -> bool {
            Python::with_gil(|py| {
                // Ctrl-C in the interpreter stops the render at this checkpoint.
                if let Err(e) = py.check_signals() {
                    failure = Some(e);
                    return false;
                }
                let Some(callback) = &progress else {
                    return true;
                };
                let answer = progress_dict(py, p).and_then(|d| callback.call1(py, (d,)));
                match answer {
                    Ok(a) if a.is_none(py) => true,
                    Ok(a) => {
                        let go_on = a.is_truthy(py).unwrap_or(false);
                        stopped |= !go_on;
                        go_on
                    }
                    Err(e) => {
                        failure = Some(e);
                        false
                    }
                }
            })
        };
        job.run_with(RunHooks {
            write_image,
            progress: Some(&mut hook),
        })
    });
    if let Some(e) = failure {
        return Err(e);
    }
    Ok((summary.map_err(py_err)?, stopped))
}

/// render(path, progress=None, **options) -> numpy.ndarray
///
/// Renders the scene at `path` with the `iris render` flags given as keyword arguments
/// (module docs) and returns the linear image, float32, height × width × 3.
/// `progress(info)` is called at 1, 2, 4, 8, … samples (passes) and at the end with a dict
/// (units, passes, seconds, rays, photons, estimate, done); returning False stops the
/// render there.
#[pyfunction]
#[pyo3(signature = (path, progress=None, **options))]
fn render<'py>(
    py: Python<'py>,
    path: &str,
    progress: Option<PyObject>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (summary, _) = run(py, path, progress, options)?;
    array(py, &summary.image)
}

/// render_summary(path, progress=None, **options) -> dict
///
/// As `render`, with what the command prints: `image`, `denoised` (with denoise="on"),
/// `method`, `spectral`, `plan` (stages: name, used, reason), `notes`, `units`, `seconds`,
/// `rays`, `estimate` (the final half-buffer estimate), `end` (samples, target, time limit,
/// interrupted, or progress when the callback stopped it).
#[pyfunction]
#[pyo3(signature = (path, progress=None, **options))]
fn render_summary<'py>(
    py: Python<'py>,
    path: &str,
    progress: Option<PyObject>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (s, stopped) = run(py, path, progress, options)?;
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
    d.set_item("estimate", s.target_estimate)?;
    let end = match s.stats.end {
        _ if stopped => "progress",
        iris::render::EndReason::Samples => "samples",
        iris::render::EndReason::Target => "target",
        iris::render::EndReason::TimeLimit => "time limit",
        iris::render::EndReason::Interrupted => "interrupted",
    };
    d.set_item("end", end)?;
    Ok(d)
}

/// plan(path, **options) -> dict
///
/// The render plan `iris render` would follow with these flags, without rendering:
/// `method`, `spectral`, `size`, `stages` (name, used, reason), `notes`.
#[pyfunction]
#[pyo3(signature = (path, **options))]
fn plan<'py>(
    py: Python<'py>,
    path: &str,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let args = render_args(path, options)?;
    let opts = iris::cli::parse_render(&args).map_err(py_err)?;
    let job = py.allow_threads(|| RenderJob::new(&opts)).map_err(py_err)?;
    let d = PyDict::new(py);
    d.set_item("method", job.plan.method.name())?;
    d.set_item("spectral", job.plan.spectral)?;
    d.set_item("size", job.prepared.size)?;
    d.set_item("stages", stages(py, &job.plan)?)?;
    let notes: Vec<String> = job.prepared.notes().iter().map(|n| n.to_string()).collect();
    d.set_item("notes", notes)?;
    Ok(d)
}

/// info(path) -> dict
///
/// What Iris reads from the file: `meshes` (name, triangles, material), `materials` (name,
/// base_color, metallic, roughness, transmission, ior, dispersion, emissive), `lights`
/// (kind, name), `cameras` (names), `warnings`, and `text`, what `iris info` prints.
#[pyfunction]
fn info<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyDict>> {
    let p = std::path::PathBuf::from(path);
    let (desc, text) = py
        .allow_threads(|| {
            let desc = iris::load::load_scene(&p)?;
            Ok::<_, iris::Error>((desc, iris::app::info_command(&p)?))
        })
        .map_err(py_err)?;
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
    let lights = PyList::empty(py);
    for l in &desc.lights {
        let e = PyDict::new(py);
        let kind = format!("{l:?}");
        e.set_item(
            "kind",
            kind.split([' ', '{', '('])
                .next()
                .unwrap_or("light")
                .to_lowercase(),
        )?;
        lights.append(e)?;
    }
    let cameras: Vec<&str> = desc.cameras.iter().map(|c| c.name.as_str()).collect();
    d.set_item("file", path)?;
    d.set_item("meshes", meshes)?;
    d.set_item("materials", materials)?;
    d.set_item("lights", lights)?;
    d.set_item("cameras", cameras)?;
    d.set_item("warnings", &desc.warnings)?;
    d.set_item("text", text)?;
    Ok(d)
}

/// read_exr(path) -> numpy.ndarray
///
/// An EXR image (its RGB channels) as Iris reads it: float32, height × width × 3.
#[pyfunction]
fn read_exr<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyAny>> {
    let image = iris::output::read_exr(std::path::Path::new(path)).map_err(py_err)?;
    array(py, &image)
}

/// Iris, a spectral renderer for glass, gems and caustics.
#[pymodule]
#[pyo3(name = "iris")]
fn iris_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(render_summary, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(info, m)?)?;
    m.add_function(wrap_pyfunction!(read_exr, m)?)?;
    m.add("IrisError", m.py().get_type::<IrisError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
