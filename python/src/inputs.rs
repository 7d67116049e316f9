//! Keyword arguments → the CLI library's inputs: the problem (preset < config < keywords), the
//! method options and the work budget. The same builders as the command line, so values, ranges
//! and messages are the CLI's (with the keywords named where the CLI names its flags).

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyDictMethods};
use rotor_rub::{ContactScheme, Method, Options, Parameter, Problem};
use rotor_rub_cli::limits::{Budget, LimitArgs, work};
use rotor_rub_cli::options::{SchemeArgs, parse_method, parse_scheme, positive};
use rotor_rub_cli::problem::{ProblemArgs, parse_parameter, parse_preset};

use crate::args;
use crate::errors::{cli, input};

/// The parameter overrides given as keywords (`speed_ratio=2.5`), validated by name and as real
/// numbers; values are range-checked with the whole problem.
pub fn overrides(params: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(Parameter, f64)>> {
    let mut set = Vec::new();
    if let Some(params) = params {
        for (key, value) in params.iter() {
            let name: String = key.extract()?;
            let parameter = parse_parameter(&name).map_err(input)?;
            let number = args::real(parameter.name(), &value)?;
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

/// The method keywords of a call, as given.
pub struct MethodKeywords<'a, 'py> {
    pub method: Option<&'a Bound<'py, PyAny>>,
    pub tol: Option<&'a Bound<'py, PyAny>>,
    pub contact_scheme: Option<&'a Bound<'py, PyAny>>,
    pub step: Option<&'a Bound<'py, PyAny>>,
}

/// Method options: `method` by name (`default` when None), tolerance, contact scheme and step,
/// validated against the method's ranges.
pub fn options(keywords: &MethodKeywords<'_, '_>, default: Method) -> PyResult<Options> {
    let method = args::text("method", keywords.method)?
        .map(|m| parse_method(&m))
        .transpose()
        .map_err(input)?
        .unwrap_or(default);
    let number = |name: &str, x: Option<&Bound<'_, PyAny>>| -> PyResult<Option<f64>> {
        args::real_opt(name, x)?
            .map(|x| positive(x).map_err(|e| input(format!("{name}: {e}"))))
            .transpose()
    };
    let scheme: Option<ContactScheme> = args::text("contact_scheme", keywords.contact_scheme)?
        .map(|s| parse_scheme(&s))
        .transpose()
        .map_err(input)?;
    let args = SchemeArgs {
        tol: number("tol", keywords.tol)?,
        contact_scheme: scheme,
        step: number("step", keywords.step)?,
    };
    args.options(method).map_err(cli)
}

/// The work budget of one call (`max_work`, default 1e9 as in the CLI), its messages naming
/// the keyword.
pub fn budget(max_work: Option<&Bound<'_, PyAny>>) -> PyResult<Budget> {
    let max_work = match args::real_opt("max_work", max_work)? {
        None => 1e9 as u64,
        Some(w) => work(w).ok_or_else(|| {
            input(format!(
                "max_work: {} is out of range: it must be an integer from 1 to 1e18",
                rotor_rub_cli::error::num(w)
            ))
        })?,
    };
    Ok(LimitArgs { max_work }.budget().named("max_work"))
}

/// A path keyword (`config`, `profile`) as given by the Python layer (already `os.fspath`).
pub fn path(value: Option<String>) -> Option<PathBuf> {
    value.map(PathBuf::from)
}
