//! `iris.Scene`: a scene file loaded once (read and validated into its description) and
//! rendered many times with other flags, as Mitsuba's `mi.load_file` then `mi.render`.
//! Each render prepares the kept description again with that render's flags (`--stone`,
//! cameras, size, lights: [`iris::prepare::prepare_loaded`]), without reading the file.

use crate::args::{merged, render_args};
use crate::convert::{array, info_dict, plan_dict, summary_dict};
use crate::progress::{run, Outcome};
use crate::py_err;
use iris::app::RenderJob;
use iris::scene::desc::SceneDesc;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Scene(path, **flags)
///
/// The scene file at `path` (str or os.PathLike), loaded once; `flags` are the defaults of
/// every render of it (`iris render` flags as keyword arguments, the module docs' rules),
/// each call's own keywords override them. `iris.load(path, **flags)` is the same.
#[pyclass(module = "iris", frozen)]
pub struct Scene {
    path: PathBuf,
    desc: SceneDesc,
    load_time: Duration,
    defaults: Py<PyDict>,
}

impl Scene {
    /// The `iris render` options of a call of `func` with `options` over the defaults.
    fn options(
        &self,
        py: Python<'_>,
        func: &str,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<iris::app::RenderOptions> {
        let all = merged(py, &self.defaults, options)?;
        let args = render_args(func, &self.path, Some(&all))?;
        iris::cli::parse_render(&args).map_err(py_err)
    }

    /// A render of the kept description with `options` over the defaults.
    fn outcome(
        &self,
        py: Python<'_>,
        func: &str,
        progress: Option<PyObject>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Outcome> {
        let opts = self.options(py, func, options)?;
        let write_image = opts.output.is_some();
        let desc = &self.desc;
        let make = || RenderJob::with_loaded(&opts, desc.clone(), self.load_time);
        run(py, make, progress, write_image)
    }
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (path, **flags))]
    pub fn new(
        py: Python<'_>,
        path: PathBuf,
        flags: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Scene> {
        let defaults = match flags {
            Some(f) => f.copy()?,
            None => PyDict::new(py),
        };
        // Bad defaults fail here, not at the first render.
        let args = render_args("Scene", &path, Some(&defaults))?;
        iris::cli::parse_render(&args).map_err(py_err)?;
        let (desc, load_time) = py
            .allow_threads(|| {
                let start = Instant::now();
                iris::load::load_scene(&path).map(|d| (d, start.elapsed()))
            })
            .map_err(|e| py_err(e.into()))?;
        Ok(Scene {
            path,
            desc,
            load_time,
            defaults: defaults.unbind(),
        })
    }

    /// The scene file's path (a str).
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The default flags (a copy).
    #[getter]
    fn flags<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.defaults.bind(py).copy()
    }

    /// render(progress=None, **flags) -> numpy.ndarray
    ///
    /// As `iris.render(path, …)` with the scene's default flags under these.
    #[pyo3(signature = (progress=None, **flags))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        progress: Option<PyObject>,
        flags: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let o = self.outcome(py, "render", progress, flags)?;
        array(py, &o.summary.image)
    }

    /// render_summary(progress=None, **flags) -> dict
    ///
    /// As `iris.render_summary(path, …)` with the scene's default flags under these.
    #[pyo3(signature = (progress=None, **flags))]
    fn render_summary<'py>(
        &self,
        py: Python<'py>,
        progress: Option<PyObject>,
        flags: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let o = self.outcome(py, "render_summary", progress, flags)?;
        summary_dict(py, &o)
    }

    /// plan(**flags) -> dict
    ///
    /// As `iris.plan(path, …)` with the scene's default flags under these.
    #[pyo3(signature = (**flags))]
    fn plan<'py>(
        &self,
        py: Python<'py>,
        flags: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let opts = self.options(py, "plan", flags)?;
        let job = py
            .allow_threads(|| RenderJob::with_loaded(&opts, self.desc.clone(), self.load_time))
            .map_err(py_err)?;
        plan_dict(py, &job)
    }

    /// info() -> dict
    ///
    /// As `iris.info(path)`: the description as loaded (`text` reads the file again, as
    /// `iris info` does).
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let text = py
            .allow_threads(|| iris::app::info_command(&self.path))
            .map_err(py_err)?;
        info_dict(py, &self.path, &self.desc, &text)
    }

    fn __repr__(&self) -> String {
        format!(
            "iris.Scene({:?}: {} meshes, {} materials, {} lights, {} cameras)",
            self.path,
            self.desc.meshes.len(),
            self.desc.materials.len(),
            self.desc.lights.len(),
            self.desc.cameras.len()
        )
    }
}
