//! Building the problem from a preset, a TOML config file and `--set` overrides, in that order of
//! precedence (later wins). Names, ranges and messages come from the parameter table
//! (`rotor_rub::Parameter`).

use std::io::Read;
use std::path::{Path, PathBuf};

use clap::Args;
use rotor_rub::{Parameter, Preset, Problem};

use crate::error::{CliError, Result};

/// Largest config or speed-profile file read (1 MiB): a parameter file is a few hundred bytes,
/// a speed profile of 1 MiB holds some 40 000 points.
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Where a problem comes from: preset < config < --set.
#[derive(Args, Debug, Clone, Default)]
pub struct ProblemArgs {
    /// Named parameter set to start from (list them with `rotor-rub presets`) [default: paper,
    /// or the config file's `preset`]
    #[arg(long, value_name = "NAME", value_parser = parse_preset)]
    pub preset: Option<Preset>,

    /// TOML file of parameter values (a regular file of at most 1 MiB): keys are the --set
    /// names, plus an optional `preset = "NAME"`; its values override the preset's
    #[arg(long, value_name = "FILE.toml")]
    pub config: Option<PathBuf>,

    /// Override one value (repeatable; overrides preset and config). `rotor-rub params` lists
    /// every name with its default, valid range and meaning
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_set)]
    pub set: Vec<(Parameter, f64)>,
}

/// The parameters a user may set: every table entry except the start time (runs start at τ = 0).
pub fn settable() -> impl Iterator<Item = Parameter> {
    Parameter::ALL
        .into_iter()
        .filter(|&p| p != Parameter::StartTime)
}

/// A settable parameter by name, or a message listing the valid names.
pub fn parse_parameter(name: &str) -> Result<Parameter, String> {
    match Parameter::from_name(name) {
        Some(p) if p != Parameter::StartTime => Ok(p),
        _ => Err(format!(
            "unknown parameter '{}': expected one of {}",
            name.escape_debug(),
            settable()
                .map(Parameter::name)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// A preset by name, or a message listing the valid names.
pub fn parse_preset(name: &str) -> Result<Preset, String> {
    Preset::from_name(name).ok_or_else(|| {
        format!(
            "unknown preset '{}': expected one of {}",
            name.escape_debug(),
            Preset::ALL.map(Preset::name).join(", ")
        )
    })
}

/// `NAME=VALUE` for `--set`: a known name and a number (ranges are checked once every layer
/// is applied, so a later layer may correct an earlier one).
pub fn parse_set(arg: &str) -> Result<(Parameter, f64), String> {
    let (name, value) = arg
        .split_once('=')
        .ok_or_else(|| format!("'{}' is not of the form NAME=VALUE", arg.escape_debug()))?;
    let parameter = parse_parameter(name.trim())?;
    let number = value
        .trim()
        .parse::<f64>()
        .map_err(|_| format!("{parameter}: '{}' is not a number", value.escape_debug()))?;
    Ok((parameter, number))
}

/// A config file's contents: the preset it names and its values.
#[derive(Debug, PartialEq)]
pub struct Config {
    /// The preset named by `preset = "NAME"`, if any.
    pub preset: Option<Preset>,
    /// The values (not yet range-checked).
    pub values: Vec<(Parameter, f64)>,
}

/// Parse a config file's text; the message says what is wrong and on which line (a duplicate
/// key: which key, on the line of its second definition).
pub fn parse_config(text: &str) -> Result<Config, String> {
    let table: toml::Table = toml::from_str(text).map_err(|e| {
        let span = e.span();
        // The line holding the span's start: one more than the line breaks before it.
        let line = span.as_ref().map(|s| {
            let head = text.get(..s.start.min(text.len())).unwrap_or("");
            head.matches('\n').count() + 1
        });
        let at = line.map(|l| format!(" (line {l})")).unwrap_or_default();
        let message = e.message().trim();
        let key = span
            .and_then(|s| text.get(s))
            .filter(|key| message == "duplicate key" && !key.is_empty() && !key.contains('\n'));
        match key {
            Some(key) => format!("not valid TOML{at}: {message} `{}`", key.trim()),
            None => format!("not valid TOML{at}: {message}"),
        }
    })?;
    let mut config = Config {
        preset: None,
        values: Vec::new(),
    };
    for (key, value) in &table {
        // A message about one key says on which line it is set.
        let at = |m: String| match key_line(text, key) {
            Some(line) => format!("line {line}: {m}"),
            None => m,
        };
        if key == "preset" {
            let name = value
                .as_str()
                .ok_or_else(|| at("preset must be a string naming a preset".into()))?;
            config.preset = Some(parse_preset(name).map_err(at)?);
            continue;
        }
        let parameter = parse_parameter(key).map_err(at)?;
        let number = match value {
            toml::Value::Float(x) => *x,
            // Exact up to 2^53; larger integers are far outside every range anyway.
            toml::Value::Integer(i) => *i as f64,
            other => {
                return Err(at(format!(
                    "{parameter} must be a number, not the {} {other}",
                    other.type_str()
                )));
            }
        };
        config.values.push((parameter, number));
    }
    Ok(config)
}

/// The line (from 1) of a config text where the top-level `key` is set (`key = …`, `"key" = …`,
/// `'key' = …`): top-level keys come before any table, so the first such line is the one.
fn key_line(text: &str, key: &str) -> Option<usize> {
    let sets_key = |line: &str| {
        let Some((left, _)) = line.split_once('=') else {
            return false;
        };
        let left = left.trim();
        let unquoted = ['"', '\'']
            .iter()
            .find_map(|q| left.strip_prefix(*q).and_then(|l| l.strip_suffix(*q)))
            .unwrap_or(left);
        unquoted == key
    };
    text.split('\n').position(sets_key).map(|i| i + 1)
}

/// Read an input file (a `kind`, e.g. `config`, written as `format`, e.g. `TOML`): a regular
/// file of at most [`MAX_CONFIG_BYTES`], UTF-8 text.
pub fn read_capped(path: &Path, kind: &str, format: &str) -> Result<String, String> {
    let not_regular = || format!("not a regular file (a {kind} must be a plain {format} file)");
    // Checked before opening: opening a FIFO would block until a writer appears.
    let before = std::fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !before.is_file() {
        return Err(not_regular());
    }
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read the file: {e}"))?;
    let meta = file
        .metadata()
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        return Err(not_regular());
    }
    if meta.len() > MAX_CONFIG_BYTES {
        return Err(format!(
            "the file has {} bytes, more than the {MAX_CONFIG_BYTES} a {kind} may have",
            meta.len()
        ));
    }
    // The cap holds even if the file grows while it is read.
    let mut bytes = Vec::new();
    file.take(MAX_CONFIG_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if bytes.len() as u64 > MAX_CONFIG_BYTES {
        return Err(format!(
            "the file is larger than the {MAX_CONFIG_BYTES} bytes a {kind} may have"
        ));
    }
    String::from_utf8(bytes).map_err(|e| format!("not UTF-8 text: {e}"))
}

fn read_config(path: &Path) -> Result<Config> {
    let fail = |m: String| CliError::input(format!("--config {}: {m}", path.display()));
    parse_config(&read_capped(path, "config", "TOML").map_err(fail)?).map_err(fail)
}

/// Which layer set a parameter, for error messages.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Source {
    Preset(Preset),
    Config,
    Set,
}

impl ProblemArgs {
    /// The files the problem is read from (the config), with the flag naming each: no output may
    /// be one of them ([`crate::output::check_distinct`]).
    pub fn input_files(&self) -> Vec<(&'static str, &Path)> {
        self.config
            .iter()
            .map(|path| ("--config", path.as_path()))
            .collect()
    }

    /// The problem with every layer applied, validated.
    pub fn build(&self) -> Result<Problem> {
        self.build_with(&[])
    }

    /// As [`ProblemArgs::build`], with `extra` values applied last (e.g. a swept parameter).
    pub fn build_with(&self, extra: &[(Parameter, f64)]) -> Result<Problem> {
        self.build_naming(extra, "--set")
    }

    /// As [`ProblemArgs::build_with`], a validation error naming the overrides `overrides`
    /// ("--set" on the command line; the Python binding's keyword arguments).
    pub fn build_naming(&self, extra: &[(Parameter, f64)], overrides: &str) -> Result<Problem> {
        let config = self.config.as_deref().map(read_config).transpose()?;
        let preset = self
            .preset
            .or(config.as_ref().and_then(|c| c.preset))
            .unwrap_or(Preset::Paper);
        let mut problem = preset.problem();
        let mut sources = [Source::Preset(preset); Parameter::COUNT];
        let mut apply = |values: &[(Parameter, f64)], source: Source| {
            for &(parameter, value) in values {
                parameter.set(&mut problem, value);
                if let Some(slot) = sources.get_mut(parameter as usize) {
                    *slot = source;
                }
            }
        };
        if let Some(c) = &config {
            apply(&c.values, Source::Config);
        }
        apply(&self.set, Source::Set);
        apply(extra, Source::Set);
        problem.validate().map_err(|e| {
            let source = e.parameter().and_then(|p| sources.get(p as usize));
            let from = match source {
                Some(Source::Set) => format!(" (from {overrides})"),
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
#[path = "problem_tests.rs"]
mod tests;
