//! Shared command-line options: method selection, accuracy settings, run length, number parsers.

use crate::error::CliError;
use clap::Args;
use rotor_rub::{ContactScheme, Method, Options, Params, PropagationError};

/// The command line's flags for the method options the runtime names (`tol`, `step`).
pub const FLAGS: &[(&str, &str)] = &[("tol", "--tol"), ("step", "--step")];

/// A method option out of range (the runtime's [`PropagationError::InvalidOption`]) as an input
/// error led by the flag that set it, from `flags` (option name, flag):
/// `--reference-tol: tol = 5e-1 is out of range for dop853: it must be in [1e-14, 1e-3]`.
pub fn flagged(e: PropagationError, flags: &[(&str, &str)]) -> CliError {
    let flag = match e {
        PropagationError::InvalidOption { what, .. } => flags
            .iter()
            .find(|(option, _)| *option == what)
            .map(|(_, flag)| *flag),
        _ => None,
    };
    match flag {
        Some(flag) => CliError::input(format!("{flag}: {e}")),
        None => CliError::input(e.to_string()),
    }
}

/// The reference method's options (`--reference`, `--reference-tol`), validated: a tolerance out
/// of the method's range is an input error naming `--reference-tol`.
pub fn reference_options(method: Method, tol: Option<f64>) -> Result<Options, CliError> {
    let options = Options {
        tol,
        ..Options::with_method(method)
    };
    options
        .validate()
        .map_err(|e| flagged(e, &[("tol", "--reference-tol")]))?;
    Ok(options)
}

/// A finite number > 0.
pub fn parse_positive(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) => positive(x),
        Err(_) => Err(format!("'{text}' is not a number")),
    }
}

/// `x` when it is a finite number > 0 (what [`parse_positive`] checks once the text is a number;
/// also the Python keywords' check).
pub fn positive(x: f64) -> Result<f64, String> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(format!(
            "{x} is out of range: it must be a finite number > 0"
        ))
    }
}

/// A finite number (any sign).
pub fn parse_finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(format!("{x} is not a finite number")),
        Err(_) => Err(format!("'{text}' is not a number")),
    }
}

/// An integer >= `min`, as a clap value parser; also in exponent form (`1e8`), as `--max-work`.
pub fn at_least(min: u64) -> impl Fn(&str) -> Result<u64, String> + Clone + Send + Sync + 'static {
    move |text: &str| {
        let n = count(text).ok_or_else(|| format!("'{text}' is not an integer >= {min}"))?;
        if n >= min {
            Ok(n)
        } else {
            Err(format!(
                "{n} is out of range: it must be an integer >= {min}"
            ))
        }
    }
}

/// A count: a non-negative integer, written out or in exponent form (`1e8`, `2.5e3`), up to
/// u64::MAX.
fn count(text: &str) -> Option<u64> {
    let text = text.trim();
    if let Ok(n) = text.parse::<u64>() {
        return Some(n);
    }
    let x: f64 = text.parse().ok()?;
    // 2^64 is the first float past u64::MAX; integral floats below it convert exactly.
    (x >= 0.0 && x.fract() == 0.0 && x < 18_446_744_073_709_551_616.0).then_some(x as u64)
}

/// A method by name.
pub fn parse_method(name: &str) -> Result<Method, String> {
    Method::from_name(name).ok_or_else(|| {
        format!(
            "unknown method '{name}': expected one of {}",
            names(Method::ALL.iter().copied())
        )
    })
}

/// A numerical reference method (one whose registry entry says it integrates the full
/// equations: dop853, rk45).
pub fn parse_reference(name: &str) -> Result<Method, String> {
    match Method::from_name(name) {
        Some(m) if m.info().numerical_reference => Ok(m),
        _ => Err(format!(
            "unknown reference method '{name}': expected one of {}",
            names(references())
        )),
    }
}

/// The numerical reference methods, in the registry's order.
fn references() -> impl Iterator<Item = Method> {
    Method::ALL
        .iter()
        .copied()
        .filter(|m| m.info().numerical_reference)
}

/// `a, b or c`.
fn names(methods: impl Iterator<Item = Method>) -> String {
    let all: Vec<&str> = methods.map(Method::name).collect();
    match all.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => all.join(""),
    }
}

/// `--method`'s help, from the registry.
fn method_help() -> String {
    let list: Vec<String> = Method::ALL
        .iter()
        .map(|m| format!("{} ({})", m.name(), m.description()))
        .collect();
    format!("Propagation method: {}", list.join("; "))
}

/// `--reference`'s help, from the registry.
pub fn reference_help() -> String {
    format!("Numerical reference method: {}", names(references()))
}

/// `--tol`'s help, from the registry.
fn tol_help() -> String {
    let list: Vec<String> = Method::ALL
        .iter()
        .map(|m| {
            format!(
                "{} {:e} in {}",
                m.name(),
                m.default_tolerance(),
                m.tolerance_range()
            )
        })
        .collect();
    format!(
        "Accuracy target (relative and absolute) [default and valid range: {}]",
        list.join(", ")
    )
}

/// `--step`'s help, with its range.
fn step_help() -> String {
    format!(
        "Fixed contact sub-step of the analytic method, in units of τ, in {} (exprb2 always uses a fixed sub-step, default {:e}; exprb43 uses it instead of step control)",
        rotor_rub::method::STEP_RANGE,
        rotor_rub::analytic::DEFAULT_EXPRB2_STEP
    )
}

/// A contact scheme by name.
pub fn parse_scheme(name: &str) -> Result<ContactScheme, String> {
    ContactScheme::from_name(name).ok_or_else(|| {
        let all: Vec<&str> = ContactScheme::ALL.iter().map(|s| s.name()).collect();
        format!(
            "unknown contact scheme '{name}': expected one of {}",
            all.join(", ")
        )
    })
}

/// The analytic method's settings (also the accuracy of any other method through `--tol`).
#[derive(Args, Debug, Clone)]
pub struct SchemeArgs {
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true, help = tol_help())]
    pub tol: Option<f64>,

    /// Contact scheme of the analytic method: exprb43 (4th order, adaptive) or exprb2 (the paper's
    /// step re-linearized at every sub-step, 2nd order, fixed sub-step) [default: exprb43]
    #[arg(long, value_name = "SCHEME", value_parser = parse_scheme)]
    pub contact_scheme: Option<ContactScheme>,

    #[arg(long, value_name = "H", value_parser = parse_positive, allow_hyphen_values = true, help = step_help())]
    pub step: Option<f64>,
}

impl SchemeArgs {
    /// Library options for `method` with these settings, validated (a tolerance or step out of
    /// its range is an input error naming the option as the runtime does, `tol = …`, the value
    /// and the range: the Python keywords' message). `--contact-scheme` and `--step` belong to
    /// methods with a contact scheme: given with another method they are an input error, not
    /// ignored.
    pub fn options(&self, method: Method) -> Result<Options, CliError> {
        let options = self.unchecked(method)?;
        options
            .validate()
            .map_err(|e| CliError::input(e.to_string()))?;
        Ok(options)
    }

    /// [`SchemeArgs::options`] with a value out of range named by its flag ([`FLAGS`]), as the
    /// command line reports it.
    pub fn cli_options(&self, method: Method) -> Result<Options, CliError> {
        let options = self.unchecked(method)?;
        options.validate().map_err(|e| flagged(e, FLAGS))?;
        Ok(options)
    }

    /// The options, with only the method mismatch checked.
    fn unchecked(&self, method: Method) -> Result<Options, CliError> {
        if !method.info().contact_scheme {
            let flag = match (self.contact_scheme, self.step) {
                (Some(_), _) => Some("--contact-scheme"),
                (None, Some(_)) => Some("--step"),
                (None, None) => None,
            };
            if let Some(flag) = flag {
                return Err(CliError::input(format!(
                    "{flag} applies only to --method analytic, not to --method {}",
                    method.name()
                )));
            }
        }
        Ok(Options {
            method,
            tol: self.tol,
            contact_scheme: self.contact_scheme.unwrap_or(ContactScheme::Exprb43),
            step: self.step,
        })
    }
}

/// The method a command runs when `--method` is not given. The defaults of every command live
/// here, in one place.
pub trait DefaultMethod: Clone + std::fmt::Debug + Default + Send + Sync + 'static {
    /// The default method.
    const METHOD: Method;
}

/// `simulate`: the paper's method (analytic), closed forms end to end.
#[derive(Clone, Debug, Default)]
pub struct SingleRun;

impl DefaultMethod for SingleRun {
    const METHOD: Method = Method::Analytic;
}

/// `sweep`, `poincare`, `spectrum`: many periods or many runs, where speed counts. Taylor
/// (BENCHMARKS.md, "The taylor method"): 0–15 % more time than hybrid at the same default
/// tolerance with switch times 100–160× closer to DOP853 at tol 1e-13; within 5 % of it at equal
/// switch-time accuracy 1e-8 and 1.1–1.5× faster at 1e-9 to 1e-11; 6× faster on rolling. Hybrid,
/// the default before it, is 15× faster than analytic.
#[derive(Clone, Debug, Default)]
pub struct Survey;

impl DefaultMethod for Survey {
    const METHOD: Method = Method::Taylor;
}

/// Method selection plus its settings; `D` gives the command's default method.
#[derive(Args, Debug, Clone)]
pub struct MethodArgs<D: DefaultMethod> {
    #[arg(long, value_name = "METHOD", default_value = D::METHOD.name(), value_parser = parse_method, help = method_help())]
    pub method: Method,

    #[command(flatten)]
    pub scheme: SchemeArgs,

    #[arg(skip)]
    _default: std::marker::PhantomData<D>,
}

impl<D: DefaultMethod> MethodArgs<D> {
    /// The library options (an input error for analytic-only flags with another method, or for
    /// a tolerance or step out of range, naming its flag).
    pub fn options(&self) -> Result<Options, CliError> {
        self.scheme.cli_options(self.method)
    }
}

/// Describes options for messages, e.g. `analytic (exprb43, tol 1e-9)`.
pub fn describe(options: &Options) -> String {
    let tol = options.tolerance();
    let method = options.method;
    if !method.info().contact_scheme {
        return format!("{} (tol {tol:e})", method.name());
    }
    let scheme = options.contact_scheme.name();
    match options.step {
        Some(h) => format!("{} ({scheme}, step {h:e}, tol {tol:e})", method.name()),
        None => format!("{} ({scheme}, tol {tol:e})", method.name()),
    }
}

/// How long to run, from τ = 0.
#[derive(Args, Debug, Clone)]
pub struct TimeArgs {
    /// End time τ_end (dimensionless time τ = ω_n t), > 0
    #[arg(long, value_name = "T", value_parser = parse_positive, allow_hyphen_values = true, conflicts_with = "periods")]
    pub t_end: Option<f64>,

    /// Run length in forcing periods 2π/η (may be fractional), > 0 [default: 20]
    #[arg(long, value_name = "N", value_parser = parse_positive, allow_hyphen_values = true)]
    pub periods: Option<f64>,
}

impl TimeArgs {
    /// The end time for these parameters.
    pub fn end_time(&self, params: &Params) -> f64 {
        match (self.t_end, self.periods) {
            (Some(t), _) => t,
            (None, n) => n.unwrap_or(20.0) * params.forcing_period(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser, Debug)]
    struct SurveyCommand {
        #[command(flatten)]
        method: MethodArgs<Survey>,
    }

    #[derive(Parser, Debug)]
    struct Single {
        #[command(flatten)]
        method: MethodArgs<SingleRun>,
    }

    #[test]
    fn each_command_kind_has_its_default_method() {
        let survey = SurveyCommand::try_parse_from(["x"]).unwrap();
        assert_eq!(survey.method.method, Method::Taylor);
        let single = Single::try_parse_from(["x"]).unwrap();
        assert_eq!(single.method.method, Method::Analytic);
        let chosen = SurveyCommand::try_parse_from(["x", "--method", "rk45"]).unwrap();
        assert_eq!(chosen.method.method, Method::Rk45);
    }

    #[test]
    fn out_of_range_tolerances_and_steps_are_input_errors() {
        let args = |tol, step| SchemeArgs {
            tol,
            contact_scheme: None,
            step,
        };
        for &m in Method::ALL {
            let e = args(Some(10.0), None).options(m).unwrap_err();
            assert_eq!(e.code, crate::error::EXIT_INPUT, "{m:?}");
            let range = m.tolerance_range();
            assert!(e.message.contains("1e1"), "{}", e.message);
            assert!(e.message.contains(&range.to_string()), "{}", e.message);
            assert!(args(Some(range.max), None).options(m).is_ok());
            // The command line names the flag, the library call the option.
            let e = args(Some(10.0), None).cli_options(m).unwrap_err();
            assert!(e.message.starts_with("--tol: tol = 1e1"), "{}", e.message);
        }
        let e = reference_options(Method::Dop853, Some(0.5)).unwrap_err();
        assert!(
            e.message
                .starts_with("--reference-tol: tol = 5e-1 is out of range for dop853"),
            "{}",
            e.message
        );
        assert!(reference_options(Method::Rk45, Some(1e-4)).is_ok());
        for step in [1e-300, 1e300] {
            let e = args(None, Some(step))
                .options(Method::Analytic)
                .unwrap_err();
            assert_eq!(e.code, crate::error::EXIT_INPUT);
            assert!(e.message.contains(&format!("{step:e}")), "{}", e.message);
        }
    }

    #[test]
    fn counts_take_exponent_form() {
        let parse = at_least(2);
        assert_eq!(parse("1e8"), Ok(100_000_000));
        assert_eq!(parse("2.5e3"), Ok(2500));
        assert_eq!(parse(" 7 "), Ok(7));
        assert_eq!(parse("18446744073709551615"), Ok(u64::MAX));
        assert!(parse("1").unwrap_err().contains("1 is out of range"));
        for bad in ["1.5", "-1", "1e20", "nan", "inf", "", "two"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn help_lists_every_registered_method() {
        let help = method_help();
        for &m in Method::ALL {
            assert!(help.contains(m.name()) && help.contains(m.description()));
        }
        assert!(parse_reference("analytic").is_err());
        for name in ["dop853", "rk45"] {
            assert!(parse_reference(name).is_ok());
        }
    }
}
