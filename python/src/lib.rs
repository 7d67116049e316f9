//! `rotor_rub._core`, the compiled core of the Python package `rotor_rub` (see
//! `python/rotor_rub/__init__.py` for the public, typed API). It calls the CLI library
//! (`rotor_rub_cli`) so inputs, results and error messages are the command line's.
//!
//! Modules: `args` (Python values → numbers, counts and flags, strictly), `inputs` (keywords →
//! the CLI library's problem and options), `watch` (long calls under the CLI library's watch:
//! Ctrl-C and progress every ~50 ms), `runs` (simulate, poincare, spectrum), `sweep` (sweeps with
//! response classes, Lyapunov exponents and continuation, on a thread pool per call), `runup` +
//! `runup_speed`, `orbit` (rr.orbit, rr.continuation), `stepper` + `stepper_state` (the stepper
//! and its checked saved state), `meta`
//! (the problem a result carries), `matrix` (rotors from matrices: `rotor_rub.Model`'s
//! checks, modes and runs through the CLI library's model files; the ring with mass), `errors` (CLI errors → ValueError / PropagationError, flags
//! named as keywords). The typed layer is `python/rotor_rub/` (results as dataclasses of numpy
//! arrays, plots, pandas/xarray/Parquet/NetCDF, progress bars, Dask sweeps).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::params::Number;
use rotor_rub::{EventKind, Preset, Regime};
use rotor_rub_cli::problem::settable;

mod args;
mod errors;
mod inputs;
mod matrix;
mod meta;
mod orbit;
mod runs;
mod runup;
mod runup_speed;
mod stepper;
mod stepper_state;
mod sweep;
mod timing;
mod watch;

/// Every settable parameter of the table: name, symbol, default, range (min, max, min_open),
/// the range as text, and meaning.
#[pyfunction]
fn parameters(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    settable()
        .map(|p| {
            let info = p.info();
            let d = PyDict::new(py);
            d.set_item("name", info.name)?;
            d.set_item("symbol", info.symbol)?;
            d.set_item("default", info.default)?;
            d.set_item("min", info.range.min)?;
            d.set_item("max", info.range.max)?;
            d.set_item("min_open", info.range.min_open)?;
            d.set_item("range", info.range.to_string())?;
            d.set_item("default_text", Number(info.default).to_string())?;
            d.set_item("doc", info.doc)?;
            Ok(d)
        })
        .collect()
}

/// Every preset: name → (description, {parameter: value} for every settable parameter).
#[pyfunction]
fn presets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for preset in Preset::ALL {
        let problem = preset.problem();
        let values = PyDict::new(py);
        for p in settable() {
            values.set_item(p.name(), p.get(&problem))?;
        }
        out.set_item(preset.name(), (preset.description(), values))?;
    }
    Ok(out)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // NumPy's C API is loaded here, at import, not on the first array a call returns: loading
    // it runs Python code, where a pending Ctrl-C would surface as a panic.
    use numpy::IntoPyArray;
    drop(Vec::<f64>::new().into_pyarray(m.py()));
    m.add_function(wrap_pyfunction!(parameters, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(runs::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(runs::poincare, m)?)?;
    m.add_function(wrap_pyfunction!(runs::spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_points, m)?)?;
    m.add_function(wrap_pyfunction!(runup::runup, m)?)?;
    m.add_function(wrap_pyfunction!(orbit::orbit, m)?)?;
    m.add_function(wrap_pyfunction!(orbit::continuation, m)?)?;
    matrix::register(m)?;
    m.add_function(wrap_pyfunction!(timing::rust_simulate_seconds, m)?)?;
    m.add_class::<stepper::PyStepper>()?;
    m.add_class::<stepper_state::PyStepperState>()?;
    m.add(
        "PropagationError",
        m.py().get_type::<errors::PropagationError>(),
    )?;
    m.add("EVENT_KINDS", EventKind::ALL.map(EventKind::name).to_vec())?;
    m.add(
        "REGIMES",
        [Regime::Free, Regime::Contact, Regime::Rolling]
            .map(Regime::name)
            .to_vec(),
    )?;
    m.add("SPEED_DIRECTIONS", ["up", "down", "hold"])?;
    m.add("WHIRL_DIRECTIONS", ["forward", "backward", "mixed"])?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
