//! Reading a speed profile from a CSV file of (τ, η) rows (`--profile`): a regular UTF-8 file
//! of at most 1 MiB, as spreadsheets and other programs write it — an optional UTF-8 byte-order
//! mark, lines ended by LF, CRLF or CR alone, fields optionally in double quotes (`""` for a
//! quote inside). `#` starts a comment line. The first row may be a header, recognised by its
//! names only ([`TIME_NAMES`], [`SPEED_NAMES`]); every other row is two numbers. Every error
//! names the file, the line and the value (and the valid range, from the runtime's validation
//! of the profile).

use std::path::Path;

use rotor_rub::speed::{SpeedPoint, SpeedProfile};

use crate::error::{CliError, Result};
use crate::problem::read_capped;

/// Names a header may give the time column (compared ignoring case).
pub const TIME_NAMES: [&str; 4] = ["time", "tau", "τ", "t"];
/// Names a header may give the speed column (compared ignoring case).
pub const SPEED_NAMES: [&str; 4] = ["speed_ratio", "eta", "η", "speed"];

/// The lines of `text` with their numbers, ended by LF, CRLF or CR.
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = Some(text);
    let mut number = 0;
    std::iter::from_fn(move || {
        let current = rest?;
        number += 1;
        match current.find(['\r', '\n']) {
            Some(i) => {
                let skip = if current[i..].starts_with("\r\n") {
                    2
                } else {
                    1
                };
                rest = Some(&current[i + skip..]).filter(|r| !r.is_empty());
                Some((number, &current[..i]))
            }
            None => {
                rest = None;
                Some((number, current))
            }
        }
    })
}

/// The fields of one row: split at commas outside double quotes, each trimmed and unquoted.
fn fields(row: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut chars = row.chars().peekable();
    loop {
        while chars.next_if(|c| c.is_whitespace()).is_some() {}
        let mut field = String::new();
        if chars.next_if_eq(&'"').is_some() {
            loop {
                match chars.next() {
                    Some('"') if chars.next_if_eq(&'"').is_some() => field.push('"'),
                    Some('"') => break,
                    Some(c) => field.push(c),
                    None => return Err("a quoted field has no closing quote".into()),
                }
            }
            while chars.next_if(|c| c.is_whitespace()).is_some() {}
            if chars.peek().is_some_and(|c| *c != ',') {
                return Err("text after a quoted field's closing quote".into());
            }
        } else {
            while let Some(c) = chars.next_if(|c| *c != ',') {
                if c == '"' {
                    return Err("a quote inside an unquoted field".into());
                }
                field.push(c);
            }
            field.truncate(field.trim_end().len());
        }
        fields.push(field);
        if chars.next().is_none() {
            return Ok(fields);
        }
    }
}

/// Whether `name` is one of `names`, ignoring case.
fn names(name: &str, names: &[&str]) -> bool {
    names
        .iter()
        .any(|n| n.to_lowercase() == name.to_lowercase())
}

/// Parse the text of a profile file (`name` for messages): its points, validated.
pub fn parse(text: &str, name: &str) -> Result<Vec<SpeedPoint>> {
    let fail =
        |line: usize, m: String| CliError::input(format!("--profile {name} line {line}: {m}"));
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut points = Vec::new();
    let mut lines_of_points = Vec::new();
    let mut first = true;
    for (line, raw) in lines(text) {
        let row = raw.trim();
        if row.is_empty() || row.starts_with('#') {
            continue;
        }
        let fields = fields(row).map_err(|m| fail(line, m))?;
        let [time, speed] = &fields[..] else {
            return Err(fail(
                line,
                format!(
                    "expected two comma-separated values, time and speed_ratio, found {}",
                    fields.len()
                ),
            ));
        };
        let first_row = std::mem::replace(&mut first, false);
        if first_row && names(time, &TIME_NAMES) && names(speed, &SPEED_NAMES) {
            continue;
        }
        let number = |column: &str, value: &str| {
            value.parse::<f64>().map_err(|_| {
                fail(
                    line,
                    format!(
                        "{column} '{}' is not a number (a header, on the first row only, names \
                         the columns: {} for the time, {} for the speed ratio)",
                        value.escape_debug(),
                        TIME_NAMES.join(", "),
                        SPEED_NAMES.join(", ")
                    ),
                )
            })
        };
        // A first row naming the time column: the speed column's name is what is wrong.
        let (t, s) = if first_row && names(time, &TIME_NAMES) {
            let s = number("speed_ratio", speed)?;
            (number("time", time)?, s)
        } else {
            (number("time", time)?, number("speed_ratio", speed)?)
        };
        points.push(SpeedPoint::new(t, s));
        lines_of_points.push(line);
    }
    if let Err(e) = SpeedProfile::new(&points) {
        return Err(match e.index().and_then(|i| lines_of_points.get(i)) {
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
        // A header is only allowed first, and only by its names.
        assert!(message("0,1\ntau,eta\n5,1\n").contains("line 2: time 'tau'"));
        assert!(message("foo,bar\n0,1\n5,1\n").contains("line 1: time 'foo'"));
        assert!(message("tau,rpm\n0,1\n5,1\n").contains("line 1: speed_ratio 'rpm'"));
    }

    #[test]
    fn quotes_bom_and_line_endings() {
        let plain = parse("0,1\n5,1.5\n", "p.csv").unwrap();
        for text in [
            "\u{feff}0,1\n5,1.5\n",
            "0,1\r5,1.5",
            "0,1\r\n5,1.5\r\n",
            "\"0\",\"1\"\n 5 , \"1.5\" \n",
            "\"tau\",\"ETA\"\r\n0,1\r\n5,1.5\r\n",
        ] {
            assert_eq!(parse(text, "p.csv").unwrap(), plain, "{text:?}");
        }
        let message = |text: &str| parse(text, "p.csv").err().unwrap().message;
        assert!(message("0,\"1\n5,1\n").contains("line 1: a quoted field has no closing"));
        assert!(message("0,\"1\"x\n").contains("line 1: text after"));
        assert!(message("0,1\"\n").contains("line 1: a quote inside"));
        assert!(message("0,1\r\r\r5,x\r").contains("line 4: speed_ratio 'x'"));
        assert_eq!(fields("\"a \"\"b\"\"\", c").unwrap(), ["a \"b\"", "c"]);
        assert_eq!(
            lines("a\r\nb\rc\n\nd").collect::<Vec<_>>(),
            [(1, "a"), (2, "b"), (3, "c"), (4, ""), (5, "d")]
        );
    }
}
