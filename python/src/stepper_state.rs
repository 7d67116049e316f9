//! `rotor_rub.StepperState`: the fixed-step stepper's full internal state (the runtime's
//! [`Snapshot`], what the FMU's get/set FMU state uses) as an immutable Python value: compared
//! bit for bit, hashable, and serialized as checked bytes (pickle, `to_bytes`/`from_bytes`): a
//! magic, a format version, the word count, the words and an FNV-1a checksum, so a truncated,
//! corrupted or foreign byte string is refused with a message, never restored.

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use rotor_rub::stepper::Snapshot;
use rotor_rub::{Parameter, Problem, Stepper};

use crate::errors::input;

const MAGIC: &[u8; 8] = b"RRSTEPST";
const FORMAT: u32 = 1;
/// Bytes before the words: magic, format, word count.
const HEAD: usize = 8 + 4 + 4;

/// FNV-1a, 64 bits.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The full internal state of a [`crate::stepper::PyStepper`]: set it back with
/// `stepper.state = saved` and the stepper repeats its run bit for bit. Reads as the 4-vector
/// (x, y, vx, vy) when indexed.
#[pyclass(name = "StepperState", module = "rotor_rub._core", frozen, eq, hash)]
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct PyStepperState {
    words: Vec<u64>,
}

impl PyStepperState {
    pub fn of(stepper: &Stepper) -> Self {
        PyStepperState {
            words: stepper.snapshot().to_words().to_vec(),
        }
    }

    /// The stepper this state was taken of.
    pub fn restore(&self) -> PyResult<Stepper> {
        let words: [u64; Snapshot::WORDS] = self
            .words
            .as_slice()
            .try_into()
            .map_err(|_| input("StepperState: wrong number of words"))?;
        let snapshot =
            Snapshot::from_words(&words).map_err(|e| input(format!("StepperState: {e}")))?;
        Stepper::restore(&snapshot).map_err(|e| input(format!("StepperState: {e}")))
    }

    fn word(&self, i: usize) -> f64 {
        f64::from_bits(self.words.get(i).copied().unwrap_or(0))
    }

    /// Index of the tail word `k` (after the model parameters, `Snapshot::to_words`' order).
    fn tail(k: usize) -> usize {
        Parameter::MODEL_COUNT + k
    }
}

#[pymethods]
impl PyStepperState {
    /// The state as checked bytes (see the module documentation).
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let mut out = Vec::with_capacity(HEAD + 8 * self.words.len() + 8);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT.to_le_bytes());
        out.extend_from_slice(&(self.words.len() as u32).to_le_bytes());
        for w in &self.words {
            out.extend_from_slice(&w.to_le_bytes());
        }
        let sum = checksum(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        PyBytes::new(py, &out)
    }

    /// A state from [`PyStepperState::to_bytes`]' output, checked (magic, format, length,
    /// checksum, then every value as a stepper restores it).
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<Self> {
        let bad = |why: String| input(format!("StepperState.from_bytes: {why}"));
        let expected = HEAD + 8 * Snapshot::WORDS + 8;
        if data.len() < HEAD || &data[..8] != MAGIC {
            return Err(bad("not a rotor_rub stepper state".into()));
        }
        let format = u32::from_le_bytes([data[8], data[9], data[10], data[11]]);
        let count = u32::from_le_bytes([data[12], data[13], data[14], data[15]]) as usize;
        if format != FORMAT || count != Snapshot::WORDS {
            return Err(bad(format!(
                "format {format} with {count} words, this rotor_rub reads format {FORMAT} with {} words (saved by another version)",
                Snapshot::WORDS
            )));
        }
        if data.len() != expected {
            return Err(bad(format!(
                "{} bytes, expected {expected} (truncated?)",
                data.len()
            )));
        }
        let (body, sum) = data.split_at(expected - 8);
        let mut stored = [0u8; 8];
        stored.copy_from_slice(sum);
        if u64::from_le_bytes(stored) != checksum(body) {
            return Err(bad("checksum mismatch: the data is corrupted".into()));
        }
        let words = body[HEAD..]
            .chunks_exact(8)
            .map(|c| {
                let mut w = [0u8; 8];
                w.copy_from_slice(c);
                u64::from_le_bytes(w)
            })
            .collect();
        let state = PyStepperState { words };
        state.restore()?;
        Ok(state)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let rebuild = slf.get_type().getattr("from_bytes")?;
        let data = slf.get().to_bytes(py);
        PyTuple::new(py, [rebuild, PyTuple::new(py, [data])?.into_any()])
    }

    /// The time τ.
    #[getter]
    fn time(&self) -> f64 {
        self.word(Self::tail(7))
    }

    /// (x, y, vx, vy).
    #[getter]
    fn vector(&self) -> [f64; 4] {
        [10, 11, 12, 13].map(|k| self.word(Self::tail(k)))
    }

    /// free, contact or rolling.
    #[getter]
    fn regime(&self) -> &'static str {
        match self.words.get(Self::tail(14)) {
            Some(1) => "contact",
            Some(2) => "rolling",
            _ => "free",
        }
    }

    /// The model parameters in force (the input force and the running speed included).
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mut problem = Problem::DEFAULT;
        let model = Parameter::ALL.iter().filter(|p| p.is_model());
        for (p, w) in model.clone().zip(&self.words) {
            p.set(&mut problem, f64::from_bits(*w));
        }
        let out = PyDict::new(py);
        for p in model {
            out.set_item(p.name(), p.get(&problem))?;
        }
        Ok(out)
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyIterator>> {
        PyTuple::new(py, self.vector())?.try_iter()
    }

    fn __len__(&self) -> usize {
        4
    }

    fn __getitem__(&self, index: isize) -> PyResult<f64> {
        let i = if index < 0 { index + 4 } else { index };
        usize::try_from(i)
            .ok()
            .and_then(|i| self.vector().get(i).copied())
            .ok_or_else(|| {
                pyo3::exceptions::PyIndexError::new_err(
                    "StepperState index out of range (x, y, vx, vy)",
                )
            })
    }

    fn __repr__(&self) -> String {
        let [x, y, vx, vy] = self.vector();
        format!(
            "StepperState(time={:e}, x={x:e}, y={y:e}, vx={vx:e}, vy={vy:e}, regime={})",
            self.time(),
            self.regime()
        )
    }
}
