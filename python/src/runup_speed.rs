//! The speed program of a Python run-up: a run-up program or a rotor preset by name, the ramp
//! options over the program's ramp, or a profile (a CSV file, read by the CLI's reader, or an
//! array of (τ, η) rows) — refused with a message naming the keyword where they conflict.

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use rotor_rub::params::Number;
use rotor_rub::speed::{RunupPreset, SpeedPoint, SpeedProfile};
use rotor_rub_cli::problem::parse_preset;
use rotor_rub_cli::runup::program::{Program, SpeedArgs};

use crate::args::{self, flag};
use crate::errors::{cli, input};
use crate::inputs;

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// The ramp keywords of a call, as given.
pub struct Ramp<'a, 'py> {
    pub from_speed: Any<'a, 'py>,
    pub to_speed: Any<'a, 'py>,
    pub rate: Any<'a, 'py>,
    pub ramp_periods: Any<'a, 'py>,
    pub settle: Any<'a, 'py>,
    pub dwell: Any<'a, 'py>,
    pub one_way: Any<'a, 'py>,
}

/// The run-up program and the rotor preset `preset` names: a program (its rotor), or a rotor
/// preset (with the default program's ramp).
pub fn programs(preset: Option<&str>) -> PyResult<(RunupPreset, Option<rotor_rub::Preset>)> {
    let default = RunupPreset::PaperHysteresis;
    match preset {
        None => Ok((default, None)),
        Some(name) => match RunupPreset::from_name(name) {
            Some(program) => Ok((program, None)),
            None => parse_preset(name).map(|p| (default, Some(p))).map_err(|_| {
                input(format!(
                    "unknown preset '{}': expected a run-up program ({}) or a rotor preset ({})",
                    name.escape_debug(),
                    RunupPreset::ALL.map(RunupPreset::name).join(", "),
                    rotor_rub::Preset::ALL
                        .map(rotor_rub::Preset::name)
                        .join(", ")
                ))
            }),
        },
    }
}

/// A profile given as an (n, 2) array of (τ, η) rows, validated (errors name the row).
fn profile_points(points: &PyReadonlyArray2<'_, f64>) -> PyResult<Program> {
    let shape = points.shape();
    if shape.get(1) != Some(&2) {
        return Err(input(format!(
            "profile: an array of {} columns, expected 2 (time, speed_ratio)",
            shape.get(1).copied().unwrap_or(0)
        )));
    }
    let array = points.as_array();
    let list: Vec<SpeedPoint> = array
        .rows()
        .into_iter()
        .map(|r| SpeedPoint::new(r[0], r[1]))
        .collect();
    if let Err(e) = SpeedProfile::new(&list) {
        return Err(input(match e.index() {
            Some(i) => format!("profile row {i}: {e}"),
            None => format!("profile: {e}"),
        }));
    }
    let description = format!(
        "speed profile ({} points, τ {} to {})",
        list.len(),
        Number(list.first().map_or(0.0, |p| p.time)),
        Number(list.last().map_or(0.0, |p| p.time))
    );
    Ok(Program {
        points: list,
        description,
    })
}

/// The speed program: `profile` (an array) or `profile_path` (a CSV file), else the program's
/// ramp with the ramp keywords applied.
pub fn speed_program(
    program: RunupPreset,
    ramp: &Ramp<'_, '_>,
    profile: Option<&PyReadonlyArray2<'_, f64>>,
    profile_path: Option<String>,
) -> PyResult<Program> {
    let given = |v: Any<'_, '_>| v.is_some_and(|v| !v.is_none());
    let options = [
        ("from_speed", ramp.from_speed),
        ("to_speed", ramp.to_speed),
        ("rate", ramp.rate),
        ("ramp_periods", ramp.ramp_periods),
        ("settle", ramp.settle),
        ("dwell", ramp.dwell),
        ("one_way", ramp.one_way),
    ];
    let with_profile = profile.is_some() || profile_path.is_some();
    if let Some((name, _)) = options.iter().find(|(_, v)| with_profile && given(*v)) {
        return Err(input(format!(
            "{name}: a ramp option, not taken with a profile"
        )));
    }
    if given(ramp.rate) && given(ramp.ramp_periods) {
        return Err(input(
            "give rate or ramp_periods, not both (they both set the ramp's pace)",
        ));
    }
    if let Some(points) = profile {
        return profile_points(points);
    }
    let number = |name: &str, v: Any<'_, '_>| args::real_opt(name, v);
    let one_way = ramp
        .one_way
        .filter(|o| !o.is_none())
        .map(|o| flag("one_way", o))
        .transpose()?;
    let speed = SpeedArgs {
        from: number("from_speed", ramp.from_speed)?,
        to: number("to_speed", ramp.to_speed)?,
        rate: number("rate", ramp.rate)?,
        ramp_periods: number("ramp_periods", ramp.ramp_periods)?,
        settle: number("settle", ramp.settle)?,
        dwell: number("dwell", ramp.dwell)?,
        one_way: one_way.unwrap_or(false),
        profile: inputs::path(profile_path),
    };
    speed.program(program).map_err(cli)
}
