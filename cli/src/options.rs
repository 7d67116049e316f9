//! Shared command-line options: method selection, accuracy settings, run length, number parsers.

use crate::error::CliError;
use clap::Args;
use rotor_rub::{ContactScheme, Method, Options, Params};

/// A finite number > 0.
pub fn parse_positive(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(x) => Err(format!(
            "{x} is out of range: it must be a finite number > 0"
        )),
        Err(_) => Err(format!("'{text}' is not a number")),
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

/// An integer >= `min`, as a clap value parser.
pub fn at_least(min: u64) -> impl Fn(&str) -> Result<u64, String> + Clone + Send + Sync + 'static {
    move |text: &str| match text.trim().parse::<u64>() {
        Ok(n) if n >= min => Ok(n),
        Ok(n) => Err(format!(
            "{n} is out of range: it must be an integer >= {min}"
        )),
        Err(_) => Err(format!("'{text}' is not an integer >= {min}")),
    }
}

/// A method by name.
pub fn parse_method(name: &str) -> Result<Method, String> {
    Method::from_name(name).ok_or_else(|| {
        format!(
            "unknown method '{name}': expected one of {}",
            Method::ALL.map(Method::name).join(", ")
        )
    })
}

/// A numerical reference method: dop853 or rk45.
pub fn parse_reference(name: &str) -> Result<Method, String> {
    match Method::from_name(name) {
        Some(m @ (Method::Dop853 | Method::Rk45)) => Ok(m),
        _ => Err(format!(
            "unknown reference method '{name}': expected dop853 or rk45"
        )),
    }
}

/// A contact scheme by name.
pub fn parse_scheme(name: &str) -> Result<ContactScheme, String> {
    ContactScheme::from_name(name)
        .ok_or_else(|| format!("unknown contact scheme '{name}': expected exprb43 or exprb2"))
}

/// The analytic method's settings (also the accuracy of any other method through `--tol`).
#[derive(Args, Debug, Clone)]
pub struct SchemeArgs {
    /// Accuracy target (relative and absolute), a number > 0 [default: 1e-9 for analytic, 1e-10
    /// for hybrid, dop853 and rk45]
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true)]
    pub tol: Option<f64>,

    /// Contact scheme of the analytic method: exprb43 (4th order, adaptive) or exprb2 (the paper's
    /// step re-linearized at every sub-step, 2nd order, fixed sub-step) [default: exprb43]
    #[arg(long, value_name = "SCHEME", value_parser = parse_scheme)]
    pub contact_scheme: Option<ContactScheme>,

    /// Fixed contact sub-step h of the analytic method, in units of τ, > 0 (exprb43 uses it
    /// instead of step control)
    #[arg(long, value_name = "H", value_parser = parse_positive, allow_hyphen_values = true)]
    pub step: Option<f64>,
}

impl SchemeArgs {
    /// Library options for `method` with these settings. `--contact-scheme` and `--step` belong
    /// to the analytic method: given with another method they are an input error, not ignored.
    pub fn options(&self, method: Method) -> Result<Options, CliError> {
        if method != Method::Analytic {
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

/// Method selection plus its settings.
#[derive(Args, Debug, Clone)]
pub struct MethodArgs {
    /// Propagation method: analytic (piecewise closed form), hybrid (closed-form free flight,
    /// DOP853 in contact), dop853 or rk45 (adaptive Runge–Kutta on the full equations)
    #[arg(long, value_name = "METHOD", default_value = "analytic", value_parser = parse_method)]
    pub method: Method,

    #[command(flatten)]
    pub scheme: SchemeArgs,
}

impl MethodArgs {
    /// The library options (an input error for analytic-only flags with another method).
    pub fn options(&self) -> Result<Options, CliError> {
        self.scheme.options(self.method)
    }
}

/// Describes options for messages, e.g. `analytic (exprb43, tol 1e-9)`.
pub fn describe(options: &Options) -> String {
    let tol = options.tolerance();
    match options.method {
        Method::Analytic => match options.step {
            Some(h) => format!(
                "analytic ({}, step {h}, tol {tol:e})",
                options.contact_scheme.name()
            ),
            None => format!("analytic ({}, tol {tol:e})", options.contact_scheme.name()),
        },
        m => format!("{} (tol {tol:e})", m.name()),
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
