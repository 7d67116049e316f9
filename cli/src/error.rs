//! The CLI's error type: a one-line message and an exit code (2 for invalid input, 1 for failures
//! while running).

use std::fmt;

use rotor_rub::PropagationError;

/// Exit code for invalid input (the same code clap uses for usage errors).
pub const EXIT_INPUT: u8 = 2;
/// Exit code for failures while running: propagation errors, I/O errors.
pub const EXIT_FAILURE: u8 = 1;

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

    /// A propagation error, with `context` (e.g. the parameter value being run) in front.
    pub fn propagation(context: &str, e: PropagationError) -> Self {
        let code = match e {
            PropagationError::InvalidProblem(_) | PropagationError::InvalidOption { .. } => {
                EXIT_INPUT
            }
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

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Keep the message on one line whatever a library put in it.
        let one_line: Vec<&str> = self.message.lines().map(str::trim).collect();
        f.write_str(&one_line.join(" "))
    }
}

impl From<PropagationError> for CliError {
    fn from(e: PropagationError) -> Self {
        CliError::propagation("", e)
    }
}
