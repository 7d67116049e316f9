//! CLI errors as Python exceptions: invalid input (the CLI's exit 2) is `ValueError`, a failed
//! propagation (exit 1) is `rotor_rub.PropagationError`, a `RuntimeError`. Messages are the CLI's.

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rotor_rub::StepperError;
use rotor_rub_cli::error::{CliError, EXIT_INPUT, short_numbers};

create_exception!(
    _core,
    PropagationError,
    PyRuntimeError,
    "A propagation failed (diverged, over the work limit while running, a singular contact)."
);

/// A CLI error as the matching Python exception.
pub fn cli(e: CliError) -> PyErr {
    let message = short_numbers(&e.message);
    if e.code == EXIT_INPUT {
        PyValueError::new_err(message)
    } else {
        PropagationError::new_err(message)
    }
}

/// An input error (ValueError) with `message`.
pub fn input(message: impl Into<String>) -> PyErr {
    cli(CliError::input(message))
}

/// A stepper error: invalid problem, configuration or step are ValueError, the rest
/// PropagationError.
pub fn stepper(e: StepperError) -> PyErr {
    match e {
        StepperError::Propagation(rotor_rub::PropagationError::InvalidProblem(_))
        | StepperError::InvalidConfig { .. }
        | StepperError::InvalidStep { .. } => PyValueError::new_err(short_numbers(&e.to_string())),
        _ => PropagationError::new_err(short_numbers(&e.to_string())),
    }
}
