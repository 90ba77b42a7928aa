//! Keyword arguments → `iris render` arguments (the module docs' rules): each key must be
//! a render flag's long name with `_` for `-` (else `TypeError`, as Python says of an
//! unknown keyword), and each value is passed as `--flag=value`, so a negative number
//! reaches the flag's own check and its message (`--spp=-1`), not clap's "unexpected
//! argument". Paths may be `str` or any `os.PathLike`.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};
use std::path::Path;
use std::sync::OnceLock;

/// The long names of the render flags ([`iris::cli::render_flags`]), computed once.
fn known_flags() -> &'static [String] {
    static FLAGS: OnceLock<Vec<String>> = OnceLock::new();
    FLAGS.get_or_init(iris::cli::render_flags)
}

/// The `TypeError` for an unknown keyword of `func`, suggesting the nearest flag.
fn unknown_keyword(func: &str, key: &str) -> PyErr {
    let flag = key.replace('_', "-");
    let near = known_flags()
        .iter()
        .map(|f| (edit_distance(&flag, f), f))
        .filter(|(d, f)| *d <= 2.max(flag.len() / 4) && *d < f.len())
        .min();
    let hint = match near {
        Some((_, f)) => format!(" (did you mean '{}'?)", f.replace('-', "_")),
        None => String::new(),
    };
    PyTypeError::new_err(format!(
        "{func}() got an unexpected keyword argument '{key}'{hint}: the keywords are \
         `iris render` flags (iris render --help)"
    ))
}

/// Levenshtein distance of two short names.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// A value as the text of one flag: `os.PathLike` through `os.fspath`, else `str(value)`.
fn text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    if !value.is_instance_of::<PyString>() && value.hasattr("__fspath__")? {
        let path: std::path::PathBuf = value.extract()?;
        return Ok(path.to_string_lossy().into_owned());
    }
    Ok(value.str()?.to_string())
}

/// Checks that every key of `options` names a render flag (`TypeError` naming the first
/// that does not, as `func()` would).
pub fn check_keys(func: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    for key in options.into_iter().flat_map(|d| d.keys()) {
        let key: String = key.extract()?;
        if !known_flags().contains(&key.replace('_', "-")) {
            return Err(unknown_keyword(func, &key));
        }
    }
    Ok(())
}

/// The `iris render` arguments for the scene at `path` and the keyword `options` of
/// `func` (module docs): flags first, then `--` and the path (so a path starting with `-`
/// is a path). Without `quiet` the render is quiet; without `denoise`, not denoised.
pub fn render_args(
    func: &str,
    path: &Path,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<String>> {
    check_keys(func, options)?;
    let mut args = Vec::new();
    let (mut quiet, mut denoise) = (false, false);
    for (key, value) in options.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        let flag = format!("--{}", key.replace('_', "-"));
        quiet |= flag == "--quiet";
        denoise |= flag == "--denoise";
        if value.is_none() {
            continue;
        }
        if let Ok(b) = value.downcast::<PyBool>() {
            if b.is_true() {
                args.push(flag);
            }
            continue;
        }
        let sequence = value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>();
        if flag == "--size" && sequence && value.len()? == 2 {
            let (w, h) = (value.get_item(0)?, value.get_item(1)?);
            args.push(format!("{flag}={}x{}", text(&w)?, text(&h)?));
        } else if sequence {
            for item in value.try_iter()? {
                args.push(format!("{flag}={}", text(&item?)?));
            }
        } else {
            args.push(format!("{flag}={}", text(&value)?));
        }
    }
    if !quiet {
        args.push("--quiet".into());
    }
    if !denoise {
        args.push("--denoise=off".into());
    }
    args.extend(["--".into(), path.to_string_lossy().into_owned()]);
    Ok(args)
}

/// `defaults` updated with `options` (a scene's load options under a render's), as a new
/// dict.
pub fn merged<'py>(
    py: Python<'py>,
    defaults: &Py<PyDict>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let all = defaults.bind(py).copy()?;
    if let Some(o) = options {
        all.update(o.as_mapping())?;
    }
    Ok(all)
}
