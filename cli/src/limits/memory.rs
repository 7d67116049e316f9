//! How much memory a command may fill with the data it keeps: half of the least of what bounds
//! the process — the physical memory, its cgroup's memory limit (cgroup v2 `memory.max`, v1
//! `memory.limit_in_bytes`, the least over the cgroup and its ancestors: SLURM jobs, Kubernetes
//! pods, containers), and the address space and data size left under `ulimit -v` and `ulimit -d`
//! (RLIMIT_AS, RLIMIT_DATA, less what the process already maps). A request past it is refused
//! before it allocates; allocations that grow while a run goes are made fallibly ([`reserve`]),
//! so a limit reached anyway is the same refusal, never an abort.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::error::{CliError, Result, num};

/// The share of a bound a command may fill: half, leaving room for the copies made while data is
/// written out and for the rest of the process.
const SHARE: u64 = 2;

/// Where the share is unknown (no /proc): 4 GiB.
const UNKNOWN: u64 = 4 << 30;

/// The memory a command may fill, and what sets it (for messages).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemoryShare {
    /// Bytes.
    pub bytes: u64,
    /// What bounds it, e.g. "half the physical memory".
    pub reason: String,
}

/// This process's share, read once.
pub fn share() -> &'static MemoryShare {
    static SHARE_OF_PROCESS: OnceLock<MemoryShare> = OnceLock::new();
    SHARE_OF_PROCESS.get_or_init(|| {
        let read = |path: &Path| std::fs::read_to_string(path).ok();
        let text = |path: &str| read(Path::new(path)).unwrap_or_default();
        let bounds = Bounds {
            meminfo: &text("/proc/meminfo"),
            cgroup: &text("/proc/self/cgroup"),
            mountinfo: &text("/proc/self/mountinfo"),
            limits: &text("/proc/self/limits"),
            status: &text("/proc/self/status"),
        };
        bounds.share(read)
    })
}

/// The texts of /proc the share is read from.
struct Bounds<'a> {
    meminfo: &'a str,
    cgroup: &'a str,
    mountinfo: &'a str,
    limits: &'a str,
    status: &'a str,
}

impl Bounds<'_> {
    /// The least of the bounds found, halved; [`UNKNOWN`] when none is. `read` reads a file of
    /// the cgroup file system.
    fn share(&self, read: impl Fn(&Path) -> Option<String>) -> MemoryShare {
        let mut bounds: Vec<(u64, &str)> = Vec::new();
        if let Some(total) = kib_field(self.meminfo, "MemTotal:") {
            bounds.push((total, "half the physical memory"));
        }
        if let Some(limit) = cgroup_limit(self.cgroup, self.mountinfo, read) {
            bounds.push((limit, "half its cgroup's memory limit"));
        }
        for (limit, mapped, reason) in [
            (
                "Max address space",
                "VmSize:",
                "half of what ulimit -v leaves this process",
            ),
            (
                "Max data size",
                "VmData:",
                "half of what ulimit -d leaves this process",
            ),
        ] {
            if let Some(limit) = soft_limit(self.limits, limit) {
                let used = kib_field(self.status, mapped).unwrap_or(0);
                bounds.push((limit.saturating_sub(used), reason));
            }
        }
        match bounds.into_iter().min_by_key(|b| b.0) {
            Some((bytes, reason)) => MemoryShare {
                bytes: bytes / SHARE,
                reason: reason.to_string(),
            },
            None => MemoryShare {
                bytes: UNKNOWN,
                reason: "4 GiB: this machine's memory is unknown".to_string(),
            },
        }
    }
}

/// A `Name:   1234 kB` field of /proc/meminfo or /proc/self/status, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find_map(|l| l.strip_prefix(name))?;
    let kib: u64 = line.split_whitespace().next()?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The soft limit of a /proc/self/limits row (`Max address space  unlimited  unlimited  bytes`),
/// `None` when unlimited.
fn soft_limit(limits: &str, name: &str) -> Option<u64> {
    let row = limits.lines().find_map(|l| l.strip_prefix(name))?;
    row.split_whitespace().next()?.parse().ok()
}

/// The memory limit of this process's cgroups: the least `memory.max` (v2) or
/// `memory.limit_in_bytes` (v1) of its cgroup and every ancestor up to the mount, from the texts
/// of /proc/self/cgroup and /proc/self/mountinfo. `None` when no limit is set or found ("max",
/// or v1's "no limit" of about 2^63).
fn cgroup_limit(
    cgroup: &str,
    mountinfo: &str,
    read: impl Fn(&Path) -> Option<String>,
) -> Option<u64> {
    let mut least: Option<u64> = None;
    for line in cgroup.lines() {
        let mut fields = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) =
            (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        let (file, mount) = if id == "0" && controllers.is_empty() {
            (
                "memory.max",
                mount_of(mountinfo, |fstype, _| fstype == "cgroup2"),
            )
        } else if controllers.split(',').any(|c| c == "memory") {
            let memory = |fstype: &str, options: &str| {
                fstype == "cgroup" && options.split(',').any(|o| o == "memory")
            };
            ("memory.limit_in_bytes", mount_of(mountinfo, memory))
        } else {
            continue;
        };
        let Some((root, mount_point)) = mount else {
            continue;
        };
        // The cgroup's directory: its path below the mounted root, under the mount point.
        let below = Path::new(path)
            .strip_prefix(&root)
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut dir = mount_point.join(below);
        loop {
            let value = read(&dir.join(file)).and_then(|t| t.trim().parse::<u64>().ok());
            if let Some(limit) = value.filter(|&v| v < 1 << 62) {
                least = Some(least.map_or(limit, |l| l.min(limit)));
            }
            if dir == mount_point || !dir.pop() {
                break;
            }
        }
    }
    least
}

/// The root and mount point of the first mount in `mountinfo` whose file-system type and
/// super-block options `wanted` accepts.
fn mount_of(mountinfo: &str, wanted: impl Fn(&str, &str) -> bool) -> Option<(PathBuf, PathBuf)> {
    mountinfo.lines().find_map(|line| {
        // `id parent major:minor root mount-point options [optional…] - fstype source super`
        let (left, right) = line.split_once(" - ")?;
        let mut left = left.split_whitespace();
        let root = left.nth(3)?;
        let mount_point = left.next()?;
        let mut right = right.split_whitespace();
        let fstype = right.next()?;
        let options = right.nth(1).unwrap_or("");
        wanted(fstype, options).then(|| (PathBuf::from(root), PathBuf::from(mount_point)))
    })
}

/// Room for `additional` more items in `items` (the data `what` keeps), allocated fallibly: when
/// the allocation fails (a memory limit reached anyway) the command is refused with the usual
/// message instead of aborting.
pub fn reserve<T>(items: &mut Vec<T>, additional: usize, what: &str) -> Result<()> {
    items.try_reserve(additional).map_err(|_| {
        let count = items.len().saturating_add(additional);
        let bytes = count as f64 * std::mem::size_of::<T>() as f64;
        let share = share();
        CliError::input(format!(
            "{what}: {count} would keep {} bytes in memory, more than this process can \
             allocate (it may fill {} bytes, {}); ask for fewer",
            num(bytes),
            num(share.bytes as f64),
            share.reason
        ))
    })
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    const MEMINFO: &str = "MemTotal:       16000000 kB\nMemFree:  1000 kB\n";
    const LIMITS: &str = "Limit                     Soft Limit           Hard Limit           Units\n\
Max data size             unlimited            unlimited            bytes\n\
Max address space         1073741824           unlimited            bytes\n";
    const STATUS: &str = "Name:\trotor-rub\nVmSize:\t  102400 kB\nVmData:\t   2048 kB\n";

    fn files(entries: &[(&str, &str)]) -> impl Fn(&Path) -> Option<String> {
        let map: HashMap<PathBuf, String> = entries
            .iter()
            .map(|(p, t)| (PathBuf::from(p), t.to_string()))
            .collect();
        move |p: &Path| map.get(p).cloned()
    }

    #[test]
    fn the_least_bound_sets_the_share() {
        let none = files(&[]);
        let physical = Bounds {
            meminfo: MEMINFO,
            cgroup: "",
            mountinfo: "",
            limits: "",
            status: STATUS,
        };
        assert_eq!(physical.share(&none).bytes, 16_000_000 * 1024 / 2);
        assert_eq!(physical.share(&none).reason, "half the physical memory");
        // ulimit -v 1 GiB with 100 MiB mapped: half of the 924 MiB left.
        let limited = Bounds {
            limits: LIMITS,
            ..physical
        };
        let share = limited.share(&none);
        assert_eq!(share.bytes, (1 << 30) / 2 - 100 * 1024 * 1024 / 2);
        assert!(share.reason.contains("ulimit -v"), "{}", share.reason);
        let nothing = Bounds {
            meminfo: "",
            cgroup: "",
            mountinfo: "",
            limits: "",
            status: "",
        };
        assert_eq!(nothing.share(&none).bytes, UNKNOWN);
    }

    const MOUNTS_V2: &str = "\
25 30 0:23 / /proc rw,nosuid - proc proc rw
31 23 0:26 / /sys/fs/cgroup rw,nosuid,nodev,noexec,relatime shared:9 - cgroup2 cgroup2 rw,nsdelegate
";

    #[test]
    fn cgroup_v2_takes_the_least_limit_up_the_hierarchy() {
        let cgroup = "0::/system.slice/job.scope\n";
        let read = files(&[
            ("/sys/fs/cgroup/system.slice/job.scope/memory.max", "max\n"),
            ("/sys/fs/cgroup/system.slice/memory.max", "2147483648\n"),
            ("/sys/fs/cgroup/memory.max", "max\n"),
        ]);
        assert_eq!(cgroup_limit(cgroup, MOUNTS_V2, &read), Some(2 << 30));
        let unlimited = files(&[("/sys/fs/cgroup/system.slice/job.scope/memory.max", "max\n")]);
        assert_eq!(cgroup_limit(cgroup, MOUNTS_V2, &unlimited), None);
        // Inside a container the namespace's root is the cgroup itself.
        let read = files(&[("/sys/fs/cgroup/memory.max", "536870912\n")]);
        assert_eq!(cgroup_limit("0::/\n", MOUNTS_V2, &read), Some(512 << 20));
        let share = Bounds {
            meminfo: MEMINFO,
            cgroup: "0::/\n",
            mountinfo: MOUNTS_V2,
            limits: "",
            status: "",
        }
        .share(&read);
        assert_eq!(share.bytes, 256 << 20);
        assert_eq!(share.reason, "half its cgroup's memory limit");
    }

    #[test]
    fn cgroup_v1_reads_the_memory_controller() {
        let cgroup = "4:memory:/slurm/uid_1000/job_42\n3:cpu,cpuacct:/slurm\n0::/\n";
        let mounts = "\
35 31 0:32 / /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory
32 31 0:29 / /sys/fs/cgroup/cpu,cpuacct rw,relatime - cgroup cgroup rw,cpu,cpuacct
";
        let read = files(&[
            (
                "/sys/fs/cgroup/memory/slurm/uid_1000/job_42/memory.limit_in_bytes",
                "4294967296\n",
            ),
            (
                "/sys/fs/cgroup/memory/slurm/memory.limit_in_bytes",
                "9223372036854771712\n",
            ),
        ]);
        assert_eq!(cgroup_limit(cgroup, mounts, &read), Some(4 << 30));
        // A mount of a subtree (root /slurm): the path is taken below it.
        let subtree = "35 31 0:32 /slurm /sys/fs/cgroup/memory rw - cgroup cgroup rw,memory\n";
        let read = files(&[(
            "/sys/fs/cgroup/memory/uid_1000/job_42/memory.limit_in_bytes",
            "1073741824\n",
        )]);
        assert_eq!(cgroup_limit(cgroup, subtree, &read), Some(1 << 30));
    }

    #[test]
    fn a_failed_reservation_is_the_usual_refusal() {
        let mut items: Vec<u64> = Vec::new();
        let e = reserve(&mut items, usize::MAX / 4, "samples").unwrap_err();
        assert_eq!(e.code, crate::error::EXIT_INPUT);
        assert!(
            e.message.starts_with("samples: ") && e.message.contains("bytes in memory"),
            "{}",
            e.message
        );
        assert!(reserve(&mut items, 10, "samples").is_ok());
        assert!(items.capacity() >= 10);
    }
}
