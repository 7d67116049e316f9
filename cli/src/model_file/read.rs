//! Reading a model file (`docs/MODEL_FILES.md`): TOML, whose matrices are inline or in an `.npz`
//! it names, or a self-contained `.npz`. Every message names the key (and, in TOML, its line),
//! the value and what is valid; unknown keys are errors, never ignored.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::npz::{Array, read_npz};
use super::spec::{
    Dense, Key, ModelError, ModelSpec, RubSpec, SpeedPoint, UnbalanceSpec, default_dof_names,
};
use crate::problem::read_capped;

/// Largest model file read: 64 MiB (an `.npz` of a 64-DOF model at hundreds of speeds).
pub const MAX_MODEL_BYTES: u64 = 64 << 20;

/// The format version this build reads (`format = 1`).
pub const FORMAT: i64 = 1;

/// Read a model file: `.npz` by its extension, TOML otherwise.
///
/// # Errors
/// A one-line message naming the file, the key, its line (TOML) and what is wrong.
pub fn load(path: &Path) -> Result<ModelSpec, String> {
    let at = |m: String| format!("{}: {m}", path.display());
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npz"))
    {
        let bytes = read_bytes(path).map_err(at)?;
        let arrays = read_npz(&bytes).map_err(at)?;
        from_npz(&arrays).map_err(at)
    } else {
        let text = read_capped(path, "model file", "TOML").map_err(at)?;
        from_toml(&text, path.parent()).map_err(at)
    }
}

/// A binary file of at most [`MAX_MODEL_BYTES`] (a regular file: a FIFO would block).
fn read_bytes(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        return Err("not a regular file (a model must be a plain .toml or .npz file)".into());
    }
    if meta.len() > MAX_MODEL_BYTES {
        return Err(format!(
            "the file has {} bytes, more than the {MAX_MODEL_BYTES} a model file may have",
            meta.len()
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(|e| format!("cannot read the file: {e}"))?
        .take(MAX_MODEL_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    Ok(bytes)
}

/// The keys of each part of a TOML model.
const TOP: &[&str] = &[
    "format",
    "name",
    "units",
    "dofs",
    "speed",
    "phase",
    "force",
    "matrices",
    "unbalance",
    "rub",
    "initial",
    "speed_dependent",
];
const MATRICES: &[&str] = &["file", "mass", "damping", "gyroscopic", "stiffness"];
const UNBALANCE: &[&str] = &["dof_x", "dof_y", "m_e", "phase"];
const RUB: &[&str] = &[
    "dof_x",
    "dof_y",
    "stator",
    "clearance",
    "contact_stiffness",
    "friction_coefficient",
    "radius",
    "offset",
];
const INITIAL: &[&str] = &["positions", "velocities"];
const SPEED_POINT: &[&str] = &["speed", "damping", "stiffness"];

type Table = toml::Table;
type Value = toml::Value;

/// A message about the value at `key` (a file key, `rub.clearance`).
fn msg(key: &str, detail: impl std::fmt::Display) -> String {
    format!("{key}{detail}")
}

fn unknown(table: &Table, allowed: &[&str], section: &str) -> Result<(), String> {
    for key in table.keys() {
        if !allowed.contains(&key.as_str()) {
            let name = if section.is_empty() {
                key.clone()
            } else {
                format!("{section}.{key}")
            };
            return Err(format!(
                "unknown key {}: {} takes {}",
                name.escape_debug(),
                if section.is_empty() {
                    "a model file"
                } else {
                    section
                },
                allowed.join(", ")
            ));
        }
    }
    Ok(())
}

fn kind(v: &Value) -> String {
    match v {
        Value::String(s) => format!("the string \"{}\"", s.escape_debug()),
        other => format!("the {} {other}", other.type_str()),
    }
}

fn number(key: &str, v: &Value) -> Result<f64, String> {
    match v {
        Value::Float(x) => Ok(*x),
        #[allow(clippy::cast_precision_loss)]
        Value::Integer(i) => Ok(*i as f64),
        other => Err(msg(key, format!(" must be a number, not {}", kind(other)))),
    }
}

fn table<'a>(key: &str, v: &'a Value) -> Result<&'a Table, String> {
    v.as_table()
        .ok_or_else(|| msg(key, format!(" must be a table, not {}", kind(v))))
}

fn array<'a>(key: &str, v: &'a Value, what: &str) -> Result<&'a Vec<Value>, String> {
    v.as_array()
        .ok_or_else(|| msg(key, format!(" must be {what}, not {}", kind(v))))
}

fn vector(key: &str, v: &Value) -> Result<Vec<f64>, String> {
    array(key, v, "an array of numbers")?
        .iter()
        .enumerate()
        .map(|(i, x)| number(&format!("{key}[{i}]"), x))
        .collect()
}

/// A matrix: an array of rows, each an array of numbers, all of one length.
fn matrix(key: &str, v: &Value) -> Result<Dense, String> {
    let rows = array(key, v, "an array of rows (arrays of numbers)")?;
    let mut data = Vec::new();
    let mut cols = None;
    for (i, row) in rows.iter().enumerate() {
        let row = vector(&format!("{key}[{i}]"), row)?;
        match cols {
            None => cols = Some(row.len()),
            Some(c) if c != row.len() => {
                return Err(msg(
                    key,
                    format!(
                        "[{i}] has {} entries where row 0 has {c}: every row must have the same length",
                        row.len()
                    ),
                ));
            }
            Some(_) => {}
        }
        data.extend(row);
    }
    Ok(Dense {
        rows: rows.len(),
        cols: cols.unwrap_or(0),
        data,
    })
}

/// A degree of freedom: its index (from 0) or its name in `dofs`.
fn dof(key: &str, v: &Value, names: &[String]) -> Result<usize, String> {
    match v {
        Value::Integer(i) => usize::try_from(*i).map_err(|_| {
            msg(
                key,
                format!(" = {i} is not a degree of freedom: an index must be ≥ 0"),
            )
        }),
        Value::String(s) => names.iter().position(|n| n == s).ok_or_else(|| {
            msg(
                key,
                format!(
                    " = \"{}\" names no degree of freedom: `dofs` has {}",
                    s.escape_debug(),
                    if names.is_empty() {
                        "no names (give indices from 0, or list the names in `dofs`)".into()
                    } else {
                        names.join(", ")
                    }
                ),
            )
        }),
        other => Err(msg(
            key,
            format!(
                " must be a degree of freedom (an index from 0 or a name from `dofs`), not {}",
                kind(other)
            ),
        )),
    }
}

/// A 2 × 2 stiffness: a number k (k·I) or [[kxx, kxy], [kyx, kyy]].
fn stiffness_2x2(key: &str, v: &Value) -> Result<[[f64; 2]; 2], String> {
    if let Ok(k) = number(key, v) {
        return Ok([[k, 0.0], [0.0, k]]);
    }
    let m = matrix(key, v).map_err(|_| {
        msg(
            key,
            format!(
                " must be a number (N/m) or a 2 × 2 matrix [[kxx, kxy], [kyx, kyy]], not {}",
                kind(v)
            ),
        )
    })?;
    if m.rows != 2 || m.cols != 2 {
        return Err(msg(
            key,
            format!(" is {} × {}; it must be 2 × 2 or a number", m.rows, m.cols),
        ));
    }
    Ok([[m.get(0, 0), m.get(0, 1)], [m.get(1, 0), m.get(1, 1)]])
}

/// A pair of numbers [x, y].
fn pair(key: &str, v: &Value) -> Result<(f64, f64), String> {
    let p = vector(key, v)?;
    match p.as_slice() {
        [x, y] => Ok((*x, *y)),
        _ => Err(msg(
            key,
            format!(" has {} entries; it must be a pair [x, y]", p.len()),
        )),
    }
}

fn required<'a>(t: &'a Table, section: &str, key: &str, what: &str) -> Result<&'a Value, String> {
    t.get(key).ok_or_else(|| {
        let name = if section.is_empty() {
            key.to_string()
        } else {
            format!("{section}.{key}")
        };
        format!("{name} is missing: {what}")
    })
}

/// A TOML model's text → its statement. `dir` resolves a relative `matrices.file`.
///
/// # Errors
/// A one-line message: the TOML's syntax (with its line), or the key, its line, the value and
/// what is valid.
pub fn from_toml(text: &str, dir: Option<&Path>) -> Result<ModelSpec, String> {
    let top: Table = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| {
            text.get(..s.start.min(text.len()))
                .unwrap_or("")
                .matches('\n')
                .count()
                + 1
        });
        let at = line.map(|l| format!(" (line {l})")).unwrap_or_default();
        format!("not valid TOML{at}: {}", e.message().trim())
    })?;
    let spec = parse(&top, dir).map_err(|e| with_line(text, e))?;
    spec.check().map_err(|e| with_line(text, e.to_string()))?;
    Ok(spec)
}

/// `message` (starting with a file key) led by the line where that key is set, when found.
fn with_line(text: &str, message: String) -> String {
    let key: String = message
        .chars()
        .take_while(|c| c.is_alphanumeric() || matches!(c, '_' | '.' | '[' | ']'))
        .collect();
    match locate(text, &key) {
        Some(line) => format!("line {line}: {message}"),
        None => message,
    }
}

/// The line (from 1) where the file key `key` (`rub.clearance`, `unbalance[1].m_e`, `speed`,
/// `matrices.mass[2][0]`) is set, for keys written as `[section]` / `[[section]]` and `field =`.
pub fn locate(text: &str, key: &str) -> Option<usize> {
    let (section, occurrence, field) = match key.split_once('.') {
        None => ("", 0, key),
        Some((head, field)) => match head.split_once('[') {
            Some((name, rest)) => (name, rest.trim_end_matches(']').parse().ok()?, field),
            None => (head, 0, field),
        },
    };
    let field = field.split('[').next().unwrap_or(field);
    let mut current = ("", 0usize);
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for (i, line) in text.split('\n').enumerate() {
        let trimmed = line.trim();
        if let Some(name) = trimmed
            .strip_prefix("[[")
            .and_then(|l| l.split("]]").next())
        {
            let name = name.trim();
            let count = seen.entry(name.to_string()).or_insert(0);
            current = (section_static(name, section), *count);
            *count += 1;
            if !section.is_empty() && name == section && field.is_empty() {
                return Some(i + 1);
            }
            continue;
        }
        if let Some(name) = trimmed.strip_prefix('[').and_then(|l| l.split(']').next()) {
            current = (section_static(name.trim(), section), 0);
            continue;
        }
        let in_section = if section.is_empty() {
            current.0.is_empty()
        } else {
            current.0 == section && current.1 == occurrence
        };
        if in_section
            && let Some((left, _)) = trimmed.split_once('=')
            && left.trim().trim_matches(['"', '\'']) == field
        {
            return Some(i + 1);
        }
    }
    None
}

/// `name` when it is the sought section (so the borrow is the key's), else a marker.
fn section_static<'a>(name: &str, sought: &'a str) -> &'a str {
    if name == sought { sought } else { "\u{0}other" }
}

fn parse(top: &Table, dir: Option<&Path>) -> Result<ModelSpec, String> {
    unknown(top, TOP, "")?;
    if let Some(v) = top.get("format") {
        match v {
            Value::Integer(FORMAT) => {}
            other => {
                return Err(format!(
                    "format = {other} is not a format this build reads: it reads format = {FORMAT}"
                ));
            }
        }
    }
    if let Some(v) = top.get("units")
        && v.as_str() != Some("SI")
    {
        return Err(format!(
            "units = {v} is not supported: model files are in SI units (units = \"SI\": m, kg, s, N, rad)"
        ));
    }
    let name = match top.get("name") {
        None => String::new(),
        Some(Value::String(s)) => s.clone(),
        Some(other) => return Err(format!("name must be a string, not {}", kind(other))),
    };
    let matrices = table(
        "matrices",
        required(
            top,
            "",
            "matrices",
            "the [matrices] table (mass and stiffness at least)",
        )?,
    )?;
    unknown(matrices, MATRICES, "matrices")?;
    let from_file = match matrices.get("file") {
        None => None,
        Some(Value::String(f)) => Some(matrices_file(f, dir)?),
        Some(other) => {
            return Err(format!(
                "matrices.file must be a string (an .npz path, relative to the model file), not {}",
                kind(other)
            ));
        }
    };
    let pick = |key: &str, short: &str, required_here: bool| -> Result<Option<Dense>, String> {
        let inline = matrices.get(key);
        let filed = from_file.as_ref().and_then(|f| f.get(short));
        match (inline, filed) {
            (Some(_), Some(_)) => Err(format!(
                "matrices.{key} is given twice: inline and as array '{short}' in matrices.file (keep one)"
            )),
            (Some(v), None) => matrix(&format!("matrices.{key}"), v).map(Some),
            (None, Some(a)) => dense_of(&format!("matrices.file array '{short}'"), a).map(Some),
            (None, None) if required_here => Err(format!(
                "matrices.{key} is missing (inline, or as array '{short}' in matrices.file)"
            )),
            (None, None) => Ok(None),
        }
    };
    let mass = pick("mass", "M", true)?.unwrap_or_else(|| Dense::zeros(0, 0));
    let n = mass.rows;
    let stiffness = pick("stiffness", "K", true)?.unwrap_or_else(|| Dense::zeros(n, n));
    let damping = pick("damping", "C", false)?.unwrap_or_else(|| Dense::zeros(n, n));
    let gyroscopic = pick("gyroscopic", "G", false)?.unwrap_or_else(|| Dense::zeros(n, n));
    let dofs = match top.get("dofs") {
        None => default_dof_names(n),
        Some(v) => array("dofs", v, "an array of names")?
            .iter()
            .enumerate()
            .map(|(i, d)| {
                d.as_str()
                    .map(str::to_string)
                    .ok_or_else(|| format!("dofs[{i}] must be a name (a string), not {}", kind(d)))
            })
            .collect::<Result<_, _>>()?,
    };
    let names: &[String] = if top.contains_key("dofs") { &dofs } else { &[] };
    let speed = number(
        "speed",
        required(top, "", "speed", "the running speed Ω in rad/s")?,
    )?;
    let phase = top.get("phase").map_or(Ok(0.0), |v| number("phase", v))?;
    let force = top
        .get("force")
        .map_or(Ok(Vec::new()), |v| vector("force", v))?;
    let unbalances = match top.get("unbalance") {
        None => Vec::new(),
        Some(v) => array("unbalance", v, "an array of tables ([[unbalance]])")?
            .iter()
            .enumerate()
            .map(|(i, u)| unbalance(i, u, names))
            .collect::<Result<_, _>>()?,
    };
    let rub = rub(
        required(
            top,
            "",
            "rub",
            "the [rub] table: where the rotor rubs and how",
        )?,
        names,
    )?;
    let initial = match top.get("initial") {
        None => None,
        Some(v) => {
            let t = table("initial", v)?;
            unknown(t, INITIAL, "initial")?;
            let zeros = || vec![0.0; n];
            let q = t
                .get("positions")
                .map_or(Ok(zeros()), |v| vector("initial.positions", v))?;
            let dq = t
                .get("velocities")
                .map_or(Ok(zeros()), |v| vector("initial.velocities", v))?;
            Some((q, dq))
        }
    };
    let mut speed_dependent = match top.get("speed_dependent") {
        None => Vec::new(),
        Some(v) => array(
            "speed_dependent",
            v,
            "an array of tables ([[speed_dependent]])",
        )?
        .iter()
        .enumerate()
        .map(|(i, p)| speed_point(i, p))
        .collect::<Result<_, _>>()?,
    };
    if let Some(file) = &from_file {
        let filed = speed_points_of(file)?;
        if !filed.is_empty() && !speed_dependent.is_empty() {
            return Err(
                "speed_dependent is given twice: as [[speed_dependent]] and as arrays speeds, C_speeds, K_speeds in matrices.file (keep one)".into(),
            );
        }
        if speed_dependent.is_empty() {
            speed_dependent = filed;
        }
    }
    Ok(ModelSpec {
        name,
        dofs,
        mass,
        damping,
        gyroscopic,
        stiffness,
        speed,
        phase,
        unbalances,
        force,
        rub,
        initial,
        speed_dependent,
    })
}

fn matrices_file(name: &str, dir: Option<&Path>) -> Result<BTreeMap<String, Array>, String> {
    let path = match dir {
        Some(d) if !Path::new(name).is_absolute() => d.join(name),
        _ => PathBuf::from(name),
    };
    let fail = |e: String| format!("matrices.file = \"{}\": {e}", name.escape_debug());
    let bytes = read_bytes(&path).map_err(fail)?;
    read_npz(&bytes).map_err(fail)
}

fn unbalance(i: usize, v: &Value, names: &[String]) -> Result<UnbalanceSpec, String> {
    let section = format!("unbalance[{i}]");
    let t = table(&section, v)?;
    unknown(t, UNBALANCE, &section)?;
    let get = |k: &str, what: &str| required(t, &section, k, what);
    Ok(UnbalanceSpec {
        dof_x: dof(
            &format!("{section}.dof_x"),
            get("dof_x", "the DOF of its x force")?,
            names,
        )?,
        dof_y: dof(
            &format!("{section}.dof_y"),
            get("dof_y", "the DOF of its y force")?,
            names,
        )?,
        m_e: number(
            &format!("{section}.m_e"),
            get("m_e", "mass times eccentricity, kg·m")?,
        )?,
        phase: t
            .get("phase")
            .map_or(Ok(0.0), |v| number(&format!("{section}.phase"), v))?,
    })
}

fn rub(v: &Value, names: &[String]) -> Result<RubSpec, String> {
    let t = table("rub", v)?;
    unknown(t, RUB, "rub")?;
    let get = |k: &str, what: &str| required(t, "rub", k, what);
    let stator = match t.get("stator") {
        None => None,
        Some(v) => {
            let pair = array("rub.stator", v, "a pair of DOFs [x, y]")?;
            match pair.as_slice() {
                [x, y] => Some((
                    dof("rub.stator[0]", x, names)?,
                    dof("rub.stator[1]", y, names)?,
                )),
                other => {
                    return Err(format!(
                        "rub.stator has {} entries; it must be a pair of DOFs [x, y] (or be left out for a fixed stator)",
                        other.len()
                    ));
                }
            }
        }
    };
    Ok(RubSpec {
        dof_x: dof("rub.dof_x", get("dof_x", "the rotor point's x DOF")?, names)?,
        dof_y: dof("rub.dof_y", get("dof_y", "the rotor point's y DOF")?, names)?,
        stator,
        clearance: number(
            "rub.clearance",
            get("clearance", "the radial clearance δ, m")?,
        )?,
        contact_stiffness: stiffness_2x2(
            "rub.contact_stiffness",
            get(
                "contact_stiffness",
                "K_c, N/m: a number or [[kxx, kxy], [kyx, kyy]]",
            )?,
        )?,
        friction_coefficient: t
            .get("friction_coefficient")
            .map_or(Ok(0.0), |v| number("rub.friction_coefficient", v))?,
        radius: t
            .get("radius")
            .map(|v| number("rub.radius", v))
            .transpose()?,
        offset: t
            .get("offset")
            .map_or(Ok((0.0, 0.0)), |v| pair("rub.offset", v))?,
    })
}

fn speed_point(i: usize, v: &Value) -> Result<SpeedPoint, String> {
    let section = format!("speed_dependent[{i}]");
    let t = table(&section, v)?;
    unknown(t, SPEED_POINT, &section)?;
    Ok(SpeedPoint {
        speed: number(
            &format!("{section}.speed"),
            required(t, &section, "speed", "the speed Ω of this point, rad/s")?,
        )?,
        damping: t
            .get("damping")
            .map(|v| matrix(&format!("{section}.damping"), v))
            .transpose()?,
        stiffness: t
            .get("stiffness")
            .map(|v| matrix(&format!("{section}.stiffness"), v))
            .transpose()?,
    })
}

/// An `.npz` array as a matrix (2-d).
fn dense_of(what: &str, a: &Array) -> Result<Dense, String> {
    match a {
        Array::Numbers { shape, data } if shape.len() == 2 => Ok(Dense {
            rows: shape[0],
            cols: shape[1],
            data: data.clone(),
        }),
        Array::Numbers { .. } => Err(format!(
            "{what} has shape {}; it must be a matrix (2-d)",
            a.shape_text()
        )),
        Array::Strings { .. } => Err(format!("{what} holds strings; it must hold numbers")),
    }
}

fn numbers_of<'a>(what: &str, a: &'a Array) -> Result<(&'a [usize], &'a [f64]), String> {
    match a {
        Array::Numbers { shape, data } => Ok((shape, data)),
        Array::Strings { .. } => Err(format!("{what} holds strings; it must hold numbers")),
    }
}

/// The arrays `speeds` (k,), `C_speeds` and `K_speeds` (k, n, n) as speed points.
fn speed_points_of(arrays: &BTreeMap<String, Array>) -> Result<Vec<SpeedPoint>, String> {
    let Some(speeds) = arrays.get("speeds") else {
        for other in ["C_speeds", "K_speeds"] {
            if arrays.contains_key(other) {
                return Err(format!(
                    "array '{other}' needs the array 'speeds' (the speeds its matrices are at, rad/s)"
                ));
            }
        }
        return Ok(Vec::new());
    };
    let (shape, speeds) = numbers_of("array 'speeds'", speeds)?;
    if shape.len() != 1 {
        return Err(format!(
            "array 'speeds' has shape {}; it must be 1-d (k,)",
            arrays
                .get("speeds")
                .map_or(String::new(), Array::shape_text)
        ));
    }
    let k = speeds.len();
    let stack = |name: &str| -> Result<Option<Vec<Dense>>, String> {
        let Some(a) = arrays.get(name) else {
            return Ok(None);
        };
        let what = format!("array '{name}'");
        let (shape, data) = numbers_of(&what, a)?;
        match shape {
            [kk, r, c] if *kk == k => Ok(Some(
                (0..k)
                    .map(|i| Dense {
                        rows: *r,
                        cols: *c,
                        data: data.get(i * r * c..(i + 1) * r * c).unwrap_or(&[]).to_vec(),
                    })
                    .collect(),
            )),
            _ => Err(format!(
                "{what} has shape {}; it must be (k, n, n) with k = {k} (one matrix per entry of 'speeds')",
                a.shape_text()
            )),
        }
    };
    let c = stack("C_speeds")?;
    let kk = stack("K_speeds")?;
    if c.is_none() && kk.is_none() {
        return Err("array 'speeds' needs 'C_speeds' or 'K_speeds' (k, n, n)".into());
    }
    Ok((0..k)
        .map(|i| SpeedPoint {
            speed: speeds.get(i).copied().unwrap_or(f64::NAN),
            damping: c.as_ref().and_then(|c| c.get(i).cloned()),
            stiffness: kk.as_ref().and_then(|k| k.get(i).cloned()),
        })
        .collect())
}

/// The arrays of a self-contained `.npz` model.
pub const NPZ_KEYS: &[&str] = &[
    "M",
    "C",
    "G",
    "K",
    "dofs",
    "speed",
    "phase",
    "unbalance",
    "force",
    "rub",
    "clearance",
    "contact_stiffness",
    "friction_coefficient",
    "radius",
    "offset",
    "initial",
    "speeds",
    "C_speeds",
    "K_speeds",
];

/// A self-contained `.npz` model (`docs/MODEL_FILES.md`, "A model in one .npz").
///
/// # Errors
/// A message naming the array and what is wrong.
pub fn from_npz(arrays: &BTreeMap<String, Array>) -> Result<ModelSpec, String> {
    if let Some(extra) = arrays.keys().find(|k| !NPZ_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "unknown array '{}': a model .npz holds {}",
            extra.escape_debug(),
            NPZ_KEYS.join(", ")
        ));
    }
    let need = |k: &str, what: &str| {
        arrays
            .get(k)
            .ok_or_else(|| format!("array '{k}' is missing: {what}"))
    };
    let scalar = |k: &str, default: Option<f64>, what: &str| -> Result<f64, String> {
        match arrays.get(k) {
            None => default.ok_or_else(|| format!("array '{k}' is missing: {what}")),
            Some(a) => match numbers_of(&format!("array '{k}'"), a)? {
                (shape, [x]) if shape.iter().all(|&d| d == 1) => Ok(*x),
                _ => Err(format!(
                    "array '{k}' has shape {}; it must be a scalar ({what})",
                    a.shape_text()
                )),
            },
        }
    };
    let flat = |k: &str| -> Result<Option<Vec<f64>>, String> {
        arrays
            .get(k)
            .map(|a| numbers_of(&format!("array '{k}'"), a).map(|(_, d)| d.to_vec()))
            .transpose()
    };
    let index = |k: &str, x: f64| -> Result<usize, String> {
        if x >= 0.0 && x.fract() == 0.0 && x < 1e9 {
            Ok(x as usize)
        } else {
            Err(format!(
                "array '{k}' holds {x}, which is not a DOF index (an integer ≥ 0)"
            ))
        }
    };
    let mass = dense_of("array 'M'", need("M", "the mass matrix (n, n), kg")?)?;
    let n = mass.rows;
    let stiffness = dense_of("array 'K'", need("K", "the stiffness matrix (n, n), N/m")?)?;
    let optional = |k: &str| -> Result<Dense, String> {
        arrays.get(k).map_or(Ok(Dense::zeros(n, n)), |a| {
            dense_of(&format!("array '{k}'"), a)
        })
    };
    let damping = optional("C")?;
    let gyroscopic = optional("G")?;
    let dofs = match arrays.get("dofs") {
        None => default_dof_names(n),
        Some(Array::Strings { data, .. }) => data.clone(),
        Some(_) => return Err("array 'dofs' must hold strings (the DOFs' names)".into()),
    };
    let unbalances = match flat("unbalance")? {
        None => Vec::new(),
        Some(u) if u.len() % 4 == 0 => u
            .chunks(4)
            .map(|c| {
                Ok(UnbalanceSpec {
                    dof_x: index("unbalance", c[0])?,
                    dof_y: index("unbalance", c[1])?,
                    m_e: c[2],
                    phase: c[3],
                })
            })
            .collect::<Result<_, String>>()?,
        Some(u) => {
            return Err(format!(
                "array 'unbalance' has {} entries; it must be (k, 4): rows dof_x, dof_y, m_e (kg·m), phase (rad)",
                u.len()
            ));
        }
    };
    let rub_dofs = flat("rub")?.ok_or_else(|| {
        "array 'rub' is missing: the rub station's DOFs [dof_x, dof_y] or [dof_x, dof_y, stator_x, stator_y]".to_string()
    })?;
    let (dof_x, dof_y, stator) = match rub_dofs.as_slice() {
        [x, y] => (index("rub", *x)?, index("rub", *y)?, None),
        [x, y, sx, sy] => (
            index("rub", *x)?,
            index("rub", *y)?,
            Some((index("rub", *sx)?, index("rub", *sy)?)),
        ),
        other => {
            return Err(format!(
                "array 'rub' has {} entries; it must be [dof_x, dof_y] or [dof_x, dof_y, stator_x, stator_y]",
                other.len()
            ));
        }
    };
    let contact_stiffness = match flat("contact_stiffness")? {
        Some(k) if k.len() == 1 => [[k[0], 0.0], [0.0, k[0]]],
        Some(k) if k.len() == 4 => [[k[0], k[1]], [k[2], k[3]]],
        Some(_) => {
            return Err("array 'contact_stiffness' must be a scalar or 2 × 2 (N/m)".into());
        }
        None => {
            return Err(
                "array 'contact_stiffness' is missing: K_c in N/m (a scalar or 2 × 2)".into(),
            );
        }
    };
    let offset = match flat("offset")? {
        None => (0.0, 0.0),
        Some(o) if o.len() == 2 => (o[0], o[1]),
        Some(o) => {
            return Err(format!(
                "array 'offset' has {} entries; it must be a pair (x, y), m",
                o.len()
            ));
        }
    };
    let initial = match flat("initial")? {
        None => None,
        Some(y) if y.len() == 2 * n => Some((y[..n].to_vec(), y[n..].to_vec())),
        Some(y) => {
            return Err(format!(
                "array 'initial' has {} entries; it must have 2n = {} (positions, m, then velocities, m/s)",
                y.len(),
                2 * n
            ));
        }
    };
    let radius = arrays
        .get("radius")
        .map(|_| scalar("radius", None, "the rotor's radius at the station, m"))
        .transpose()?;
    Ok(ModelSpec {
        name: String::new(),
        dofs,
        mass,
        damping,
        gyroscopic,
        stiffness,
        speed: scalar("speed", None, "the running speed Ω, rad/s")?,
        phase: scalar("phase", Some(0.0), "the forcing phase at t = 0, rad")?,
        unbalances,
        force: flat("force")?.unwrap_or_default(),
        rub: RubSpec {
            dof_x,
            dof_y,
            stator,
            clearance: scalar("clearance", None, "the radial clearance δ, m")?,
            contact_stiffness,
            friction_coefficient: scalar("friction_coefficient", Some(0.0), "μ")?,
            radius,
            offset,
        },
        initial,
        speed_dependent: speed_points_of(arrays)?,
    })
    .and_then(|spec: ModelSpec| {
        spec.check().map_err(|e| npz_message(&e))?;
        Ok(spec)
    })
}

/// A model error in an `.npz`'s words (its arrays, not the TOML keys).
pub fn npz_message(e: &ModelError) -> String {
    let name = match e.key {
        Key::File => "model".to_string(),
        Key::Dofs => "array 'dofs'".into(),
        Key::Mass => "array 'M'".into(),
        Key::Damping => "array 'C'".into(),
        Key::Gyroscopic => "array 'G'".into(),
        Key::Stiffness => "array 'K'".into(),
        Key::Speed => "array 'speed'".into(),
        Key::Phase => "array 'phase'".into(),
        Key::Unbalance(i, f) => format!("array 'unbalance' row {i} ({f})"),
        Key::Force => "array 'force'".into(),
        Key::Rub(f @ ("dof_x" | "dof_y" | "stator")) => format!("array 'rub' ({f})"),
        Key::Rub(f) => format!("array '{f}'"),
        Key::InitialPositions => "array 'initial' (positions)".into(),
        Key::InitialVelocities => "array 'initial' (velocities)".into(),
        Key::SpeedDependent(i, "speed") => format!("array 'speeds' [{i}]"),
        Key::SpeedDependent(i, "damping") => format!("array 'C_speeds' [{i}]"),
        Key::SpeedDependent(i, f) => format!("array 'K_speeds' [{i}] ({f})"),
    };
    e.message_with(&name)
}
