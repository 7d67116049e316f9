//! The run-up diagram of a run: its two branches as curves, their rubbing speeds and jumps.

use rotor_rub::params::Number;

use super::analysis::Branch;
use crate::plot::LegendMark;
use crate::plot::runup::{COAST_DOWN, Curve, RUN_UP, RunupFigure};

/// The run-up diagram of the two branches.
pub fn figure(
    problem: &rotor_rub::Problem,
    speed: &str,
    method: &str,
    branches: [&Branch; 2],
) -> RunupFigure {
    let p = &problem.params;
    // Plain symbols: the embedded font has no combining circumflex.
    let title = format!(
        "Run-up and coast-down: K = ({}, {}, {}, {}), stator offset ({}, {}), ν = {}, η_m = {}, ρ = {}",
        Number(p.k_xx),
        Number(p.k_xy),
        Number(p.k_yx),
        Number(p.k_yy),
        Number(p.offset_x),
        Number(p.offset_y),
        Number(p.damping_ratio),
        Number(p.mass_ratio),
        Number(p.eccentricity_ratio)
    );
    let (curves, legend) = branch_curves(branches);
    RunupFigure {
        title,
        subtitle: format!(
            "{speed}; {method}; thick: largest radius, thin: smallest radius per forcing period"
        ),
        legend,
        curves,
        axes: None,
    }
}

/// The two branches' curves (largest and smallest radius per period, rubbing speeds, jumps) and
/// their legend: the planar run-up's and a matrix model's alike.
pub(super) fn branch_curves(branches: [&Branch; 2]) -> (Vec<Curve>, Vec<(LegendMark, String)>) {
    let mut legend = Vec::new();
    let mut curves = Vec::new();
    for (branch, color) in branches.into_iter().zip([RUN_UP, COAST_DOWN]) {
        if branch.rows.is_empty() {
            continue;
        }
        legend.push((LegendMark::Line(color), branch.label().to_string()));
        legend.push((
            LegendMark::Shade(color),
            format!("rubs ({})", branch.label()),
        ));
        curves.push(Curve {
            color,
            points: branch
                .rows
                .iter()
                .map(|r| (r.speed_ratio, r.max_radius, r.min_radius))
                .collect(),
            contact: branch.contact_intervals(),
            jumps: branch
                .jumps
                .iter()
                .map(|j| (j.speed_ratio, j.before, j.after))
                .collect(),
        });
    }
    legend.push((LegendMark::Triangle(RUN_UP), "jump".to_string()));
    (curves, legend)
}
