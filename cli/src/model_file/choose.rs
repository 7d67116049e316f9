//! What a command runs ([`target`]: the paper's planar model, a model file or the ring with
//! mass), the columns an option names, and the refusal of a planar-only option.

use rotor_rub::{Problem, State};

use super::analyses::Subject;
use crate::error::{CliError, Result};

/// The (x, y, x', y') of a row's orbit columns in clearances (`indices` from
/// [`Subject::orbit_columns`], `clearance` the files' clearance): what the response class and
/// the plots take.
pub fn orbit_state(row: &[f64], indices: &[usize; 4], clearance: f64) -> State {
    let at = |k: usize| {
        indices
            .get(k)
            .and_then(|&i| row.get(i))
            .map_or(f64::NAN, |v| v / clearance)
    };
    State::new(at(0), at(1), at(2), at(3))
}

/// What an analysis runs: the paper's planar model, or a matrix model.
#[derive(Clone, Debug)]
pub enum Target {
    /// The paper's rotor with a massless ring (the planar propagator).
    Planar(Problem),
    /// A model file or the ring with mass.
    Matrix(Subject),
}

/// The target of a command from its `--model` and problem options: the model file when given
/// (read and checked value by value: exit 2 naming the file), else the problem, a matrix
/// subject when its ring has mass (`stator_mass_ratio` > 0).
///
/// # Errors
/// A model file that cannot be read or is wrong; a problem value out of range.
pub fn target(
    model: Option<&std::path::Path>,
    problem: &crate::problem::ProblemArgs,
) -> Result<Target> {
    if let Some(path) = model {
        let spec = super::command::read(path)?;
        return Ok(Target::Matrix(Subject::file(spec, path)));
    }
    let problem = problem.build()?;
    if problem.params.stator_mass_ratio > 0.0 {
        Ok(Target::Matrix(Subject::Ring(problem)))
    } else {
        Ok(Target::Planar(problem))
    }
}

/// The columns an option names (`all`: every column; `None`: `default`).
///
/// # Errors
/// As [`Subject::pick`].
pub fn chosen_columns(
    subject: &Subject,
    flag: &str,
    names: Option<&str>,
    default: &[String],
) -> Result<Vec<usize>> {
    match names {
        Some("all") => Ok((0..subject.columns().len()).collect()),
        Some(names) => subject.pick(flag, names),
        None => subject.pick(flag, &default.join(",")),
    }
}

/// The indices of [`Subject::orbit_columns`].
pub fn orbit_indices(subject: &Subject) -> [usize; 4] {
    let all = subject.columns();
    subject
        .orbit_columns()
        .map(|name| all.iter().position(|c| c == name).unwrap_or(usize::MAX))
}

/// An option the planar model alone has, refused for a matrix model (exit 2).
pub fn planar_only(flag: &str, subject: &Subject) -> CliError {
    let what = match subject {
        Subject::File { label, .. } => format!("a model file (--model {label})"),
        Subject::Ring(_) => "the stator ring with mass (stator_mass_ratio > 0)".to_string(),
    };
    CliError::input(format!(
        "{flag} applies only to the paper's planar model, not to {what}"
    ))
}
