//! CLI errors as Python exceptions: invalid input (the CLI's exit 2, a run over `max_work`
//! included) is `ValueError`, a failed propagation (exit 1) is `rotor_rub.PropagationError`, a
//! `RuntimeError`. Messages are the CLI's with its flags named as the Python keywords.

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rotor_rub::StepperError;
use rotor_rub_cli::error::{CliError, EXIT_INPUT, short_numbers};

create_exception!(
    _core,
    PropagationError,
    PyRuntimeError,
    "A propagation failed (diverged, a singular contact, a stepper's work cap)."
);

/// The CLI's flags and the keywords that say the same in Python, longest first where one flag
/// starts another.
const KEYWORD_OF_FLAG: [(&str, &str); 17] = [
    ("--samples-per-period", "samples_per_period"),
    ("--sample-count", "samples"),
    ("--contact-scheme", "contact_scheme"),
    ("--speed-holds", "speed_holds"),
    ("--ramp-periods", "ramp_periods"),
    ("--max-work", "max_work"),
    ("--transient", "transient"),
    ("--periods", "periods"),
    ("--profile", "profile"),
    ("--method", "method"),
    ("--config", "config"),
    ("--settle", "settle"),
    ("--dwell", "dwell"),
    ("--t-end", "t_end"),
    ("--keep", "keep"),
    ("--step", "step"),
    ("--tol", "tol"),
];

/// `message` with every CLI flag of [`KEYWORD_OF_FLAG`] named as its Python keyword.
pub fn keywords(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    'scan: while let Some(at) = rest.find("--") {
        let (before, from) = rest.split_at(at);
        out.push_str(before);
        for (flag, keyword) in KEYWORD_OF_FLAG {
            let Some(after) = from.strip_prefix(flag) else {
                continue;
            };
            let next = after.chars().next();
            if next.is_none_or(|c| !(c.is_ascii_alphanumeric() || c == '-')) {
                out.push_str(keyword);
                rest = after;
                continue 'scan;
            }
        }
        out.push_str("--");
        rest = &from[2..];
    }
    out.push_str(rest);
    out
}

/// A CLI error as the matching Python exception.
pub fn cli(e: CliError) -> PyErr {
    let message = keywords(&short_numbers(&e.message));
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
