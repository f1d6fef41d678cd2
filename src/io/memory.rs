//! How much more memory this process may allocate: the least of what the operating system
//! has available (`MemAvailable`), what its control group allows (a Slurm job's `--mem`, a
//! container's limit: cgroup v2 `memory.max`, v1 `memory.limit_in_bytes`, less what the group
//! already holds) and what its resource limits leave (`ulimit -v`: `RLIMIT_AS` less the address
//! space in use; `RLIMIT_DATA` less the data segment). A check against `MemAvailable` alone
//! passes a job with `--mem=4G` on a 256 GB node, which the kernel then kills.

use std::fmt;
use std::path::Path;

/// What bounds the memory a run is checked against.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MemoryBound {
    /// `--max-memory` (or `max_memory=` in Python), as given.
    Given,
    /// The memory the operating system has available (`MemAvailable` of `/proc/meminfo`).
    Available,
    /// A control group's limit less its usage; the file that sets the limit.
    Cgroup(String),
    /// `RLIMIT_AS` (`ulimit -v`) less the address space in use.
    AddressSpace,
    /// `RLIMIT_DATA` (`ulimit -d`) less the data segment in use.
    DataSegment,
}

impl fmt::Display for MemoryBound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MemoryBound::Given => write!(f, "set by --max-memory"),
            MemoryBound::Available => write!(f, "the memory available, MemAvailable of /proc/meminfo"),
            MemoryBound::Cgroup(file) => write!(f, "the control group's limit {file} less what the group holds"),
            MemoryBound::AddressSpace => write!(f, "RLIMIT_AS (ulimit -v) less the address space in use"),
            MemoryBound::DataSegment => write!(f, "RLIMIT_DATA (ulimit -d) less the data segment in use"),
        }
    }
}

/// A limit in bytes and what sets it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemoryLimit {
    /// Bytes the process may still allocate.
    pub bytes: u64,
    /// What sets the limit.
    pub bound: MemoryBound,
}

/// The limit runs are checked against: `max_memory` when given, else the least of the
/// bounds this process is under ([module doc](self)); `None` where none is known.
pub fn memory_limit(max_memory: Option<u64>) -> Option<MemoryLimit> {
    if let Some(bytes) = max_memory {
        return Some(MemoryLimit { bytes, bound: MemoryBound::Given });
    }
    let available = available_memory().map(|b| (b, MemoryBound::Available));
    let cgroup = std::fs::read_to_string("/proc/self/cgroup")
        .ok()
        .and_then(|text| cgroup_headroom(Path::new("/sys/fs/cgroup"), &text))
        .map(|(b, file)| (b, MemoryBound::Cgroup(file)));
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let rlimits = rlimit_headrooms(&status);
    least([available, cgroup].into_iter().flatten().chain(rlimits))
}

/// Memory the operating system can still give this process, in bytes (`MemAvailable` of
/// `/proc/meminfo`); `None` where that is not known.
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The least of `bounds` (the first of equal ones).
fn least(bounds: impl IntoIterator<Item = (u64, MemoryBound)>) -> Option<MemoryLimit> {
    bounds
        .into_iter()
        .fold(None, |best: Option<(u64, MemoryBound)>, b| match best {
            Some(old) if old.0 <= b.0 => Some(old),
            _ => Some(b),
        })
        .map(|(bytes, bound)| MemoryLimit { bytes, bound })
}

/// Limits at or above this are "no limit" (v1 writes 2⁶³ rounded to a page).
const UNLIMITED: u64 = 1 << 60;

/// The least headroom (limit less usage) of the memory control groups this process is in and
/// their ancestors, under `root` (`/sys/fs/cgroup`), read from `proc_cgroup` (the text of
/// `/proc/self/cgroup`); with the file that sets it.
pub fn cgroup_headroom(root: &Path, proc_cgroup: &str) -> Option<(u64, String)> {
    let mut found: Vec<(u64, String)> = Vec::new();
    for line in proc_cgroup.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(_), Some(controllers), Some(path)) = (parts.next(), parts.next(), parts.next()) else { continue };
        // (mount below `root`, limit file, usage file)
        let layouts: &[(&str, &str, &str)] = if controllers.is_empty() {
            &[("", "memory.max", "memory.current"), ("unified", "memory.max", "memory.current")]
        } else if controllers.split(',').any(|c| c == "memory") {
            &[("memory", "memory.limit_in_bytes", "memory.usage_in_bytes")]
        } else {
            continue;
        };
        for &(mount, limit_file, usage_file) in layouts {
            let base = root.join(mount);
            // The group itself and each ancestor up to the mount (a container sees its own
            // group as the mount's root, and its path may not exist below it).
            let mut dir = Some(Path::new(path.trim_start_matches('/')));
            while let Some(d) = dir {
                let group = base.join(d);
                let read = |f: &str| std::fs::read_to_string(group.join(f)).ok()?.trim().parse::<u64>().ok();
                if let Some(limit) = read(limit_file).filter(|&l| l < UNLIMITED) {
                    let used = read(usage_file).unwrap_or(0);
                    found.push((limit.saturating_sub(used), group.join(limit_file).display().to_string()));
                }
                dir = d.parent();
            }
        }
    }
    found.into_iter().min_by_key(|(b, _)| *b)
}

/// The headroom `RLIMIT_AS` and `RLIMIT_DATA` leave, from their soft limits and the `VmSize`
/// and `VmData` lines of `status` (the text of `/proc/self/status`).
fn rlimit_headrooms(status: &str) -> Vec<(u64, MemoryBound)> {
    headrooms(status, soft_limit(Resource::AddressSpace), soft_limit(Resource::Data))
}

/// The headroom of an address-space limit `as_limit` and a data limit `data_limit` (bytes;
/// `None` for none) for a process whose `/proc/self/status` reads `status`.
fn headrooms(status: &str, as_limit: Option<u64>, data_limit: Option<u64>) -> Vec<(u64, MemoryBound)> {
    let in_use = |key: &str| -> u64 {
        let kib = status.lines().find_map(|l| l.strip_prefix(key)?.split_whitespace().next()?.parse::<u64>().ok());
        kib.unwrap_or(0) * 1024
    };
    [(as_limit, "VmSize:", MemoryBound::AddressSpace), (data_limit, "VmData:", MemoryBound::DataSegment)]
        .into_iter()
        .filter_map(|(limit, key, bound)| {
            let limit = limit.filter(|&l| l < UNLIMITED)?;
            Some((limit.saturating_sub(in_use(key)), bound))
        })
        .collect()
}

#[derive(Clone, Copy)]
enum Resource {
    AddressSpace,
    Data,
}

/// The soft limit on `resource`, `None` where unlimited or unknown.
#[cfg(unix)]
fn soft_limit(resource: Resource) -> Option<u64> {
    let which = match resource {
        Resource::AddressSpace => libc::RLIMIT_AS,
        Resource::Data => libc::RLIMIT_DATA,
    };
    let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: `getrlimit` writes the struct it is given and nothing else.
    let rc = unsafe { libc::getrlimit(which, &mut lim) };
    // `rlim_t` is 64 bits here, narrower or wider elsewhere.
    #[allow(clippy::unnecessary_cast)]
    let limit = lim.rlim_cur as u64;
    (rc == 0 && lim.rlim_cur != libc::RLIM_INFINITY).then_some(limit)
}

#[cfg(not(unix))]
fn soft_limit(_: Resource) -> Option<u64> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_least_bound_is_taken_and_named() {
        let l = least([
            (8_000, MemoryBound::Available),
            (3_000, MemoryBound::Cgroup("memory.max".into())),
            (5_000, MemoryBound::AddressSpace),
        ])
        .unwrap();
        assert_eq!(l, MemoryLimit { bytes: 3_000, bound: MemoryBound::Cgroup("memory.max".into()) });
        assert!(least([]).is_none());
        assert_eq!(memory_limit(Some(7)).unwrap(), MemoryLimit { bytes: 7, bound: MemoryBound::Given });
    }

    #[test]
    fn cgroup_limits_are_read_for_v2_and_v1_and_ancestors() {
        let root = tempfile::tempdir().unwrap();
        let w = |rel: &str, text: &str| {
            let p = root.path().join(rel);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, text).unwrap();
        };
        // v2: a job step below a job whose limit is the smaller headroom.
        w("job/step/memory.max", "max\n");
        w("job/step/memory.current", "100\n");
        w("job/memory.max", "4000000000\n");
        w("job/memory.current", "1000000000\n");
        let (bytes, file) = cgroup_headroom(root.path(), "0::/job/step\n").unwrap();
        assert_eq!(bytes, 3_000_000_000);
        assert!(file.ends_with("job/memory.max"), "{file}");
        // v1: the memory controller's line only; an unlimited root is no limit.
        w("memory/memory.limit_in_bytes", "9223372036854771712\n");
        w("memory/slurm/memory.limit_in_bytes", "2000\n");
        w("memory/slurm/memory.usage_in_bytes", "500\n");
        let text = "5:cpu:/slurm\n4:memory:/slurm\n0::/\n";
        assert_eq!(cgroup_headroom(root.path(), text).map(|(b, _)| b), Some(1500));
        assert_eq!(cgroup_headroom(root.path(), "4:memory:/\n"), None);
        assert_eq!(cgroup_headroom(root.path(), "garbage"), None);
    }

    #[test]
    fn rlimit_headroom_subtracts_what_is_in_use() {
        let status = "Name:\tcovga\nVmSize:\t  2048 kB\nVmData:\t  1024 kB\n";
        let h = headrooms(status, Some(1 << 22), Some(1 << 30));
        assert_eq!(
            h,
            vec![
                ((1 << 22) - 2048 * 1024, MemoryBound::AddressSpace),
                ((1 << 30) - 1024 * 1024, MemoryBound::DataSegment)
            ]
        );
        assert_eq!(headrooms(status, None, Some(u64::MAX)), vec![]);
        assert_eq!(headrooms(status, Some(1000), None), vec![(0, MemoryBound::AddressSpace)]);
    }
}
