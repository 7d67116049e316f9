//! Keyword arguments → the CLI library's inputs: the problem (preset < config < keywords), the
//! method options and the work budget. The same builders as the command line, so values, ranges
//! and messages are the CLI's.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyDictMethods};
use rotor_rub::{ContactScheme, Method, Options, Parameter, Problem};
use rotor_rub_cli::error::num;
use rotor_rub_cli::limits::{Budget, LimitArgs, work};
use rotor_rub_cli::options::{SchemeArgs, parse_method, parse_scheme, positive};
use rotor_rub_cli::problem::{ProblemArgs, parse_parameter, parse_preset};

use crate::errors::{cli, input};

/// The parameter overrides given as keywords (`speed_ratio=2.5`), validated by name; values are
/// range-checked with the whole problem.
pub fn overrides(params: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(Parameter, f64)>> {
    let mut set = Vec::new();
    if let Some(params) = params {
        for (key, value) in params.iter() {
            let name: String = key.extract()?;
            let parameter = parse_parameter(&name).map_err(input)?;
            let number: f64 = value.extract().map_err(|_| {
                input(format!(
                    "{parameter}: {} is not a number",
                    value.repr().map_or_else(|_| "?".into(), |r| r.to_string())
                ))
            })?;
            set.push((parameter, number));
        }
    }
    Ok(set)
}

/// The problem from `preset`, a TOML `config` file and keyword overrides (later wins), validated.
pub fn problem(
    preset: Option<&str>,
    config: Option<PathBuf>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<Problem> {
    let preset = preset.map(parse_preset).transpose().map_err(input)?;
    let args = ProblemArgs {
        preset,
        config,
        set: overrides(params)?,
    };
    args.build_naming(&[], KEYWORDS).map_err(cli)
}

/// How a validation message names the parameter keywords (the CLI's "--set").
pub const KEYWORDS: &str = "keyword arguments";

/// Method options: `method` by name (`default` when None), tolerance, contact scheme and step,
/// validated against the method's ranges.
pub fn options(
    method: Option<&str>,
    default: Method,
    tol: Option<f64>,
    contact_scheme: Option<&str>,
    step: Option<f64>,
) -> PyResult<Options> {
    let method = method
        .map(parse_method)
        .transpose()
        .map_err(input)?
        .unwrap_or(default);
    let number = |name: &str, x: Option<f64>| -> PyResult<Option<f64>> {
        x.map(|x| positive(x).map_err(|e| input(format!("{name}: {e}"))))
            .transpose()
    };
    let scheme: Option<ContactScheme> = contact_scheme
        .map(parse_scheme)
        .transpose()
        .map_err(input)?;
    let args = SchemeArgs {
        tol: number("tol", tol)?,
        contact_scheme: scheme,
        step: number("step", step)?,
    };
    args.options(method).map_err(cli)
}

/// The work budget of one call (`max_work`, default 1e9 as in the CLI).
pub fn budget(max_work: Option<f64>) -> PyResult<Budget> {
    let max_work = match max_work {
        None => 1e9 as u64,
        Some(w) => work(w).ok_or_else(|| {
            input(format!(
                "max_work: '{}' is not an integer from 1 to 1e18",
                num(w)
            ))
        })?,
    };
    Ok(LimitArgs { max_work }.budget())
}

/// A count given as a Python int, at least `min` (≥ 0).
pub fn count(name: &str, value: i64, min: u64) -> PyResult<u64> {
    u64::try_from(value)
        .ok()
        .filter(|&n| n >= min)
        .ok_or_else(|| {
            input(format!(
                "{name}: {value} is out of range: it must be an integer >= {min}"
            ))
        })
}
