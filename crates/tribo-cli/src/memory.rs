//! Memory before solving, the command line's part: what the machine has, `--max-memory`, and
//! the refusal (exit 2, nothing written) when the case's estimate
//! ([`tribo_case::memory`]) would not fit.

use crate::exit::{CliError, CliResult};
pub use tribo_case::memory::*;
use tribo_case::CaseError;

/// The memory this process may use, bytes, and where the figure comes from: the smaller of
/// `/proc/meminfo`'s MemAvailable and the cgroup's limit (`/sys/fs/cgroup/memory.max` less
/// `memory.current`); None where neither can be read (not Linux).
pub fn available() -> Option<(u64, &'static str)> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().strip_suffix("kB"))
            .and_then(|v| v.trim().parse::<u64>().ok())
            .map(|kb| kb.saturating_mul(1024))
    });
    let read = |p: &str| {
        std::fs::read_to_string(p)
            .ok()
            .and_then(|t| t.trim().parse::<u64>().ok())
    };
    let cgroup = read("/sys/fs/cgroup/memory.max")
        .map(|max| max.saturating_sub(read("/sys/fs/cgroup/memory.current").unwrap_or(0)));
    match (meminfo, cgroup) {
        (Some(m), Some(c)) if c < m => Some((c, "the cgroup limit /sys/fs/cgroup/memory.max")),
        (Some(m), _) => Some((m, "MemAvailable in /proc/meminfo")),
        (None, Some(c)) => Some((c, "the cgroup limit /sys/fs/cgroup/memory.max")),
        (None, None) => None,
    }
}

/// A size such as "4 GiB", "100MiB", "512 MB", "2G" or "1000000" (bytes). Binary (KiB, MiB,
/// GiB, TiB; K, M, G, T) and decimal (kB, MB, GB, TB) units.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let x: f64 = num
        .parse()
        .map_err(|_| format!("{text:?} is not a size: a number and a unit, e.g. \"4 GiB\""))?;
    let factor: f64 = match unit.trim() {
        "" | "B" => 1.0,
        "KiB" | "K" | "k" => 1024.0,
        "MiB" | "M" => 1048576.0,
        "GiB" | "G" => 1073741824.0,
        "TiB" | "T" => 1099511627776.0,
        "kB" | "KB" => 1e3,
        "MB" => 1e6,
        "GB" => 1e9,
        "TB" => 1e12,
        other => {
            return Err(format!(
                "unknown unit {other:?} in {text:?}: use B, KiB, MiB, GiB, TiB (or kB, MB, GB, TB)"
            ))
        }
    };
    let bytes = x * factor;
    if !(1.0..1.8e19).contains(&bytes) {
        return Err(format!("{text:?} is not a size between 1 B and 16 EiB"));
    }
    Ok(bytes as u64)
}

/// Refuses (exit 2, naming `--max-memory` or the machine's figure) an estimate above the
/// limit: `max` where given, else what the machine has.
pub fn check(estimate: &Estimate, max: Option<u64>) -> CliResult<()> {
    let (limit, source) = match max {
        Some(m) => (m, "--max-memory".to_string()),
        None => match available() {
            Some((a, s)) => (a, s.to_string()),
            None => return Ok(()),
        },
    };
    if estimate.bytes <= limit {
        return Ok(());
    }
    Err(CliError::Case(CaseError::field(
        "memory",
        estimate.describe(),
        format!(
            "the case needs more than the {} allowed by {source}; reduce grid.n, the field's n \
             or the mesh (or raise --max-memory)",
            human(limit)
        ),
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes() {
        assert_eq!(parse_size("4 GiB").unwrap(), 4 << 30);
        assert_eq!(parse_size("100MiB").unwrap(), 100 << 20);
        assert_eq!(parse_size("512 MB").unwrap(), 512_000_000);
        assert_eq!(parse_size("2G").unwrap(), 2 << 30);
        assert_eq!(parse_size("1000").unwrap(), 1000);
        assert_eq!(parse_size("1.5 KiB").unwrap(), 1536);
        for bad in ["", "GiB", "4 GB/s", "-1 GiB", "0", "1e30 TiB", "four"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_large_bem_case_is_refused_under_its_estimate() {
        // 3000 quadratic elements, 12000 unknowns: 4.8 GiB, refused under 4 GiB.
        let e = bem(12000, 0);
        assert!(check(&e, Some(4 << 30)).is_err());
        assert!(check(&e, Some(8 << 30)).is_ok());
    }
}
