//! The branch file of `rotor-rub continue`: one row per point of every branch, in branch order,
//! each bifurcation located as a row of its own.

use std::path::Path;

use rotor_rub::EventKind;

use super::{BranchPoint, Continuation};
use crate::error::Result;
use crate::output::{AtomicFile, CsvOut};

/// The branch file's header: the continued parameter's value, the orbit's period (forcing
/// periods), its largest and smallest radius |q| and contact fraction, the multipliers' moduli
/// (largest first), stability and the bifurcation located there; then the branch, the state on
/// the section, the contacts per orbit and the multipliers themselves.
pub const HEADER: [&str; 25] = [
    "value",
    "period",
    "max_radius",
    "min_radius",
    "contact_fraction",
    "modulus_1",
    "modulus_2",
    "modulus_3",
    "modulus_4",
    "stable",
    "bifurcation",
    "branch",
    "x",
    "y",
    "vx",
    "vy",
    "contacts",
    "multiplier_1_re",
    "multiplier_1_im",
    "multiplier_2_re",
    "multiplier_2_im",
    "multiplier_3_re",
    "multiplier_3_im",
    "multiplier_4_re",
    "multiplier_4_im",
];

/// One point's fields, in [`HEADER`]'s order (floats in shortest round-trip form).
pub fn row(p: &BranchPoint) -> Vec<String> {
    let s = p.summary();
    let m = &p.solution.multipliers;
    let state = p.state();
    let mut fields = vec![
        p.value().to_string(),
        p.periods().to_string(),
        s.max_radius.to_string(),
        s.min_radius.to_string(),
        s.contact_fraction().to_string(),
    ];
    fields.extend(m.iter().map(|z| z.abs().to_string()));
    fields.push(if p.stable() { "true" } else { "false" }.to_owned());
    fields.push(p.kind.map_or("", |k| k.name()).to_owned());
    fields.push(p.branch.to_string());
    fields.extend(state.to_array().iter().map(f64::to_string));
    fields.push(s.count(EventKind::Enter).to_string());
    for z in m {
        fields.push(z.re.to_string());
        fields.push(z.im.to_string());
    }
    fields
}

/// Write the branches to `path` (a finished temporary, to be committed with the plot).
pub fn write(path: &Path, result: &Continuation) -> Result<AtomicFile> {
    let mut out = CsvOut::create(path, &HEADER)?;
    for p in &result.points {
        out.record(row(p))?;
    }
    out.finish()
}
