//! What a stepped run-up ([`super::matrix`]) shows: its diagram and its report's lines about
//! the branches.

use std::fmt::Write as _;

use rotor_rub::Options;

use super::analysis::Branch;
use super::figure::branch_curves;
use super::steps::Program;
use crate::error::num;
use crate::model_file::Subject;
use crate::options::describe;
use crate::plot::runup::RunupFigure;

/// The run-up diagram of a stepped run (the speed in rad/s and the station's radius in m for a
/// model file; η and the rotor's radius in clearances for the ring).
pub fn figure(
    subject: &Subject,
    program: &Program,
    options: &Options,
    [up, down]: [&Branch; 2],
) -> RunupFigure {
    let file = matches!(subject, Subject::File { .. });
    let unit = subject.length_unit();
    let (curves, legend) = branch_curves([up, down]);
    RunupFigure {
        title: match subject {
            Subject::File { label, .. } => {
                format!("Stepped run-up of {label}: the rub station's orbit radius |P|")
            }
            Subject::Ring(p) => format!(
                "Stepped run-up of the paper's rotor with a ring of mass m̂ = {}",
                num(p.params.stator_mass_ratio)
            ),
        },
        subtitle: format!(
            "{}; {}; thick: largest radius, thin: smallest radius per forcing period",
            program.description,
            describe(options)
        ),
        legend,
        curves,
        axes: Some(if file {
            (
                "speed Ω (rad/s), held over each step".to_string(),
                format!("rub station radius |P| per forcing period ({unit})"),
            )
        } else {
            (
                "speed ratio η = Ω/ω_n, held over each step".to_string(),
                format!("orbit radius |q| per forcing period ({unit})"),
            )
        }),
    }
}

/// The report's lines about the speed program, the method and each branch.
pub fn summary(
    subject: &Subject,
    program: &Program,
    options: &Options,
    [up, down]: [&Branch; 2],
) -> String {
    let file = matches!(subject, Subject::File { .. });
    let unit = subject.length_unit();
    let mut report = String::new();
    let _ = writeln!(report, "speed: {}", program.description);
    let _ = writeln!(report, "method: {}", describe(options));
    let symbol = if file { "Ω" } else { "η" };
    for branch in [up, down] {
        let (Some(first), Some(last)) = (branch.rows.first(), branch.rows.last()) else {
            continue;
        };
        let peak = branch
            .rows
            .iter()
            .max_by(|a, b| a.max_radius.total_cmp(&b.max_radius));
        let _ = write!(
            report,
            "{}: {symbol} {} -> {} over {} forcing periods, rubbing in {:.0} % of them",
            branch.label(),
            num(first.speed_ratio),
            num(last.speed_ratio),
            branch.rows.len(),
            100.0 * branch.rubbing_fraction()
        );
        if let Some(p) = peak {
            let _ = write!(
                report,
                ", largest radius {:.4e} {unit} at {symbol} = {}",
                p.max_radius,
                num(p.speed_ratio)
            );
        }
        let _ = writeln!(report, "; {} jumps", branch.jumps.len());
    }
    report
}
