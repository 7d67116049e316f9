//! The metadata line a sweep shard file starts with, so that `merge` can tell a complete,
//! consistent set of shards from a missing, duplicated, mismatched or damaged one.
//!
//! The line is `# rotor-rub sweep shard I/N; rows R; fnv1a64 H; run <description>`: the shard's
//! index and count, its number of data rows, the FNV-1a 64 checksum of everything after the
//! line (header and rows), and a description of the run (version, sweep range, periods, method,
//! tolerance and every parameter) that all shards of one sweep share. Only shard files carry it;
//! the unsharded sweep and the merged file are plain CSV.

/// How the metadata line starts.
pub const MARK: &str = "# rotor-rub sweep shard ";

/// What a shard file says about itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardInfo {
    /// Shard index I, 0 <= I < N.
    pub index: u64,
    /// Number of shards N.
    pub count: u64,
    /// Data rows in the file.
    pub rows: u64,
    /// FNV-1a 64 of the bytes after the metadata line.
    pub checksum: u64,
    /// The run every shard of the sweep shares.
    pub run: String,
}

/// FNV-1a, 64 bits: detects a truncated or edited file (not an adversary).
pub fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

impl ShardInfo {
    /// The metadata line, with its newline.
    pub fn line(&self) -> String {
        format!(
            "{MARK}{}/{}; rows {}; fnv1a64 {:016x}; run {}\n",
            self.index, self.count, self.rows, self.checksum, self.run
        )
    }

    /// Parse a metadata line (without its newline).
    pub fn parse(line: &str) -> Result<Self, String> {
        let bad = |what: &str| format!("its metadata line is damaged ({what})");
        let rest = line.strip_prefix(MARK).ok_or_else(|| {
            "it has no shard metadata line: not written by `rotor-rub sweep --shard`".to_string()
        })?;
        let mut parts = rest.splitn(4, "; ");
        let (Some(shard), Some(rows), Some(sum), Some(run)) =
            (parts.next(), parts.next(), parts.next(), parts.next())
        else {
            return Err(bad("missing fields"));
        };
        let (index, count) = shard.split_once('/').ok_or_else(|| bad("shard I/N"))?;
        let index: u64 = index.parse().map_err(|_| bad("shard index"))?;
        let count: u64 = count.parse().map_err(|_| bad("shard count"))?;
        if count == 0 || index >= count {
            return Err(bad("shard I/N out of range"));
        }
        let rows = rows
            .strip_prefix("rows ")
            .and_then(|r| r.parse().ok())
            .ok_or_else(|| bad("rows"))?;
        let checksum = sum
            .strip_prefix("fnv1a64 ")
            .and_then(|h| u64::from_str_radix(h, 16).ok())
            .ok_or_else(|| bad("checksum"))?;
        let run = run
            .strip_prefix("run ")
            .ok_or_else(|| bad("run"))?
            .to_string();
        Ok(Self {
            index,
            count,
            rows,
            checksum,
            run,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_round_trips() {
        let info = ShardInfo {
            index: 2,
            count: 5,
            rows: 150,
            checksum: checksum(b"value,period\n"),
            run: "rotor-rub 0.1.0; from 1 to 2".into(),
        };
        let line = info.line();
        assert_eq!(ShardInfo::parse(line.trim_end()), Ok(info));
        assert!(ShardInfo::parse("value,period,x").is_err());
        assert!(ShardInfo::parse("# rotor-rub sweep shard 3/3; rows 1; fnv1a64 0; run x").is_err());
    }

    #[test]
    fn checksum_is_fnv1a() {
        // Published FNV-1a 64 test vectors.
        assert_eq!(checksum(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(checksum(b"a"), 0xaf63_dc4c_8601_ec8c);
    }
}
