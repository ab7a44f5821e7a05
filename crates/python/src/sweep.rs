//! A sweep over the library's [`flexrig::study::Sweep`]: the grid from Python values, its points
//! run in parallel (GIL released) into columns, and pickling so that a Dask worker can run a
//! chunk of the points.

use std::path::{Path, PathBuf};

use flexrig::study::spec::MAX_POINTS;
use flexrig::study::sweep::{SUMMARY_COLUMNS, SweepOptions, SweepRow};
use flexrig::study::{Dimension, Sweep as RunnerSweep};
use flexrig_rig::Override;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyMapping, PyString, PyTuple};

use crate::convert::{to_toml, toml_to_py};
use crate::{detached, input_error, to_py};

/// A sweep of a base scene over a grid (or zip) of scene fields. Built by `flexrig.sweep`;
/// picklable (a Dask worker runs chunks of its points).
#[pyclass(frozen, module = "flexrig._flexrig")]
pub struct Sweep {
    inner: RunnerSweep,
    base_text: String,
    dimensions: Vec<Dimension>,
    zip: bool,
}

/// The values of one grid entry: a str is a CLI SPEC (`0.1,0.2`, `10:60:11`, `1e-3:1:5:log`,
/// `@file`), a list, tuple, range or array gives its items, anything else is one value.
/// At most `budget` values (the grid's point bound over the other entries' counts), counted
/// before any is converted.
fn dimension(
    path: &str,
    spec: &Bound<'_, PyAny>,
    base_dir: Option<&Path>,
    budget: usize,
) -> PyResult<Dimension> {
    let checked = Override::parse(&format!("{path}=0")).map_err(|_| {
        input_error(
            path,
            format!(
                "grid: {path:?} is not a scene path: give dotted field names, e.g. \
                 robot.payload_kg or operator.start.release_angle_deg"
            ),
        )
    })?;
    let path = checked.path;
    if spec.is_instance_of::<PyString>() {
        let text: String = spec.extract()?;
        let read = |file: &str| {
            let local = PathBuf::from(file);
            match base_dir {
                Some(dir) if !local.exists() => flexrig::shared::output::read_text_limited(
                    &dir.join(file),
                    flexrig::study::spec::MAX_VALUE_FILE_BYTES,
                ),
                _ => flexrig::shared::output::read_text_limited(
                    &local,
                    flexrig::study::spec::MAX_VALUE_FILE_BYTES,
                ),
            }
        };
        return Dimension::parse_within(&format!("{path}={text}"), &read, budget).map_err(|e| {
            let message = e.to_string().replace("--set ", "grid: ");
            input_error(&path, message)
        });
    }
    // a sized collection (list, tuple, range, NumPy array, pandas Series) is counted first
    if spec.cast::<PyMapping>().is_err()
        && !spec.is_instance_of::<PyString>()
        && let Ok(count) = spec.len()
        && count > budget
    {
        return Err(input_error(
            &path,
            format!(
                "grid: {path} has {count} values; the grid may have at most {MAX_POINTS} \
                 points, so this entry at most {budget} with the others"
            ),
        ));
    }
    let values: Vec<toml::Value> = if spec.cast::<PyMapping>().is_ok() {
        vec![to_toml(&path, spec)?]
    } else if spec.hasattr("tolist")? {
        let list = spec.call_method0("tolist")?;
        if list.is_instance_of::<PyList>() {
            list.try_iter()?
                .map(|v| to_toml(&path, &v?))
                .collect::<PyResult<_>>()?
        } else {
            vec![to_toml(&path, &list)?]
        }
    } else if let Ok(items) = spec.try_iter() {
        items
            .map(|v| to_toml(&path, &v?))
            .collect::<PyResult<_>>()?
    } else {
        vec![to_toml(&path, spec)?]
    };
    if values.is_empty() {
        return Err(input_error(
            &path,
            format!("grid: {path} has no values (an empty list)"),
        ));
    }
    Ok(Dimension { path, values })
}

/// A varied value as a cell: scalars as Python values, tables and arrays as TOML text (as in
/// the CLI's CSV).
fn cell<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    match v {
        toml::Value::Table(_) | toml::Value::Array(_) | toml::Value::Datetime(_) => {
            Ok(v.to_string().into_pyobject(py)?.into_any())
        }
        _ => toml_to_py(py, v),
    }
}

impl Sweep {
    fn build(base_text: String, dimensions: Vec<Dimension>, zip: bool) -> PyResult<Self> {
        if dimensions.is_empty() {
            return Err(input_error(
                "grid",
                "grid: the grid is empty; give at least one scene path and its values, e.g. \
                 {\"robot.payload_kg\": [0.1, 0.2]}"
                    .into(),
            ));
        }
        if let Some(d) = dimensions.iter().find(|d| d.path.is_empty()) {
            return Err(input_error(
                "grid",
                format!("grid: empty path {:?}", d.path),
            ));
        }
        if zip
            && let Some(d) = dimensions
                .iter()
                .find(|d| d.values.len() != dimensions[0].values.len())
        {
            return Err(input_error(
                "zip",
                format!(
                    "zip: every grid entry needs the same number of values to zip ({} has {}, \
                     {} has {})",
                    dimensions[0].path,
                    dimensions[0].values.len(),
                    d.path,
                    d.values.len()
                ),
            ));
        }
        let inner = RunnerSweep::new(&base_text, dimensions.clone(), zip).map_err(to_py)?;
        Ok(Sweep {
            inner,
            base_text,
            dimensions,
            zip,
        })
    }

    /// The rows as columns: index, values (one list per path), status, error, summary, notes.
    fn columns<'py>(&self, py: Python<'py>, rows: &[SweepRow]) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        let index: Vec<i64> = rows.iter().map(|r| r.index as i64).collect();
        out.set_item("index", PyArray1::from_vec(py, index))?;
        let values = PyList::empty(py);
        for (k, _) in self.dimensions.iter().enumerate() {
            let column = PyList::empty(py);
            for r in rows {
                let point = self.inner.point(r.index);
                column.append(cell(py, &point[k].value)?)?;
            }
            values.append(column)?;
        }
        out.set_item("values", values)?;
        let status: Vec<&str> = rows.iter().map(|r| r.status.as_str()).collect();
        let error: Vec<&str> = rows.iter().map(|r| r.error.as_str()).collect();
        out.set_item("status", status)?;
        out.set_item("error", error)?;
        let summary: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| r.summary.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
            .collect();
        let summary = if summary.is_empty() {
            PyArray2::zeros(py, [0, SUMMARY_COLUMNS.len()], false)
        } else {
            PyArray2::from_vec2(py, &summary)
                .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?
        };
        out.set_item("summary", summary)?;
        let notes: Vec<&str> = rows.iter().map(|r| r.notes.as_str()).collect();
        out.set_item("notes", notes)?;
        Ok(out)
    }
}

#[pymethods]
impl Sweep {
    /// A sweep of the scene `base_text` over `grid`, a list of (dotted path, values) pairs (see
    /// `flexrig.sweep`); `zip` runs the value lists side by side instead of the full grid;
    /// `base_dir` is where `@file` specs are looked for after the working directory. An unknown
    /// path or a value of the wrong type raises InputError before anything runs.
    #[new]
    #[pyo3(signature = (base_text, grid, zip=false, base_dir=None))]
    fn new(
        base_text: String,
        grid: Vec<(String, Bound<'_, PyAny>)>,
        zip: bool,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Self> {
        let mut dimensions = Vec::with_capacity(grid.len());
        let mut product = 1usize;
        for (path, spec) in &grid {
            let budget = if zip {
                MAX_POINTS
            } else {
                MAX_POINTS / product
            };
            let d = dimension(path, spec, base_dir.as_deref(), budget)?;
            product = product.saturating_mul(d.values.len());
            dimensions.push(d);
        }
        Self::build(base_text, dimensions, zip)
    }

    /// Number of points (runs).
    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// The varied paths, in grid order (the value columns of the table).
    #[getter]
    fn paths(&self) -> Vec<String> {
        self.dimensions.iter().map(|d| d.path.clone()).collect()
    }

    /// True for a zipped sweep.
    #[getter]
    fn zip(&self) -> bool {
        self.zip
    }

    /// The base scene's TOML text.
    #[getter]
    fn base_text(&self) -> &str {
        &self.base_text
    }

    /// The grid with every spec resolved: a list of (path, list of values).
    fn grid<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        for d in &self.dimensions {
            let values = PyList::empty(py);
            for v in &d.values {
                values.append(toml_to_py(py, v)?)?;
            }
            out.append(PyTuple::new(
                py,
                [
                    d.path.clone().into_pyobject(py)?.into_any(),
                    values.into_any(),
                ],
            )?)?;
        }
        Ok(out)
    }

    /// The sweep's fingerprint (the same as `flexrig sweep` writes to sweep.json).
    fn fingerprint(&self) -> String {
        self.inner.fingerprint()
    }

    /// Runs the points `indices` (all by default) and returns the rows as columns: a dict with
    /// `index` (int64 array), `values` (a list per path), `status` and `error` (lists of str) and
    /// `summary` (float64 array, one row per point, SUMMARY_COLUMNS; NaN where absent) and
    /// `notes` (a list of str: the drive's notes, `; ` between two, empty without). A run that
    /// fails is a row with status `error` and its message. `threads`: None uses every core
    /// (rayon), 1 runs in the calling thread, k > 1 a pool of k threads. GIL released; Ctrl-C
    /// stops the sweep and raises KeyboardInterrupt.
    #[pyo3(signature = (indices=None, threads=None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        indices: Option<Vec<Bound<'py, PyAny>>>,
        threads: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let n = self.inner.len();
        if indices.is_none() {
            flexrig::study::spec::check_process_points("grid", n).map_err(to_py)?;
        }
        // any Python int is taken and judged here (a negative or huge one is an InputError
        // naming the argument, not an OverflowError of the conversion)
        let indices: Vec<usize> = match indices {
            None => (0..n).collect(),
            Some(items) => items
                .iter()
                .map(|item| {
                    item.extract::<i128>()
                        .ok()
                        .and_then(|i| usize::try_from(i).ok())
                        .filter(|&i| i < n)
                        .ok_or_else(|| {
                            input_error(
                                "indices",
                                format!(
                                    "indices: point {item} does not exist (the sweep has {n} \
                                     points, 0 to {})",
                                    n.saturating_sub(1)
                                ),
                            )
                        })
                })
                .collect::<PyResult<_>>()?,
        };
        let threads: Option<usize> = match threads {
            None => None,
            Some(t) => Some(
                t.extract::<i128>()
                    .ok()
                    .and_then(|k| usize::try_from(k).ok())
                    .filter(|&k| (1..=4096).contains(&k))
                    .ok_or_else(|| {
                        input_error(
                            "threads",
                            format!(
                                "threads = {t}: must be a whole number from 1 to 4096 (or None \
                                 for every core)"
                            ),
                        )
                    })?,
            ),
        };
        let options = SweepOptions::default();
        let inner = &self.inner;
        let rows = detached(py, &options.cancel, || match threads {
            Some(1) => Ok(indices
                .iter()
                .map(|&i| inner.run_point(i, &options))
                .collect()),
            Some(k) => rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map(|pool| pool.install(|| inner.run(&indices, &options, &|_| {}))),
            None => Ok(inner.run(&indices, &options, &|_| {})),
        })?
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
        if rows.iter().any(|r| r.status == "interrupted") {
            return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
                "the sweep was interrupted",
            ));
        }
        self.columns(py, &rows)
    }

    /// Pickling: the base text and the resolved grid.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let class = py.get_type::<Sweep>();
        let args = (self.base_text.clone(), self.grid(py)?, self.zip, py.None());
        (class, args).into_pyobject(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "Sweep({} points over {})",
            self.inner.len(),
            self.dimensions
                .iter()
                .map(|d| format!("{} ({} values)", d.path, d.values.len()))
                .collect::<Vec<_>>()
                .join(if self.zip { " zipped with " } else { " × " })
        )
    }
}
