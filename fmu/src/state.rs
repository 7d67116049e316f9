//! Saved FMU states (rigs roll back): a state is a copy of the [`Model`]; serialized, it is a
//! fixed number of little-endian 64-bit words — a marker and format version, the parameter
//! table's values, the settings, the stepper's [`Snapshot`] and the counters — read back with
//! every value checked ([`Stepper::restore`]).

use rotor_rub::stepper::{Snapshot, Stepper};
use rotor_rub::{Parameter, Problem};

use crate::message::Message;
use crate::model::{Model, Settings};
use crate::msg;

/// Marks a serialized state ("rrfmu" + format version 1).
const MARKER: u64 = 0x7272_666d_7500_0001;
/// Words: marker, table, two settings, stepper flag, snapshot, count, next step.
pub const WORDS: usize = 1 + Parameter::COUNT + 2 + 1 + Snapshot::WORDS + 2;
/// Serialized size in bytes.
pub const BYTES: usize = 8 * WORDS;

/// The model as bytes.
pub fn serialize(model: &Model) -> [u8; BYTES] {
    let mut words = [0u64; WORDS];
    let table = Parameter::ALL.map(|p| p.get(&model.problem).to_bits());
    let snapshot = model.stepper.map(|s| s.snapshot().to_words());
    let head = [MARKER]
        .into_iter()
        .chain(table)
        .chain([
            model.settings.internal_step.to_bits(),
            model.settings.tolerance.to_bits(),
            u64::from(snapshot.is_some()),
        ])
        .chain(snapshot.unwrap_or([0; Snapshot::WORDS]))
        .chain([model.contact_count, model.next_step.to_bits()]);
    for (w, v) in words.iter_mut().zip(head) {
        *w = v;
    }
    let mut out = [0u8; BYTES];
    for (chunk, w) in out.chunks_exact_mut(8).zip(words) {
        chunk.copy_from_slice(&w.to_le_bytes());
    }
    out
}

/// The model serialized in `bytes`, every value checked.
pub fn deserialize(bytes: &[u8]) -> Result<Model, Message> {
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
    let mut it = words.into_iter();
    let mut next = || it.next().unwrap_or(0);
    if next() != MARKER {
        return Err(msg!(
            "not a serialized state of this FMU (marker or format version differs)"
        ));
    }
    let mut problem = Problem::DEFAULT;
    for p in Parameter::ALL {
        p.set(&mut problem, f64::from_bits(next()));
    }
    problem
        .validate()
        .map_err(|e| msg!("serialized state: {e}"))?;
    let settings = Settings {
        internal_step: f64::from_bits(next()),
        tolerance: f64::from_bits(next()),
    };
    let has_stepper = next() == 1;
    let mut snapshot = [0u64; Snapshot::WORDS];
    for w in snapshot.iter_mut() {
        *w = next();
    }
    let stepper = if has_stepper {
        let s = Snapshot::from_words(&snapshot).map_err(|e| msg!("serialized state: {e}"))?;
        Some(Stepper::restore(&s).map_err(|e| msg!("serialized state: {e}"))?)
    } else {
        None
    };
    let contact_count = next();
    let next_step = f64::from_bits(next());
    let (lo, hi) = crate::variables::INTERNAL_STEP_RANGE;
    let (tlo, thi) = crate::variables::TOLERANCE_RANGE;
    if !((lo..=hi).contains(&settings.internal_step) && (tlo..=thi).contains(&settings.tolerance)) {
        return Err(msg!("serialized state: settings {settings:?} out of range"));
    }
    if !(next_step.is_finite() && next_step > 0.0 && next_step <= settings.internal_step) {
        return Err(msg!("serialized state: next step {next_step} is invalid"));
    }
    Ok(Model {
        problem,
        settings,
        stepper,
        contact_count,
        next_step,
    })
}
