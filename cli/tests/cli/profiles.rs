//! Issue 32 item 12 (run-up): speed-profile files as spreadsheets and other systems write them
//! (a UTF-8 BOM; CRLF or CR-only line endings; quoted fields) read as the plain file; a header is
//! recognised by its column names, never guessed; and the events file holds every switch of the
//! run, those after the last whole forcing period too.

use std::fs;
use std::path::Path;

use crate::common::{bin, num, read_csv};

/// Run `runup --profile p.csv` with `text` as the profile; the rows file, or the error line.
fn runup(dir: &Path, text: &[u8], extra: &[&str]) -> Result<String, String> {
    fs::write(dir.join("p.csv"), text).unwrap();
    let out = bin()
        .current_dir(dir)
        .args(["runup", "--profile", "p.csv", "--out", "r.csv", "--no-plot"])
        .args(["--method", "hybrid"])
        .args(extra)
        .output()
        .unwrap();
    if out.status.success() {
        Ok(fs::read_to_string(dir.join("r.csv")).unwrap())
    } else {
        assert_eq!(out.status.code(), Some(2));
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

#[test]
fn line_endings_bom_and_quotes_read_as_the_plain_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plain = runup(d, b"0,1\n30,1.2\n60,1.2\n", &[]).unwrap();
    for text in [
        &b"\xef\xbb\xbf0,1\n30,1.2\n60,1.2\n"[..],
        b"0,1\r\n30,1.2\r\n60,1.2\r\n",
        b"0,1\r30,1.2\r60,1.2\r",
        b"0,1\r30,1.2\r60,1.2",
        b"\xef\xbb\xbf# exported\r\rtime,speed_ratio\r0,1\r30,1.2\r60,1.2\r",
        // A quoted first row is data, not a header.
        b"\"0\",\"1\"\n30,1.2\n\"60\", \"1.2\"\n",
        b"\"tau\",\"eta\"\r\n\"0\",\"1\"\r\n\"30\",\"1.2\"\r\n\"60\",\"1.2\"\r\n",
        b"Time , Speed_Ratio\n0,1\n30,1.2\n60,1.2\n",
        b"\xcf\x84,\xce\xb7\n0,1\n30,1.2\n60,1.2\n",
    ] {
        let shown = String::from_utf8_lossy(text).into_owned();
        assert_eq!(runup(d, text, &[]).as_ref(), Ok(&plain), "{shown:?}");
    }
}

#[test]
fn a_first_row_is_a_header_only_by_its_names() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (text, expected) in [
        (
            &b"foo,bar\n0,1\n60,1.2\n"[..],
            &["p.csv line 1", "'foo'", "time, tau"][..],
        ),
        (b"tau,rpm\n0,1\n60,1.2\n", &["line 1", "'rpm'"]),
        (b"\"x\",1\n60,1.2\n", &["line 1", "'x'"]),
        (b"0,1\n\"tau\",\"eta\"\n60,1.2\n", &["line 2", "'tau'"]),
        (b"0,\"1\n60,1.2\n", &["line 1", "quote"]),
        (b"0,1\r30,x\r", &["line 2", "'x'"]),
    ] {
        let shown = String::from_utf8_lossy(text).into_owned();
        let err = runup(d, text, &[]).expect_err(&shown);
        for piece in expected {
            assert!(err.contains(piece), "{shown:?}: '{piece}' not in {err}");
        }
    }
}

#[test]
fn the_events_file_keeps_the_switches_of_the_last_partial_period() {
    // 100 / π = 31.8 forcing periods at η = 2: the switches after period 31 were dropped.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    runup(d, b"0,2\n100,2\n", &[]).unwrap();
    let out = bin()
        .current_dir(d)
        .args(["simulate", "--set", "speed_ratio=2", "--t-end", "100"])
        .args(["--method", "hybrid", "--events", "s.csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let (header, runup_events) = read_csv(&d.join("r-events.csv"));
    assert_eq!(header[0], "time");
    let (_, simulate_events) = read_csv(&d.join("s.csv"));
    assert_eq!(runup_events.len(), simulate_events.len());
    for (r, s) in runup_events.iter().zip(&simulate_events) {
        assert!((num(&r[0]) - num(&s[0])).abs() < 1e-12, "{r:?} vs {s:?}");
        assert_eq!(r[4], s[1], "{r:?} vs {s:?}");
    }
    // The partial period after the last row of the per-period file.
    let (_, rows) = read_csv(&d.join("r.csv"));
    let last_row: u64 = rows.last().unwrap()[1].parse().unwrap();
    let last_event = runup_events.last().unwrap();
    assert_eq!(last_event[2], (last_row + 1).to_string());
    assert!(num(&last_event[0]) > num(&rows.last().unwrap()[3]));
}
