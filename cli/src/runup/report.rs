//! The report of `rotor-rub runup` on stdout: the speed program, the method, each branch's
//! speeds, rubbing, largest radius and jumps, and the hysteresis between the branches.

use std::fmt::Write as _;

use rotor_rub::Method;
use rotor_rub::variable_speed::{Jump, VariableSpeedOptions};

use super::analysis::{Branch, largest_difference};
use crate::options::describe;

/// The report's lines about the run (the caller adds the files').
pub fn summary(speed: &str, options: &VariableSpeedOptions, [up, down]: [&Branch; 2]) -> String {
    let mut report = String::new();
    let _ = writeln!(report, "speed: {}", speed);
    let _ = writeln!(
        report,
        "method: {}{}",
        describe(&options.options),
        if options.options.method == Method::Analytic {
            format!(
                ", speed held over {} steps per forcing period",
                options.speed_holds
            )
        } else {
            String::new()
        }
    );
    for branch in [up, down] {
        summarize(&mut report, branch);
    }
    let size = |j: &&Jump| (j.after - j.before).abs();
    let falls = up
        .jumps
        .iter()
        .filter(|j| j.after < j.before)
        .max_by(|a, b| size(a).total_cmp(&size(b)));
    let rises = down
        .jumps
        .iter()
        .filter(|j| j.after > j.before)
        .max_by(|a, b| size(a).total_cmp(&size(b)));
    if let (Some(fall), Some(rise)) = (falls, rises) {
        let _ = writeln!(
            report,
            "hysteresis loop: from η = {:.4} (the coast-down jumps up) to η = {:.4} (the run-up jumps down)",
            rise.speed_ratio, fall.speed_ratio
        );
    }
    if let Some((speed, a, b)) = largest_difference(up, down) {
        let _ = writeln!(
            report,
            "hysteresis: largest difference of the largest radius, run-up {} vs coast-down {} clearances at η = {:.4}",
            short(a),
            short(b),
            speed
        );
    }
    report
}

/// A radius for the report: four significant digits.
fn short(x: f64) -> String {
    format!("{x:.4}")
}

/// One branch's lines of the report.
fn summarize(report: &mut String, branch: &Branch) {
    if branch.rows.is_empty() {
        return;
    }
    let (first, last) = (
        branch.rows.first().map_or(0.0, |r| r.speed_ratio),
        branch.rows.last().map_or(0.0, |r| r.speed_ratio),
    );
    let peak = branch
        .rows
        .iter()
        .max_by(|a, b| a.max_radius.total_cmp(&b.max_radius));
    let _ = write!(
        report,
        "{}: η {:.3} -> {:.3} over {} forcing periods, rubbing in {:.0} % of them",
        branch.label(),
        first,
        last,
        branch.rows.len(),
        100.0 * branch.rubbing_fraction()
    );
    if let Some(p) = peak {
        let _ = write!(
            report,
            ", largest radius {} at η = {:.4}",
            short(p.max_radius),
            p.speed_ratio
        );
    }
    report.push('\n');
    if branch.jumps.is_empty() {
        let _ = writeln!(report, "  no jump");
    }
    for j in &branch.jumps {
        let _ = writeln!(
            report,
            "  jump at η = {:.4}: largest radius {} -> {}",
            j.speed_ratio,
            short(j.before),
            short(j.after)
        );
    }
}
