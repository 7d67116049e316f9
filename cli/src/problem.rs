//! Building the problem from a preset, a TOML config file and `--set` overrides, in that order of
//! precedence (later wins).

use std::path::{Path, PathBuf};

use clap::Args;
use rotor_rub::{Field, ParamError, Preset, Problem};

use crate::error::{CliError, Result};

/// Where a problem comes from: preset < config < --set.
#[derive(Args, Debug, Clone, Default)]
pub struct ProblemArgs {
    /// Named parameter set to start from (list them with `rotor-rub presets`) [default: paper,
    /// or the config file's `preset`]
    #[arg(long, value_name = "NAME", value_parser = parse_preset)]
    pub preset: Option<Preset>,

    /// TOML file of parameter values: keys are the --set names, plus an optional
    /// `preset = "NAME"`; its values override the preset's
    #[arg(long, value_name = "FILE.toml")]
    pub config: Option<PathBuf>,

    /// Override one value (repeatable; overrides preset and config). Names: speed_ratio (η =
    /// Ω/ω_n, must be > 0), damping_ratio (ν, must be >= 0), mass_ratio (η_m, must be > 0),
    /// eccentricity_ratio (ρ̂, unbalance eccentricity over the clearance, must be > 0), phase
    /// (φ0, rad), k_xx, k_xy, k_yx, k_yy (stator stiffness over rotor stiffness; k_xx and k_yy
    /// must be >= 0), offset_x, offset_y (stator offset, in clearances), x0, y0 (initial
    /// position, in clearances), vx0, vy0 (initial velocity, in clearances per unit τ)
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_set)]
    pub set: Vec<(Field, f64)>,
}

/// The fields a user may set: every [`Field`] except the start time (runs start at τ = 0).
pub fn settable_fields() -> impl Iterator<Item = Field> {
    Field::ALL.into_iter().filter(|&f| f != Field::StartTime)
}

/// What a field is, with its symbol and unit, for listings.
pub fn meaning(field: Field) -> &'static str {
    match field {
        Field::SpeedRatio => "η = Ω/ω_n, running speed over natural frequency",
        Field::DampingRatio => "ν, viscous damping ratio",
        Field::MassRatio => "η_m, unbalance mass over disk mass",
        Field::EccentricityRatio => "ρ̂, unbalance eccentricity in clearances",
        Field::Phase => "φ0, unbalance phase at τ = 0, rad",
        Field::KXx | Field::KXy | Field::KYx | Field::KYy => {
            "stator support stiffness over rotor stiffness"
        }
        Field::OffsetX | Field::OffsetY => "stator centre offset, clearances",
        Field::X0 | Field::Y0 => "initial position, clearances",
        Field::Vx0 | Field::Vy0 => "initial velocity, clearances per unit τ",
        Field::StartTime => "start time τ0",
    }
}

/// A settable field by name, or a message listing the valid names.
pub fn parse_field(name: &str) -> Result<Field, String> {
    match Field::from_name(name) {
        Some(f) if f != Field::StartTime => Ok(f),
        _ => Err(format!(
            "unknown parameter '{name}': expected one of {}",
            settable_fields()
                .map(Field::name)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// A preset by name, or a message listing the valid names.
pub fn parse_preset(name: &str) -> Result<Preset, String> {
    Preset::from_name(name).ok_or_else(|| {
        format!(
            "unknown preset '{name}': expected one of {}",
            Preset::ALL.map(Preset::name).join(", ")
        )
    })
}

/// A finite or non-finite number (range checks are `Problem::validate`'s job).
fn parse_number(field: Field, text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| format!("{field}: '{text}' is not a number"))
}

/// `NAME=VALUE` for `--set`.
pub fn parse_set(arg: &str) -> Result<(Field, f64), String> {
    let (name, value) = arg
        .split_once('=')
        .ok_or_else(|| format!("'{arg}' is not of the form NAME=VALUE"))?;
    let field = parse_field(name.trim())?;
    Ok((field, parse_number(field, value)?))
}

/// Which layer set a field, for error messages.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Source {
    Preset(Preset),
    Config,
    Set,
}

/// A config file's contents: the preset it names and its values.
struct Config {
    preset: Option<Preset>,
    values: Vec<(Field, f64)>,
}

fn read_config(path: &Path) -> Result<Config> {
    let shown = path.display();
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::input(format!("--config {shown}: cannot read the file: {e}")))?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        let at = line.map(|l| format!(" (line {l})")).unwrap_or_default();
        CliError::input(format!(
            "--config {shown}: not valid TOML{at}: {}",
            e.message().trim()
        ))
    })?;
    let mut config = Config {
        preset: None,
        values: Vec::new(),
    };
    for (key, value) in &table {
        if key == "preset" {
            let name = value.as_str().ok_or_else(|| {
                CliError::input(format!(
                    "--config {shown}: preset must be a string naming a preset"
                ))
            })?;
            config.preset = Some(
                parse_preset(name)
                    .map_err(|m| CliError::input(format!("--config {shown}: {m}")))?,
            );
            continue;
        }
        let field =
            parse_field(key).map_err(|m| CliError::input(format!("--config {shown}: {m}")))?;
        let number = match value {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            other => {
                return Err(CliError::input(format!(
                    "--config {shown}: {field} must be a number, not the {} {other}",
                    other.type_str()
                )));
            }
        };
        config.values.push((field, number));
    }
    Ok(config)
}

fn error_field(e: &ParamError) -> Option<Field> {
    match *e {
        ParamError::NonFinite { field, .. }
        | ParamError::NotPositive { field, .. }
        | ParamError::Negative { field, .. }
        | ParamError::TooLarge { field, .. } => Some(field),
        ParamError::UndampedResonance => None,
    }
}

impl ProblemArgs {
    /// The problem with every layer applied, validated.
    pub fn build(&self) -> Result<Problem> {
        self.build_with(&[])
    }

    /// As [`ProblemArgs::build`], with `extra` values applied last (e.g. a swept parameter).
    pub fn build_with(&self, extra: &[(Field, f64)]) -> Result<Problem> {
        let config = self.config.as_deref().map(read_config).transpose()?;
        let preset = self
            .preset
            .or(config.as_ref().and_then(|c| c.preset))
            .unwrap_or(Preset::Paper);
        let mut problem = preset.problem();
        let mut sources = [Source::Preset(preset); Field::ALL.len()];
        let mut apply = |values: &[(Field, f64)], source: Source| {
            for &(field, value) in values {
                field.set(&mut problem, value);
                sources[field as usize] = source;
            }
        };
        if let Some(c) = &config {
            apply(&c.values, Source::Config);
        }
        apply(&self.set, Source::Set);
        apply(extra, Source::Set);
        problem.validate().map_err(|e| {
            let from = match error_field(&e).map(|f| sources[f as usize]) {
                Some(Source::Set) => " (from --set)".to_string(),
                Some(Source::Config) => format!(
                    " (from --config {})",
                    self.config.as_deref().unwrap_or(Path::new("")).display()
                ),
                Some(Source::Preset(p)) => format!(" (from preset {})", p.name()),
                None => String::new(),
            };
            CliError::input(format!("invalid parameters{from}: {e}"))
        })?;
        Ok(problem)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_parses_and_rejects() {
        assert_eq!(parse_set("k_xx=2"), Ok((Field::KXx, 2.0)));
        assert!(parse_set("k_xx").unwrap_err().contains("NAME=VALUE"));
        assert!(
            parse_set("start_time=1")
                .unwrap_err()
                .contains("unknown parameter")
        );
        assert!(parse_set("phase=abc").unwrap_err().contains("phase"));
    }

    #[test]
    fn field_indices_match_all_order() {
        for (i, f) in Field::ALL.into_iter().enumerate() {
            assert_eq!(f as usize, i);
        }
    }
}
