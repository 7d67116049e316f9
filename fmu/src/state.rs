//! Saved FMU states (rigs roll back): a state is a copy of the [`Model`]; serialized, it is a
//! fixed number of little-endian 64-bit words:
//!
//! | words | content |
//! |---|---|
//! | 1 | marker "rrfmu" and format version ([`FORMAT_VERSION`]) |
//! | 1 | length in bytes ([`BYTES`]) |
//! | 1 | unit system (0 dimensionless, 1 SI) |
//! | `Parameter::COUNT` | the values as set, in the importer's units |
//! | 9 | start time, internal step, tolerance, work cap, ω_n, δ, M, pending flag, stepper flag |
//! | `Snapshot::WORDS` | the stepper's words ([`AnyStepper::to_words`]: the planar [`Snapshot`], or the ring's stepper, told apart by their markers) |
//! | 2 | contact count, next internal step |
//! | 1 | CRC-32 (IEEE) of every byte before it |
//!
//! Read back, the checksum is verified first: a CRC-32 detects every error burst of up to 32
//! bits, so every single-byte corruption anywhere in a state is refused (the checksum word's
//! own bytes included: they no longer match). Then every value is checked as a set of it
//! would be ([`AnyStepper::from_words`] for the stepper). A ring's stepper restored from its
//! words restarts its method at the saved time and state (within its tolerance of the run it
//! continues; a saved state that is not serialized is a copy, bit for bit).

use rotor_rub::Parameter;
use rotor_rub::stepper::{AnyStepper, Snapshot};

use crate::message::Message;
use crate::model::{Model, Settings};
use crate::msg;
use crate::units::{Scales, Units};
use crate::variables;

/// The serialized form's version: 2 added the length, unit system, scales, work cap, pending
/// flag and checksum words.
pub const FORMAT_VERSION: u64 = 2;
/// "rrfmu" in the top five bytes, the version below.
const MARKER_PREFIX: u64 = 0x7272_666d_7500_0000;
const MARKER: u64 = MARKER_PREFIX | FORMAT_VERSION;
/// Words: marker, length, units, table, 9 settings and flags, snapshot, count, next step, CRC.
pub const WORDS: usize = 3 + Parameter::COUNT + 9 + Snapshot::WORDS + 2 + 1;
/// Serialized size in bytes.
pub const BYTES: usize = 8 * WORDS;

/// The model as bytes.
pub fn serialize(model: &Model) -> [u8; BYTES] {
    let st = &model.settings;
    let table = Parameter::ALL.map(|p| p.get(&model.requested).to_bits());
    let snapshot = model.stepper.as_ref().map(AnyStepper::to_words);
    let words = [
        MARKER,
        BYTES as u64,
        match model.units {
            Units::Dimensionless => 0,
            Units::Si => 1,
        },
    ]
    .into_iter()
    .chain(table)
    .chain([
        model.start_time.to_bits(),
        st.internal_step.to_bits(),
        st.tolerance.to_bits(),
        u64::from(st.max_internal_steps),
        st.scales.natural_frequency.to_bits(),
        st.scales.clearance.to_bits(),
        st.scales.mass.to_bits(),
        u64::from(model.pending),
        u64::from(snapshot.is_some()),
    ])
    .chain(snapshot.unwrap_or([0; Snapshot::WORDS]))
    .chain([model.contact_count, model.next_step.to_bits()]);
    let mut out = [0u8; BYTES];
    for (chunk, w) in out.chunks_exact_mut(8).zip(words) {
        chunk.copy_from_slice(&w.to_le_bytes());
    }
    let (body, tail) = out.split_at_mut(BYTES - 8);
    tail.copy_from_slice(&u64::from(crc32(body)).to_le_bytes());
    out
}

/// The model serialized in `bytes` for an instance of `units`, every value checked.
pub fn deserialize(bytes: &[u8], units: Units) -> Result<Model, Message> {
    if bytes.len() != BYTES {
        return Err(msg!(
            "serialized FMU state has {} bytes, expected {BYTES}",
            bytes.len()
        ));
    }
    let mut words = [0u64; WORDS];
    for (w, chunk) in words.iter_mut().zip(bytes.chunks_exact(8)) {
        let mut b = [0u8; 8];
        b.copy_from_slice(chunk);
        *w = u64::from_le_bytes(b);
    }
    let marker = words.first().copied().unwrap_or(0);
    if marker & !0xffff != MARKER_PREFIX {
        return Err(msg!(
            "not a serialized state of this FMU (no rotor-rub marker)"
        ));
    }
    if marker != MARKER {
        return Err(msg!(
            "serialized state of format version {}: this FMU reads version {FORMAT_VERSION}",
            marker & 0xffff
        ));
    }
    let (body, _) = bytes.split_at(BYTES - 8);
    let stored = words.last().copied().unwrap_or(0);
    if stored != u64::from(crc32(body)) {
        return Err(msg!(
            "serialized state is corrupted: its checksum does not match (refused, nothing changed)"
        ));
    }
    let mut it = words.into_iter().skip(1);
    let mut next = || it.next().unwrap_or(0);
    if next() != BYTES as u64 {
        return Err(msg!("serialized state: length word differs from {BYTES}"));
    }
    let stored_units = match next() {
        0 => Units::Dimensionless,
        1 => Units::Si,
        other => return Err(msg!("serialized state: unknown unit system {other}")),
    };
    if stored_units != units {
        return Err(msg!(
            "serialized state of the {stored_units:?} FMU cannot be restored into the {units:?} one"
        ));
    }
    let mut model = Model::new(units);
    for p in Parameter::ALL {
        let value = f64::from_bits(next());
        if !value.is_finite() {
            return Err(msg!("serialized state: {p} = {value} is not finite"));
        }
        p.set(&mut model.requested, value);
    }
    let f = |w: u64| f64::from_bits(w);
    model.start_time = f(next());
    let settings = Settings {
        internal_step: f(next()),
        tolerance: f(next()),
        max_internal_steps: u32::try_from(next()).unwrap_or(0),
        scales: Scales {
            natural_frequency: f(next()),
            clearance: f(next()),
            mass: f(next()),
        },
    };
    let flag = |w: u64, what: &str| match w {
        0 => Ok(false),
        1 => Ok(true),
        other => Err(msg!("serialized state: {what} flag {other} is not 0 or 1")),
    };
    model.pending = flag(next(), "pending")?;
    let has_stepper = flag(next(), "stepper")?;
    let mut snapshot = [0u64; Snapshot::WORDS];
    for w in snapshot.iter_mut() {
        *w = next();
    }
    model.contact_count = next();
    model.next_step = f(next());
    check_settings(&mut model, settings)?;
    if !model.start_time.is_finite() {
        return Err(msg!(
            "serialized state: start time {} is not finite",
            model.start_time
        ));
    }
    if has_stepper {
        model.stepper =
            Some(AnyStepper::from_words(&snapshot).map_err(|e| msg!("serialized state: {e}"))?);
    } else if model.pending {
        return Err(msg!(
            "serialized state: pending parameters before initialization"
        ));
    }
    let step = model.model_internal_step();
    if !(model.next_step.is_finite() && model.next_step > 0.0 && model.next_step <= step) {
        return Err(msg!(
            "serialized state: next step {} is invalid",
            model.next_step
        ));
    }
    Ok(model)
}

/// Check the settings as their setters would, then take them.
fn check_settings(model: &mut Model, settings: Settings) -> Result<(), Message> {
    settings
        .scales
        .check()
        .map_err(|(name, value, _)| msg!("serialized state: {name} = {value} is out of range"))?;
    let values = [
        (200, settings.internal_step),
        (201, settings.tolerance),
        (202, f64::from(settings.max_internal_steps)),
    ];
    for (vr, value) in values {
        let var = variables::find(vr, model.units).ok_or_else(|| msg!("no setting {vr}"))?;
        let (lo, hi) = (var.min.unwrap_or(f64::MIN), var.max.unwrap_or(f64::MAX));
        if !(value.is_finite() && (lo..=hi).contains(&value)) {
            return Err(msg!(
                "serialized state: {} = {value} is out of range",
                var.name
            ));
        }
    }
    model.settings = settings;
    if model.units == Units::Dimensionless && model.settings.scales != Scales::ONE {
        return Err(msg!(
            "serialized state: the dimensionless FMU's scales must be 1"
        ));
    }
    Ok(())
}

/// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320) of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        let index = ((crc ^ u32::from(b)) & 0xff) as usize;
        crc = CRC_TABLE.get(index).copied().unwrap_or(0) ^ (crc >> 8);
    }
    !crc
}

static CRC_TABLE: [u32; 256] = crc_table();

// `i` < 256 on every index: the loop's bound.
#[allow(clippy::indexing_slicing)]
const fn crc_table() -> [u32; 256] {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        table[i] = c;
        i += 1;
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        // The CRC-32 check value of "123456789".
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
    }

    #[test]
    fn a_default_model_round_trips() {
        for units in [Units::Dimensionless, Units::Si] {
            let model = Model::new(units);
            let bytes = serialize(&model);
            let back = deserialize(&bytes, units).unwrap();
            assert_eq!(serialize(&back), bytes);
        }
        let si = serialize(&Model::new(Units::Si));
        let e = deserialize(&si, Units::Dimensionless).unwrap_err();
        assert!(e.as_str().contains("cannot be restored"), "{e:?}");
    }
}
