//! What every result carries about the problem it came from: every parameter's value, the
//! method and its settings (the tolerance in force, not only the one given), and the version
//! (the Python layer's `rotor_rub.Problem`).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::{Options, Problem};
use rotor_rub_cli::options::describe;
use rotor_rub_cli::problem::settable;

/// `{"params": {name: value}, "method": …, "tol": …, "contact_scheme": …, "step": …,
/// "method_text": …, "version": …}`.
pub fn problem<'py>(
    py: Python<'py>,
    problem: &Problem,
    options: &Options,
) -> PyResult<Bound<'py, PyDict>> {
    let params = PyDict::new(py);
    for p in settable() {
        params.set_item(p.name(), p.get(problem))?;
    }
    let out = PyDict::new(py);
    out.set_item("params", params)?;
    out.set_item("method", options.method.name())?;
    out.set_item("tol", options.tolerance())?;
    let scheme = options.method.info().contact_scheme;
    out.set_item(
        "contact_scheme",
        scheme.then(|| options.contact_scheme.name()),
    )?;
    out.set_item("step", options.step)?;
    out.set_item("method_text", describe(options))?;
    out.set_item("version", env!("CARGO_PKG_VERSION"))?;
    Ok(out)
}
