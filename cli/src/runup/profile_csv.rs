//! Reading a speed profile from a CSV file of (τ, η) rows (`--profile`): a regular UTF-8 file
//! of at most 1 MiB; `#` starts a comment line; an optional header line names the columns.
//! Every error names the file, the line and the value (and the valid range, from the runtime's
//! validation of the profile).

use std::path::Path;

use rotor_rub::speed::{SpeedPoint, SpeedProfile};

use crate::error::{CliError, Result};
use crate::problem::read_capped;

/// Parse the text of a profile file (`name` for messages): its points, validated.
pub fn parse(text: &str, name: &str) -> Result<Vec<SpeedPoint>> {
    let fail =
        |line: usize, m: String| CliError::input(format!("--profile {name} line {line}: {m}"));
    let mut points = Vec::new();
    let mut lines = Vec::new();
    let mut header_allowed = true;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let row = raw.trim();
        if row.is_empty() || row.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = row.split(',').map(str::trim).collect();
        let [time, speed] = fields[..] else {
            return Err(fail(
                line,
                format!(
                    "expected two comma-separated values, time and speed_ratio, found {}",
                    fields.len()
                ),
            ));
        };
        let numbers = (time.parse::<f64>(), speed.parse::<f64>());
        match numbers {
            (Ok(t), Ok(s)) => {
                points.push(SpeedPoint::new(t, s));
                lines.push(line);
            }
            // A header: the first row, naming both columns (no number in it).
            (Err(_), Err(_)) if header_allowed => {}
            (Err(_), _) => {
                return Err(fail(
                    line,
                    format!("time '{}' is not a number", time.escape_debug()),
                ));
            }
            (_, Err(_)) => {
                return Err(fail(
                    line,
                    format!("speed_ratio '{}' is not a number", speed.escape_debug()),
                ));
            }
        }
        header_allowed = false;
    }
    if let Err(e) = SpeedProfile::new(&points) {
        return Err(match e.index().and_then(|i| lines.get(i)) {
            Some(&line) => fail(line, e.to_string()),
            None => CliError::input(format!("--profile {name}: {e}")),
        });
    }
    Ok(points)
}

/// Read and parse a profile file.
pub fn read(path: &Path) -> Result<Vec<SpeedPoint>> {
    let name = path.display().to_string();
    let text = read_capped(path, "speed profile", "CSV")
        .map_err(|m| CliError::input(format!("--profile {name}: {m}")))?;
    parse(&text, &name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_header_and_comments() {
        let points = parse(
            "# run-up\ntau, eta\n0, 0.5\n\n100,1.5\n 250 , 1.5\n",
            "p.csv",
        )
        .unwrap();
        assert_eq!(points.len(), 3);
        assert_eq!(points[1], SpeedPoint::new(100.0, 1.5));
        // Lines count comments, the header and blank lines: the bad row is line 6.
        let e = parse(
            "# run-up\ntau, eta\n0, 0.5\n\n100,1.5\n 50 , 1.5\n",
            "p.csv",
        )
        .err()
        .unwrap();
        assert!(e.message.contains("line 6"), "{}", e.message);
    }

    #[test]
    fn errors_name_the_line_and_the_value() {
        let message = |text: &str| parse(text, "p.csv").err().unwrap().message;
        assert_eq!(
            message("0,1\n1,1,1\n"),
            "--profile p.csv line 2: expected two comma-separated values, time and speed_ratio, found 3"
        );
        assert!(message("0,1\nx,1\n").contains("line 2: time 'x' is not a number"));
        assert!(message("t,eta\n0,1\n5,fast\n").contains("line 3: speed_ratio 'fast'"));
        assert!(message("0,1\n10,1.2\n5,1.4\n").contains("line 3: time = 5 is not after"));
        assert!(
            message("0,1\n10,NaN\n").contains("line 2: speed_ratio = NaN is not a finite number")
        );
        assert!(
            message("0,1\n10,200\n")
                .contains("line 2: speed_ratio = 200 is out of range: it must be in [0.001, 100]")
        );
        assert!(message("0,1\n").contains("at least 2 points"));
        // A header is only allowed first.
        assert!(message("0,1\ntau,eta\n5,1\n").contains("line 2: time 'tau'"));
    }
}
