//! Python values → numbers, counts and flags, checked as strictly as the command line parses
//! text: a number is a real scalar (int, float or a numpy scalar; not a bool, a string or an
//! array), a count an integer (int or a numpy integer; not a float), a flag a bool (or
//! `numpy.bool_`). Every refusal is a ValueError naming the keyword, the value and what it must
//! be — never an OverflowError or a silent conversion (`True` taken as 1.0).

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyFloat, PyInt, PyType};

use crate::errors::input;

static REAL: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static INTEGRAL: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// `repr(value)` for a message (shortened past 60 characters).
pub fn shown(value: &Bound<'_, PyAny>) -> String {
    let text = value
        .repr()
        .map_or_else(|_| "?".to_string(), |r| r.to_string());
    if text.chars().count() > 60 {
        let head: String = text.chars().take(57).collect();
        format!("{head}...")
    } else {
        text
    }
}

/// The value's type name, for a message (`str`, `numpy.ndarray`).
fn type_name(value: &Bound<'_, PyAny>) -> String {
    let ty = value.get_type();
    let name = ty.name().map_or_else(|_| "?".into(), |n| n.to_string());
    match ty.module().map(|m| m.to_string()) {
        Ok(module) if module != "builtins" => format!("{module}.{name}"),
        _ => name,
    }
}

/// Whether `value` is a bool (Python's or numpy's), which is never taken as a number.
fn is_bool(value: &Bound<'_, PyAny>) -> bool {
    value.is_instance_of::<PyBool>()
        || (!value.is_instance_of::<PyInt>()
            && !value.is_instance_of::<PyFloat>()
            && value.extract::<bool>().is_ok())
}

/// A real number: int, float, a numpy floating or integer scalar, any `numbers.Real`.
pub fn real(name: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    let py = value.py();
    // Exact floats and ints first: the common case costs two type checks.
    let accepted = value.is_exact_instance_of::<PyFloat>()
        || value.is_exact_instance_of::<PyInt>()
        || (!is_bool(value) && value.is_instance(REAL.import(py, "numbers", "Real")?)?);
    if !accepted {
        return Err(input(format!(
            "{name}: {} ({}) is not a number: give an int or a float",
            shown(value),
            type_name(value)
        )));
    }
    value.extract::<f64>().map_err(|_| {
        input(format!(
            "{name}: {} is out of range: it must be a finite number",
            shown(value)
        ))
    })
}

/// An optional real number (None stays None).
pub fn real_opt(name: &str, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<f64>> {
    value
        .filter(|v| !v.is_none())
        .map(|v| real(name, v))
        .transpose()
}

/// A count: an integer (int or a numpy integer) from `min` to `u64::MAX`.
pub fn count(name: &str, value: &Bound<'_, PyAny>, min: u64) -> PyResult<u64> {
    let py = value.py();
    let integral = value.is_exact_instance_of::<PyInt>()
        || (!is_bool(value) && value.is_instance(INTEGRAL.import(py, "numbers", "Integral")?)?);
    if !integral {
        return Err(input(format!(
            "{name}: {} ({}) is not an integer",
            shown(value),
            type_name(value)
        )));
    }
    match value.extract::<u64>() {
        Ok(n) if n >= min => Ok(n),
        Ok(n) => Err(below(name, &n.to_string(), min)),
        Err(_) => {
            let negative = value.lt(0).unwrap_or(false);
            if negative {
                Err(below(name, &shown(value), min))
            } else {
                Err(input(format!(
                    "{name}: {} is out of range: it must be an integer from {min} to {}",
                    shown(value),
                    u64::MAX
                )))
            }
        }
    }
}

fn below(name: &str, value: &str, min: u64) -> PyErr {
    input(format!(
        "{name}: {value} is out of range: it must be an integer >= {min}"
    ))
}

/// A flag: True or False (or a numpy bool).
pub fn flag(name: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
    if !is_bool(value) {
        return Err(input(format!(
            "{name}: {} ({}) is not True or False",
            shown(value),
            type_name(value)
        )));
    }
    value.extract::<bool>()
}

/// A text option (a method or scheme name).
pub fn text(name: &str, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<String>> {
    match value.filter(|v| !v.is_none()) {
        None => Ok(None),
        Some(v) => v.extract::<String>().map(Some).map_err(|_| {
            input(format!(
                "{name}: {} ({}) is not a string",
                shown(v),
                type_name(v)
            ))
        }),
    }
}
