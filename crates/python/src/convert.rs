//! Python values ↔ TOML values (scene fields, overrides, sweep values) and JSON values (summaries).

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyMapping, PyString, PyTuple};

use crate::input_error;

/// The TOML value of the Python value `v` at scene path `path` (named in errors): bool, int,
/// float (and NumPy scalars), str, a mapping with str keys (a table), a list or tuple (an array).
/// Nesting deeper than a scene value can be (a cyclic list, a very deep dict) raises InputError
/// naming the path instead of recursing without bound.
pub fn to_toml(path: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    to_toml_at(path, v, 0)
}

/// Most levels of nesting of a scene given as a dict (the file's own tables, then the values'
/// tables and arrays).
const MAX_NESTING: usize = flexrig_rig::overrides::MAX_VALUE_DEPTH + 4;

fn to_toml_at(path: &str, v: &Bound<'_, PyAny>, depth: usize) -> PyResult<toml::Value> {
    if depth > MAX_NESTING {
        let shown: String = path.chars().take(80).collect();
        return Err(input_error(
            &shown,
            format!(
                "scene field {shown}: the value nests lists or dicts more than {MAX_NESTING} \
                 levels deep (a cyclic list?); a scene value is a number, a string, a boolean, \
                 or a dict or list of them"
            ),
        ));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            input_error(
                path,
                format!("scene field {path} = {v}: an integer must fit in 64 bits"),
            )
        });
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if let Ok(mapping) = v.cast::<PyMapping>() {
        let mut table = toml::Table::new();
        for item in mapping.items()?.iter() {
            let (key, value): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item.extract()?;
            let Ok(key) = key.extract::<String>() else {
                return Err(input_error(
                    path,
                    format!("scene field {path}: the keys of a table must be str, not {key:?}"),
                ));
            };
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            table.insert(key, to_toml_at(&sub, &value, depth + 1)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .enumerate()
            .map(|(i, item)| to_toml_at(&format!("{path}[{i}]"), &item?, depth + 1))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // NumPy and other numeric scalars: integers by __index__, others by __float__; arrays by
    // tolist()
    let type_name = v.get_type().name()?.to_string();
    if type_name.starts_with("bool") {
        return Ok(toml::Value::Boolean(v.is_truthy()?));
    }
    if v.hasattr("__index__")?
        && let Ok(i) = v.extract::<i64>()
    {
        return Ok(toml::Value::Integer(i));
    }
    if v.hasattr("__float__")?
        && !v.hasattr("__len__")?
        && let Ok(x) = v.extract::<f64>()
    {
        return Ok(toml::Value::Float(x));
    }
    if v.hasattr("tolist")? {
        return to_toml_at(path, &v.call_method0("tolist")?, depth + 1);
    }
    Err(input_error(
        path,
        format!(
            "scene field {path}: a value of type {type_name} is not a scene value \
             (bool, int, float, str, dict or list)"
        ),
    ))
}

/// The Python value of a TOML value (tables as dicts, arrays as lists).
pub fn toml_to_py<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(x) => x.into_pyobject(py)?.into_any(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(toml_to_py(py, item)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(t) => {
            let dict = PyDict::new(py);
            for (k, item) in t {
                dict.set_item(k, toml_to_py(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// The Python value of a JSON value (objects as dicts, arrays as lists, null as None).
pub fn json_to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        serde_json::Value::Null => py.None().into_bound(py),
        serde_json::Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        serde_json::Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(u)) => u.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        serde_json::Value::String(s) => s.into_pyobject(py)?.into_any(),
        serde_json::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            list.into_any()
        }
        serde_json::Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, item) in map {
                dict.set_item(k, json_to_py(py, item)?)?;
            }
            dict.into_any()
        }
    })
}
