//! The one way the command writes to its standard output and standard error: reports and
//! listings ([`out`]), error and warning lines ([`error`], [`warn`]), clap's help, version and
//! usage messages ([`clap_message`]) and progress bars ([`progress`]). Nothing else in the CLI
//! touches stdout or stderr (`.ci/run` fails on a `println!`, `eprintln!` or a direct
//! `stdout()`/`stderr()` elsewhere).
//!
//! One rule for a closed pipe (`rotor-rub presets | head -c 10`): writing to it ends the command
//! quietly with [`EXIT_PIPE`](crate::error::EXIT_PIPE) (141, what a shell reports for a Unix tool killed by SIGPIPE),
//! nothing more is written, and no panic; output files are complete, since every command prints
//! its report after they are in place. A stderr that cannot be written (closed, full) changes
//! nothing: the exit code carries the outcome.

use std::fmt;
use std::io::{self, IsTerminal, Write};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle, TermLike};

use crate::error::{CliError, EXIT_FAILURE, Result, short_numbers};

/// Write `text` to stdout: a closed pipe is [`CliError::broken_pipe`] (exit 141, quiet); any
/// other failure (a full disk behind a redirect) is a failure, exit 1.
pub fn out(text: &str) -> Result<()> {
    let mut stdout = io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Err(CliError::broken_pipe()),
        Err(e) => Err(CliError::failure(format!(
            "cannot write to standard output: {e} (the output files are complete)"
        ))),
    }
}

/// Write `text` to stderr, ignoring failures (see the module documentation).
fn err(text: &str) {
    let mut stderr = io::stderr().lock();
    let _ = stderr
        .write_all(text.as_bytes())
        .and_then(|()| stderr.flush());
}

/// `error: <message>` on stderr, long numbers shortened.
pub fn error(message: &str) {
    err(&format!("error: {}\n", short_numbers(message)));
}

/// `warning: <message>` on stderr.
pub fn warn(message: &str) {
    err(&format!("warning: {message}\n"));
}

/// A line on stderr that is neither an error nor a warning (the interrupt notice).
pub fn note(message: &str) {
    err(&format!("{message}\n"));
}

/// Print clap's help, version or usage message where clap would (help and version on stdout,
/// the rest on stderr), styled as clap styles it for that stream, and return the exit code:
/// clap's, or 141 when stdout is a closed pipe.
pub fn clap_message(e: &clap::Error) -> u8 {
    let styled = e.render();
    let code = u8::try_from(e.exit_code()).unwrap_or(EXIT_FAILURE);
    if e.use_stderr() {
        let text = match anstream::AutoStream::choice(&io::stderr()) {
            anstream::ColorChoice::Never => styled.to_string(),
            _ => styled.ansi().to_string(),
        };
        err(&text);
        return code;
    }
    let text = match anstream::AutoStream::choice(&io::stdout()) {
        anstream::ColorChoice::Never => styled.to_string(),
        _ => styled.ansi().to_string(),
    };
    match out(&text) {
        Ok(()) => code,
        Err(e) => {
            if !e.message.is_empty() {
                error(&e.message);
            }
            e.code
        }
    }
}

/// A progress bar of `len` steps drawn on stderr when stderr is a terminal (hidden otherwise),
/// with indicatif's `template`.
pub fn progress(len: u64, template: &str) -> ProgressBar {
    let target = if io::stderr().is_terminal() {
        ProgressDrawTarget::term_like(Box::new(Stderr))
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(len), target);
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style);
    }
    bar
}

/// The terminal on stderr, for indicatif: drawn through [`err`], so a terminal gone away does
/// not stop the run.
struct Stderr;

impl fmt::Debug for Stderr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Stderr")
    }
}

impl TermLike for Stderr {
    fn width(&self) -> u16 {
        console::Term::stderr().size().1
    }

    fn height(&self) -> u16 {
        console::Term::stderr().size().0
    }

    fn move_cursor_up(&self, n: usize) -> io::Result<()> {
        self.write_str(&if n > 0 {
            format!("\x1b[{n}A")
        } else {
            String::new()
        })
    }

    fn move_cursor_down(&self, n: usize) -> io::Result<()> {
        self.write_str(&if n > 0 {
            format!("\x1b[{n}B")
        } else {
            String::new()
        })
    }

    fn move_cursor_right(&self, n: usize) -> io::Result<()> {
        self.write_str(&if n > 0 {
            format!("\x1b[{n}C")
        } else {
            String::new()
        })
    }

    fn move_cursor_left(&self, n: usize) -> io::Result<()> {
        self.write_str(&if n > 0 {
            format!("\x1b[{n}D")
        } else {
            String::new()
        })
    }

    fn write_line(&self, s: &str) -> io::Result<()> {
        err(&format!("{s}\n"));
        Ok(())
    }

    fn write_str(&self, s: &str) -> io::Result<()> {
        err(s);
        Ok(())
    }

    fn clear_line(&self) -> io::Result<()> {
        self.write_str("\r\x1b[2K")
    }

    fn flush(&self) -> io::Result<()> {
        Ok(())
    }
}
