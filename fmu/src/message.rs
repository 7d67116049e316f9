//! Log messages without allocation: formatted into a fixed buffer (truncated to fit) and handed
//! to the importer's logger as a NUL-terminated string. Every error the FMU reports names the
//! value and what it should have been.

use core::fmt::{self, Write};

/// Capacity of one message in bytes, NUL included.
pub const CAPACITY: usize = 400;

/// A formatted message in a fixed buffer.
#[derive(Clone, Copy)]
pub struct Message {
    bytes: [u8; CAPACITY],
    len: usize,
}

impl Message {
    /// The message of `args`, truncated to [`CAPACITY`] − 1 bytes (on a character boundary).
    pub fn new(args: fmt::Arguments<'_>) -> Message {
        let mut m = Message {
            bytes: [0; CAPACITY],
            len: 0,
        };
        let _ = m.write_fmt(args);
        m
    }

    /// The text.
    pub fn as_str(&self) -> &str {
        let bytes = self.bytes.get(..self.len).unwrap_or(&[]);
        core::str::from_utf8(bytes).unwrap_or("")
    }

    /// The text as a NUL-terminated C string (the byte after the text is always 0).
    pub fn as_ptr(&self) -> *const core::ffi::c_char {
        self.bytes.as_ptr().cast()
    }
}

impl fmt::Debug for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Write for Message {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let room = CAPACITY - 1 - self.len;
        let mut n = s.len().min(room);
        while n > 0 && !s.is_char_boundary(n) {
            n -= 1;
        }
        if let (Some(dst), Some(src)) = (self.bytes.get_mut(self.len..self.len + n), s.get(..n)) {
            dst.copy_from_slice(src.as_bytes());
            self.len += n;
        }
        Ok(())
    }
}

/// A [`Message`] from format arguments: `msg!("x = {x}")`.
#[macro_export]
macro_rules! msg {
    ($($t:tt)*) => {
        $crate::message::Message::new(format_args!($($t)*))
    };
}
