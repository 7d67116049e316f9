//! The documentation inside each FMU (`documentation/index.html`, the entry point FMI 2.0.x and
//! 3.0 name): what the model is, how a step behaves, the accuracy it can and cannot give, and
//! every variable with its unit, start value and range — written from the same variable table
//! as the model description, so the two cannot disagree.

use std::fmt::Write;

use crate::description::{attributes, escape, model_name, summary};
use crate::instance::CATEGORIES;
use crate::units::Units;
use crate::variables::{self, Kind};

const BEHAVIOUR: &str = r#"
<h2>How a communication step is computed</h2>
<p>The FMU wraps the fixed-step stepper of rotor-rub: free flight is stepped with its exact closed-form map,
contact with fourth-order exponential Rosenbrock sub-steps (exprb43), and every contact switch inside a step
(enter, exit and, with friction, reverse, roll, slip) is located on the closed forms. A communication step is
covered by internal steps of at most <code>internal_step</code>, halved where the contact sub-steps' error
estimate exceeds <code>tolerance</code>, so the result does not depend on the importer's step size.
Inputs (<code>fx</code>, <code>fy</code>, the speed) are held constant over a communication step; a speed
change keeps the forcing phase continuous.</p>
<ul>
<li><b>The stator ring with mass</b>: <code>stator_mass_ratio</code> &gt; 0 (fixed) runs the ring's n = 4
model: rotor and ring move together, the contact acting on their relative displacement. Its internal steps
are the ring stepper's (the taylor method: exact free flight of both bodies, Taylor-series contact, every
switch located; no error-estimate halving), each ending at its first switch. <code>contact_stiffness</code>
and <code>stator_damping</code> are tunable; the outputs <code>xs</code>, <code>ys</code>, <code>vxs</code>,
<code>vys</code> give the ring's centre and velocity (0 for the massless ring). Left at their start values,
the ring's entries are the model's defaults whatever the SI scales.</li>
<li><b>Early return</b> (FMI 3.0, when the importer allows it): <code>fmi3DoStep</code> returns at the first
switch, with <code>earlyReturn</code> and the switch time as <code>lastSuccessfulTime</code>.</li>
<li><b>Bounded work</b>: one communication step makes at most <code>max_internal_steps</code> internal steps
(default 1e6). Reaching the cap ends the step early: an early return (FMI 3.0 with early return allowed), or
<code>Discard</code> — FMI 3.0 leaves the FMU at the step's start, FMI 2.0 at the time reached
(<code>fmi2LastSuccessfulTime</code>, from which stepping may continue). A <code>doStep</code> never blocks for
minutes, however long the step asked for.</li>
<li><b>No direct feedthrough</b>: positions, velocities, the normal force and the contact count at a
communication point do not depend on the inputs set there (they act over the next step), so a controller
closing a loop over them has no algebraic loop. <code>in_contact</code> and <code>slip_regime</code> depend on
the speed input (it re-decides the regime and the slip direction at once).</li>
<li><b>Tunable parameters</b> take effect at the next <code>doStep</code>, validated there as one set: the
order in which they were set does not matter, and a refused set (an error naming every value) changes
nothing.</li>
<li><b>State</b>: get/set FMU state and serialization (a fixed-size form with a format version and a CRC-32
checksum: a corrupted state is refused).</li>
<li><b>Errors</b>: a bad value, a wrong value reference or a call out of phase returns an error status with a
logged message naming the value and its valid range; nothing panics across the C boundary, and no
<code>doStep</code>, get or set allocates memory.</li>
</ul>
<h2>Accuracy, and its floor on chaotic motion</h2>
<p>Each contact sub-step meets <code>tolerance</code> (max norm, relative to 1 + |state|); switch times are
found to about 1e-15. Over a long run the error is the local errors carried by the motion. On a chaotic
response nearby trajectories separate like e<sup>λτ</sup>: the paper preset at speed ratio 1.5 has a largest
Lyapunov exponent λ ≈ 0.085 per unit of dimensionless time (0.037 at speed ratio 2). Measured with this FMU
at an internal step of 1e-3: runs at tolerance 1e-8 and 1e-12 differ by 1e-9 clearances at τ ≈ 90, by 1e-3 at
τ ≈ 260 and by 0.1 at τ ≈ 320 (about 80 forcing periods); runs at 1e-12 and 1e-14 part at the same times
(τ ≈ 87, 250, 310), and halving the internal step moves them by 10–30 time units. The rounding of the last bit
(1e-16) alone reaches the size of the clearance within ln(1e16)/λ ≈ 430 time units. Tightening
<code>tolerance</code> or <code>internal_step</code> therefore cannot beat this floor: past the horizon, any
two correct simulations — this FMU at two tolerances, or two importers — agree statistically (the same
attractor, orbit radii, contact fractions, spectra), not point by point. Periodic and quasi-periodic responses
have no such floor.</p>
"#;

/// The documentation page of `units`.
pub fn index_html(units: Units) -> String {
    let mut x = String::new();
    let name = model_name(units);
    let _ = writeln!(
        x,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{name}</title>"
    );
    let _ = writeln!(
        x,
        "<style>body{{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}}table{{border-collapse:collapse}}td,th{{border:1px solid #bbb;padding:2px 6px;text-align:left;vertical-align:top}}</style></head><body>"
    );
    let _ = writeln!(
        x,
        "<h1>{name} {}</h1>\n<p>{}.</p>",
        env!("CARGO_PKG_VERSION"),
        escape(summary(units))
    );
    x.push_str(match units {
        Units::Dimensionless => {
            "<p>All quantities are the model's dimensionless ones: lengths in radial clearances δ, time τ = ω<sub>n</sub>t, stiffnesses over the rotor's stiffness, forces per unit mass in clearances·ω<sub>n</sub><sup>2</sup>; the FMI 2.0 description leaves the independent variable implicit (it is τ as well). The SI variant of this FMU (<code>rotor_rub_si</code>) takes ω<sub>n</sub>, δ and M and speaks seconds, metres and newtons.</p>\n"
        }
        Units::Si => {
            "<p>Units: time in s, positions in m, velocities in m/s, forces in N, stiffnesses in N/m, the speed in rad/s (displayed in rpm). Three fixed parameters set the scales: <code>natural_frequency</code> ω<sub>n</sub> [rad/s], <code>clearance</code> δ [m] and <code>mass</code> M [kg] (rotor stiffness k = Mω<sub>n</sub><sup>2</sup>). Internally the model runs in τ = ω<sub>n</sub>t with lengths in clearances; its valid ranges, scaled, apply (a value outside is refused with the scaled range). The dimensionless variant is <code>rotor_rub</code>.</p>\n"
        }
    });
    x.push_str(BEHAVIOUR);
    let _ = writeln!(
        x,
        "<h2>Variables</h2>\n<table><tr><th>name</th><th>causality</th><th>variability</th><th>type</th><th>unit</th><th>start</th><th>min</th><th>max</th><th>description</th></tr>"
    );
    let show = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
    for v in variables::all(units) {
        let (causality, variability, _) = attributes(v.role);
        let kind = match v.kind {
            Kind::Float => "Float64",
            Kind::Int64 => "Int64",
            Kind::Int32 => "Int32",
            Kind::Bool => "Boolean",
        };
        let unit = if v.kind == Kind::Float {
            v.dimension.unit(units)
        } else {
            ""
        };
        let _ = writeln!(
            x,
            "<tr><td><code>{}</code></td><td>{causality}</td><td>{variability}</td><td>{kind}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(v.name),
            escape(unit),
            show(v.start),
            show(v.min),
            show(v.max),
            escape(v.description)
        );
    }
    let _ = writeln!(x, "</table>\n<h2>Log categories</h2>\n<ul>");
    for (category, _, text) in CATEGORIES {
        let _ = writeln!(x, "<li><code>{category}</code>: {}</li>", escape(text));
    }
    let _ = writeln!(
        x,
        "</ul>\n<p>The model, its derivations and its valid ranges: <code>docs/MODEL.md</code> of rotor-rub; the FMU's source: <code>fmu/</code>.</p>\n</body></html>"
    );
    x
}
