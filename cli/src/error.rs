//! The CLI's error type: a one-line message and an exit code (2 for invalid input, 1 for failures
//! while running).

use std::fmt;

use rotor_rub::PropagationError;

/// Exit code for invalid input (the same code clap uses for usage errors).
pub const EXIT_INPUT: u8 = 2;
/// Exit code for failures while running: propagation errors, I/O errors.
pub const EXIT_FAILURE: u8 = 1;
/// Exit code when stdout is a closed pipe: 128 + SIGPIPE, what a shell reports for a Unix tool
/// killed by SIGPIPE (`cat file | head -1`); nothing is printed.
pub const EXIT_PIPE: u8 = 141;

/// A failed command: what to print on stderr and how to exit.
#[derive(Debug)]
pub struct CliError {
    /// Exit status.
    pub code: u8,
    /// One-line message (without the `error: ` prefix).
    pub message: String,
}

/// Result of a command.
pub type Result<T, E = CliError> = std::result::Result<T, E>;

impl CliError {
    /// Invalid input (exit code 2).
    pub fn input(message: impl Into<String>) -> Self {
        Self {
            code: EXIT_INPUT,
            message: message.into(),
        }
    }

    /// A failure while running (exit code 1).
    pub fn failure(message: impl Into<String>) -> Self {
        Self {
            code: EXIT_FAILURE,
            message: message.into(),
        }
    }

    /// Stdout is a closed pipe: exit quietly with [`EXIT_PIPE`].
    pub fn broken_pipe() -> Self {
        Self {
            code: EXIT_PIPE,
            message: String::new(),
        }
    }

    /// A propagation error, with `context` (e.g. the parameter value being run) in front.
    pub fn propagation(context: &str, e: PropagationError) -> Self {
        let code = match e {
            // A matrix model's refusal (an option it does not take, a start of the wrong
            // size) is bad input too.
            PropagationError::InvalidProblem(_)
            | PropagationError::InvalidOption { .. }
            | PropagationError::InvalidModel(_) => EXIT_INPUT,
            _ => EXIT_FAILURE,
        };
        let message = if context.is_empty() {
            format!("propagation failed: {e}")
        } else {
            format!("propagation failed ({context}): {e}")
        };
        Self { code, message }
    }
}

impl CliError {
    /// The same error with `context` in front of its message.
    pub fn context(self, context: &str) -> Self {
        Self {
            message: format!("{context}: {}", self.message),
            ..self
        }
    }
}

/// A number for a message: shortest round-trip digits, in exponent form outside [1e-4, 1e15) so
/// that no message carries hundreds of digits (`1e300`, not a 301-digit integer).
pub fn num(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&magnitude) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `text` with every number written in more than 21 characters (more than any `u64`, so counts
/// stay exact) (`1e300` printed in fixed point
/// by a library or a parser) rewritten by [`num`]: a safety net under every message printed.
pub fn short_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        let (before, from) = rest.split_at(start);
        out.push_str(before);
        let len = from
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(from.len());
        let (token, after) = from.split_at(len);
        match token.parse::<f64>() {
            Ok(x) if token.len() > 21 => out.push_str(&num(x)),
            _ => out.push_str(token),
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Keep the message on one line whatever a library put in it.
        let one_line: Vec<&str> = self.message.lines().map(str::trim).collect();
        f.write_str(&short_numbers(&one_line.join(" ")))
    }
}

impl From<PropagationError> for CliError {
    fn from(e: PropagationError) -> Self {
        CliError::propagation("", e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_numbers_are_shortened() {
        let long = format!("step = {} is invalid", 1e300);
        assert_eq!(short_numbers(&long), "step = 1e300 is invalid");
        let small = format!("tol {} and 2.5 and 12345", 1e-300);
        assert_eq!(short_numbers(&small), "tol 1e-300 and 2.5 and 12345");
        assert_eq!(num(1e-7), "1e-7");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(1.8446744073709552e19), "1.8446744073709552e19");
    }
}
