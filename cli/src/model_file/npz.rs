//! NumPy's `.npz` (a zip of `.npy` arrays, stored or deflated, as `numpy.savez` and
//! `numpy.savez_compressed` write it) read into named arrays of f64 (or strings), C or Fortran
//! order, any little- or big-endian integer, float or boolean dtype. Nothing is trusted: every
//! size is checked against the bytes there are, so a damaged or hostile file is an error naming
//! the array, never a panic or an allocation it did not pay for.

use std::collections::BTreeMap;
use std::io::{Cursor, Read};

use npyz::{DType, NpyFile, Order, TypeChar};

/// One array of an `.npz`: its shape and its entries in C order (row-major).
#[derive(Clone, Debug, PartialEq)]
pub enum Array {
    /// Numbers (integers and booleans converted to f64).
    Numbers {
        /// The shape (empty for a 0-d array, a scalar).
        shape: Vec<usize>,
        /// The entries, row-major.
        data: Vec<f64>,
    },
    /// Strings (`U` or `S` dtype), e.g. DOF names.
    Strings {
        /// The shape.
        shape: Vec<usize>,
        /// The entries, row-major.
        data: Vec<String>,
    },
}

impl Array {
    /// The shape.
    pub fn shape(&self) -> &[usize] {
        match self {
            Array::Numbers { shape, .. } | Array::Strings { shape, .. } => shape,
        }
    }

    /// The shape as text: `(3, 3)`, `()` for a scalar.
    pub fn shape_text(&self) -> String {
        let dims: Vec<String> = self.shape().iter().map(usize::to_string).collect();
        match dims.len() {
            1 => format!("({},)", dims.join("")),
            _ => format!("({})", dims.join(", ")),
        }
    }
}

/// The largest number of entries one array may have (64 DOFs' speed-dependent matrices at 4096
/// speeds: 2²⁴ entries, 128 MiB).
const MAX_ENTRIES: u64 = 1 << 24;

/// The arrays of an `.npz` by name (the member's name without `.npy`).
///
/// # Errors
/// A message naming what is wrong: not a zip, a member that is not `.npy`, an unsupported
/// dtype (complex, object/pickled, structured), a truncated array.
pub fn read_npz(bytes: &[u8]) -> Result<BTreeMap<String, Array>, String> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| format!("not an .npz file (a zip archive of .npy arrays): {e}"))?;
    let mut arrays = BTreeMap::new();
    for i in 0..archive.len() {
        let mut member = archive
            .by_index(i)
            .map_err(|e| format!("cannot read member {i} of the archive: {e}"))?;
        if member.is_dir() {
            continue;
        }
        let name = member
            .name()
            .map_err(|e| format!("member {i} of the archive has no readable name: {e}"))?
            .to_string();
        let Some(key) = name.strip_suffix(".npy") else {
            return Err(format!(
                "member '{}' is not a .npy array (an .npz holds only .npy arrays)",
                name.escape_debug()
            ));
        };
        // The declared size is the archive's word, capped: the read below stops there.
        let cap = MAX_ENTRIES * 8 + (1 << 16);
        if member.size() > cap {
            return Err(format!(
                "array '{}' has {} bytes, more than the {cap} an array may have",
                key.escape_debug(),
                member.size()
            ));
        }
        let mut raw = Vec::new();
        (&mut member)
            .take(cap + 1)
            .read_to_end(&mut raw)
            .map_err(|e| format!("array '{}': cannot decompress it: {e}", key.escape_debug()))?;
        let array = read_npy(&raw).map_err(|e| format!("array '{}': {e}", key.escape_debug()))?;
        arrays.insert(key.to_string(), array);
    }
    Ok(arrays)
}

/// One `.npy` array.
///
/// # Errors
/// What is wrong with it.
pub fn read_npy(raw: &[u8]) -> Result<Array, String> {
    let npy = NpyFile::new(raw).map_err(|e| format!("not a valid .npy array: {e}"))?;
    let shape: Vec<usize> = npy
        .shape()
        .iter()
        .map(|&d| usize::try_from(d).map_err(|_| format!("dimension {d} is too large")))
        .collect::<Result<_, _>>()?;
    let mut count: u64 = 1;
    for &d in npy.shape() {
        count = count.saturating_mul(d);
    }
    if count > MAX_ENTRIES {
        return Err(format!(
            "it has {count} entries, more than the {MAX_ENTRIES} an array may have"
        ));
    }
    let order = npy.order();
    let DType::Plain(ty) = npy.dtype() else {
        return Err(format!(
            "dtype {} is not supported (structured or sub-array dtypes): save plain float arrays",
            npy.dtype().descr()
        ));
    };
    let item = ty.num_bytes().unwrap_or(0) as u64;
    let available = raw.len() as u64;
    if count.saturating_mul(item) > available {
        return Err(format!(
            "the file is truncated: {count} entries of {item} bytes do not fit in its {available} bytes"
        ));
    }
    let size = ty.size_field();
    let bad = |what: &str| {
        Err(format!(
            "dtype '{ty}' ({what}) is not supported: save the array as float64"
        ))
    };
    let io = |e: std::io::Error| format!("cannot read its data: {e}");
    let array = match ty.type_char() {
        TypeChar::Float => match size {
            8 => numbers(shape, npy.into_vec::<f64>().map_err(io)?),
            4 => numbers(shape, widen(npy.into_vec::<f32>().map_err(io)?)),
            _ => return bad("a float of this size"),
        },
        TypeChar::Int => match size {
            8 => numbers(shape, widen(npy.into_vec::<i64>().map_err(io)?)),
            4 => numbers(shape, widen(npy.into_vec::<i32>().map_err(io)?)),
            2 => numbers(shape, widen(npy.into_vec::<i16>().map_err(io)?)),
            1 => numbers(shape, widen(npy.into_vec::<i8>().map_err(io)?)),
            _ => return bad("an integer of this size"),
        },
        TypeChar::Uint => match size {
            8 => numbers(shape, widen(npy.into_vec::<u64>().map_err(io)?)),
            4 => numbers(shape, widen(npy.into_vec::<u32>().map_err(io)?)),
            2 => numbers(shape, widen(npy.into_vec::<u16>().map_err(io)?)),
            1 => numbers(shape, widen(npy.into_vec::<u8>().map_err(io)?)),
            _ => return bad("an integer of this size"),
        },
        TypeChar::Bool => {
            let v = npy.into_vec::<bool>().map_err(io)?;
            numbers(shape, v.into_iter().map(f64::from).collect())
        }
        TypeChar::UnicodeStr | TypeChar::ByteStr => Array::Strings {
            data: npy.into_vec::<String>().map_err(io)?,
            shape,
        },
        TypeChar::Complex => return bad("complex"),
        TypeChar::Object => return bad("Python objects, pickled"),
        _ => return bad("not a number"),
    };
    Ok(match (order, array) {
        (Order::Fortran, Array::Numbers { shape, data }) => Array::Numbers {
            data: to_c_order(&shape, &data),
            shape,
        },
        (Order::Fortran, Array::Strings { shape, data }) => Array::Strings {
            data: to_c_order(&shape, &data),
            shape,
        },
        (_, a) => a,
    })
}

fn numbers(shape: Vec<usize>, data: Vec<f64>) -> Array {
    Array::Numbers { shape, data }
}

/// Every entry as f64 (integers beyond 2⁵³ round: no DOF index or size comes near).
fn widen<T: Copy + num_like::ToF64>(v: Vec<T>) -> Vec<f64> {
    v.into_iter().map(num_like::ToF64::to_f64).collect()
}

mod num_like {
    /// A number as f64.
    pub trait ToF64 {
        fn to_f64(self) -> f64;
    }
    macro_rules! exact {
        ($($t:ty),*) => {$(impl ToF64 for $t { fn to_f64(self) -> f64 { f64::from(self) } })*};
    }
    exact!(f32, i32, i16, i8, u32, u16, u8);
    impl ToF64 for i64 {
        #[allow(clippy::cast_precision_loss)]
        fn to_f64(self) -> f64 {
            self as f64
        }
    }
    impl ToF64 for u64 {
        #[allow(clippy::cast_precision_loss)]
        fn to_f64(self) -> f64 {
            self as f64
        }
    }
}

/// Entries stored in Fortran order (first index fastest) rearranged into C order.
fn to_c_order<T: Clone>(shape: &[usize], data: &[T]) -> Vec<T> {
    let total = data.len();
    let mut out = Vec::with_capacity(total);
    let mut index = vec![0usize; shape.len()];
    for _ in 0..total {
        // Fortran offset of the C-order index.
        let mut offset = 0;
        let mut stride = 1;
        for (&i, &d) in index.iter().zip(shape) {
            offset += i * stride;
            stride *= d;
        }
        if let Some(x) = data.get(offset) {
            out.push(x.clone());
        }
        // Next C-order index (last index fastest).
        for (i, &d) in index.iter_mut().zip(shape).rev() {
            *i += 1;
            if *i < d {
                break;
            }
            *i = 0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_order_becomes_c_order() {
        // A 2 × 3 matrix [[0, 1, 2], [3, 4, 5]] stored column after column.
        let fortran = [0.0, 3.0, 1.0, 4.0, 2.0, 5.0];
        assert_eq!(
            to_c_order(&[2, 3], &fortran),
            [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
        );
        assert_eq!(to_c_order::<f64>(&[], &[7.0]), [7.0]);
    }

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        assert!(read_npz(b"not a zip").unwrap_err().contains("not an .npz"));
        assert!(read_npy(b"\x93NUMPY garbage").is_err());
    }
}
