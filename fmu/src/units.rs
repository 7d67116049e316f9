//! The FMU's two unit systems, served by one binary: the model's own dimensionless quantities
//! (the paper's: lengths in clearances, time τ = ω_n t, stiffnesses over the rotor's) and SI
//! units for a rig (seconds, metres, newtons, kilograms, rad/s). The importer picks one by the
//! FMU it loads: `rotor_rub_fmi3.fmu` (dimensionless) or `rotor_rub_si_fmi3.fmu` (SI), each with
//! its own model description and instantiation token (`description.rs`).
//!
//! An SI value is the dimensionless one times a factor built from three scales — the natural
//! frequency ω_n (rad/s), the radial clearance δ (m) and the rotor mass M (kg)
//! ([`Scales::factor`]): lengths δ, velocities δ ω_n, stiffnesses M ω_n² (the rotor's
//! stiffness k = M ω_n²), forces M ω_n² δ, speeds ω_n, time 1/ω_n. The dimensionless FMU is the
//! same code with every scale 1, so its numbers pass through unchanged, bit for bit.

/// Which unit system an FMU instance speaks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// The model's dimensionless quantities (unit "1").
    Dimensionless,
    /// SI units, scaled by ω_n, δ and M.
    Si,
}

/// What a variable measures: its unit in each system and its factor from the scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// A pure number (ratios, coefficients, flags, counts).
    One,
    /// An angle, rad.
    Angle,
    /// A length, m (clearances in the dimensionless FMU).
    Length,
    /// A velocity, m/s.
    Velocity,
    /// A stiffness, N/m (over the rotor's stiffness M ω_n² in the dimensionless FMU).
    Stiffness,
    /// A force, N (per unit mass, in clearances·ω_n², in the dimensionless FMU).
    Force,
    /// An angular speed, rad/s (over ω_n in the dimensionless FMU).
    AngularSpeed,
    /// A time, s (τ = ω_n t in the dimensionless FMU).
    Time,
    /// A mass, kg.
    Mass,
    /// A viscous damping coefficient, N·s/m (over M ω_n in the dimensionless FMU).
    Damping,
}

impl Dimension {
    /// The unit's name in `units` ("1" for every quantity of the dimensionless FMU).
    pub fn unit(self, units: Units) -> &'static str {
        match (units, self) {
            (Units::Dimensionless, _) | (Units::Si, Dimension::One) => "1",
            (Units::Si, Dimension::Angle) => "rad",
            (Units::Si, Dimension::Length) => "m",
            (Units::Si, Dimension::Velocity) => "m/s",
            (Units::Si, Dimension::Stiffness) => "N/m",
            (Units::Si, Dimension::Force) => "N",
            (Units::Si, Dimension::AngularSpeed) => "rad/s",
            (Units::Si, Dimension::Time) => "s",
            (Units::Si, Dimension::Mass) => "kg",
            (Units::Si, Dimension::Damping) => "N.s/m",
        }
    }

    /// The display unit a rig engineer reads (none for the dimensionless FMU).
    pub fn display_unit(self, units: Units) -> Option<&'static str> {
        match (units, self) {
            (Units::Dimensionless, _) => None,
            (Units::Si, Dimension::Angle) => Some("deg"),
            (Units::Si, Dimension::Length) => Some("um"),
            (Units::Si, Dimension::Velocity) => Some("mm/s"),
            (Units::Si, Dimension::Stiffness) => Some("N/um"),
            (Units::Si, Dimension::AngularSpeed) => Some("rpm"),
            (Units::Si, Dimension::Time) => Some("ms"),
            (Units::Si, _) => None,
        }
    }
}

/// One unit of `<UnitDefinitions>`: its name, SI base-unit exponents (kg, m, s, rad) and
/// display units as (name, factor) with display = factor · value.
pub struct UnitDefinition {
    /// The unit's name.
    pub name: &'static str,
    /// Exponents of kg, m, s and rad.
    pub base: [(&'static str, i32); 4],
    /// Display units: (name, factor).
    pub display: &'static [(&'static str, f64)],
}

/// Degrees per radian.
const DEG: f64 = 180.0 / core::f64::consts::PI;
/// rpm per rad/s.
const RPM: f64 = 60.0 / core::f64::consts::TAU;

/// The units the SI FMU declares, with their display units.
pub const SI_UNITS: [UnitDefinition; 10] = [
    unit("1", 0, 0, 0, 0, &[]),
    unit("rad", 0, 0, 0, 1, &[("deg", DEG)]),
    unit("m", 0, 1, 0, 0, &[("mm", 1e3), ("um", 1e6)]),
    unit("m/s", 0, 1, -1, 0, &[("mm/s", 1e3)]),
    unit("N/m", 1, 0, -2, 0, &[("N/mm", 1e-3), ("N/um", 1e-6)]),
    unit("N", 1, 1, -2, 0, &[]),
    unit("rad/s", 0, 0, -1, 1, &[("rpm", RPM)]),
    unit("s", 0, 0, 1, 0, &[("ms", 1e3)]),
    unit("kg", 1, 0, 0, 0, &[]),
    unit("N.s/m", 1, 0, -1, 0, &[]),
];

const fn unit(
    name: &'static str,
    kg: i32,
    m: i32,
    s: i32,
    rad: i32,
    display: &'static [(&'static str, f64)],
) -> UnitDefinition {
    UnitDefinition {
        name,
        base: [("kg", kg), ("m", m), ("s", s), ("rad", rad)],
        display,
    }
}

/// The three scales of the SI FMU (all 1 in the dimensionless one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// ω_n, rad/s: the rotor's natural frequency √(k/M).
    pub natural_frequency: f64,
    /// δ, m: the radial clearance.
    pub clearance: f64,
    /// M, kg: the rotor (disk) mass.
    pub mass: f64,
}

/// The SI FMU's default scales: a 10 kg rotor with its first critical speed at 3000 rpm
/// (ω_n = 100π rad/s) in a clearance of 0.1 mm.
pub const SI_DEFAULT: Scales = Scales {
    natural_frequency: 100.0 * core::f64::consts::PI,
    clearance: 1e-4,
    mass: 10.0,
};

/// Valid natural frequencies, rad/s (0.01 rpm to ~1e7 rpm).
pub const NATURAL_FREQUENCY_RANGE: (f64, f64) = (1e-3, 1e6);
/// Valid clearances, m (1 nm to 10 m).
pub const CLEARANCE_RANGE: (f64, f64) = (1e-9, 10.0);
/// Valid masses, kg (1 mg to 1e9 kg).
pub const MASS_RANGE: (f64, f64) = (1e-6, 1e9);

impl Scales {
    /// Every scale 1: the dimensionless FMU.
    pub const ONE: Scales = Scales {
        natural_frequency: 1.0,
        clearance: 1.0,
        mass: 1.0,
    };

    /// The factor from a dimensionless value to the unit system's: value = factor · model
    /// value (time: τ = ω_n t, so its factor is 1/ω_n, applied as a division: see
    /// [`Scales::to_importer`]).
    pub fn factor(&self, d: Dimension) -> f64 {
        let (w, delta, m) = (self.natural_frequency, self.clearance, self.mass);
        match d {
            Dimension::One | Dimension::Angle => 1.0,
            Dimension::Length => delta,
            Dimension::Velocity => delta * w,
            Dimension::Stiffness => m * w * w,
            Dimension::Force => m * w * w * delta,
            Dimension::AngularSpeed => w,
            Dimension::Time => 1.0 / w,
            Dimension::Mass => m,
            Dimension::Damping => m * w,
        }
    }

    /// A model (dimensionless) value in the importer's units.
    pub fn to_importer(&self, d: Dimension, value: f64) -> f64 {
        match d {
            Dimension::Time => value / self.natural_frequency,
            _ => value * self.factor(d),
        }
    }

    /// An importer's value as the model's (dimensionless) value.
    pub fn to_model(&self, d: Dimension, value: f64) -> f64 {
        match d {
            Dimension::Time => value * self.natural_frequency,
            _ => value / self.factor(d),
        }
    }

    /// Whether each scale is finite and in its range.
    pub fn check(&self) -> Result<(), (&'static str, f64, (f64, f64))> {
        let named = [
            (
                "natural_frequency",
                self.natural_frequency,
                NATURAL_FREQUENCY_RANGE,
            ),
            ("clearance", self.clearance, CLEARANCE_RANGE),
            ("mass", self.mass, MASS_RANGE),
        ];
        for (name, value, (lo, hi)) in named {
            if !(value.is_finite() && (lo..=hi).contains(&value)) {
                return Err((name, value, (lo, hi)));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_scales_pass_values_through_unchanged() {
        let dims = [
            Dimension::One,
            Dimension::Angle,
            Dimension::Length,
            Dimension::Velocity,
            Dimension::Stiffness,
            Dimension::Force,
            Dimension::AngularSpeed,
            Dimension::Time,
            Dimension::Mass,
        ];
        for d in dims {
            for v in [0.1, -3.7, 1e-300, 12345.678] {
                assert_eq!(Scales::ONE.to_importer(d, v).to_bits(), v.to_bits());
                assert_eq!(Scales::ONE.to_model(d, v).to_bits(), v.to_bits());
            }
            let back = SI_DEFAULT.to_model(d, SI_DEFAULT.to_importer(d, 0.3));
            assert!((back - 0.3).abs() < 1e-15, "{d:?}");
        }
        // k = M ω_n²: a stiffness of the rotor's own is 1 in the model.
        let k = SI_DEFAULT.mass * SI_DEFAULT.natural_frequency.powi(2);
        assert!((SI_DEFAULT.to_model(Dimension::Stiffness, k) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn every_si_dimension_has_a_declared_unit_and_display_unit() {
        let dims = [
            Dimension::One,
            Dimension::Angle,
            Dimension::Length,
            Dimension::Velocity,
            Dimension::Stiffness,
            Dimension::Force,
            Dimension::AngularSpeed,
            Dimension::Time,
            Dimension::Mass,
        ];
        for d in dims {
            let unit = SI_UNITS
                .iter()
                .find(|u| u.name == d.unit(Units::Si))
                .unwrap_or_else(|| panic!("{d:?}: unit not declared"));
            if let Some(shown) = d.display_unit(Units::Si) {
                assert!(unit.display.iter().any(|(n, _)| *n == shown), "{d:?}");
            }
        }
    }
}
