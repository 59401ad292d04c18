//! Memory before solving: an estimate of a case's peak memory, what the machine has, and the
//! refusal (exit 2, nothing written) when the case would not fit. Out of memory is otherwise
//! an abort (the allocator) or a panic deep in a solver, after minutes of work.
//!
//! The estimates are linear models in the sizes that dominate, calibrated against the peak
//! resident set (VmHWM, `/usr/bin/time -v`'s "Maximum resident set size") of release runs; the
//! test `memory_estimate_is_within_a_factor_of_two_of_the_peak` in tests/cli.rs checks the
//! factor on mid-size cases. They are deliberately on the high side (within a factor 2).

use crate::case::{Case, FieldPoints};
use crate::error::{CliError, CliResult};

/// Largest case file read, bytes: the largest example is ~10 KiB; a case file is a few
/// hundred lines of TOML (height maps and meshes are separate files). The TOML parser needs
/// ~80 times a file's size (a 50 MB file took 3.9 GB), so a larger file is refused before
/// reading.
pub const MAX_CASE_FILE_BYTES: u64 = 16 << 20;

/// Resident memory of the process before any case-dependent allocation (binary, fonts of the
/// plots, the PNG canvases), bytes.
const BASE_BYTES: f64 = 12.0 * 1048576.0;

/// A case's estimated peak memory and its main parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The total, bytes.
    pub bytes: u64,
    /// The parts (name, bytes), largest first.
    pub parts: Vec<(&'static str, u64)>,
}

impl Estimate {
    fn new(parts: Vec<(&'static str, f64)>) -> Self {
        let mut parts: Vec<(&'static str, u64)> = parts
            .into_iter()
            .filter(|p| p.1 > 0.0)
            .map(|(n, b)| (n, b.min(u64::MAX as f64) as u64))
            .collect();
        parts.sort_by_key(|p| std::cmp::Reverse(p.1));
        let bytes = parts.iter().fold(0u64, |s, p| s.saturating_add(p.1));
        Estimate { bytes, parts }
    }

    /// One line: the total and the parts.
    pub fn describe(&self) -> String {
        let parts: Vec<String> = self
            .parts
            .iter()
            .map(|(n, b)| format!("{n} {}", human(*b)))
            .collect();
        format!("about {} ({})", human(self.bytes), parts.join(", "))
    }
}

/// Bytes as "12.3 MiB".
pub fn human(bytes: u64) -> String {
    let b = bytes as f64;
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let k = ((b.max(1.0).log2() / 10.0).floor() as usize).min(units.len() - 1);
    if k == 0 {
        format!("{bytes} B")
    } else {
        format!("{:.1} {}", b / (1u64 << (10 * k)) as f64, units[k])
    }
}

/// The half-space pipeline's peak: per contact element the normal solver's FFT buffers
/// (influence spectra and work arrays on the 2nx x 2ny padded grid) and the element arrays of
/// the outputs; per field point the stress tensor, the derived quantities and the VTK
/// writer's buffers; per damage criterion a value per point.
pub fn half_space(case: &Case) -> Estimate {
    let elements = (case.n[0] as f64) * (case.n[1] as f64);
    // Measured: 10.4 MiB at 21 x 21, 11.1 MiB at 64 x 64, 14.8 MiB at 128 x 128 (normal
    // contact with all outputs): ~280 B per element above a 10.4 MiB base.
    let per_element = 400.0;
    let tangential = if case.friction.is_some() {
        800.0 * elements
    } else {
        0.0
    };
    let (points, field_fft) = match &case.field {
        None => (0.0, 0.0),
        Some(f) => {
            let p = f.n.iter().map(|&k| k as f64).product::<f64>();
            let fft = match f.points {
                // Per depth: six stress components on the padded grid, complex.
                FieldPoints::Centres => 6.0 * 4.0 * 16.0 * elements * 2.0,
                FieldPoints::Uniform => 0.0,
            };
            (p, fft)
        }
    };
    let damage = case
        .damage
        .as_ref()
        .map_or(0.0, |d| (d.criteria.len() as f64 + 2.0) * 64.0 * points);
    Estimate::new(vec![
        ("base", BASE_BYTES),
        ("contact grid", per_element * elements),
        ("tangential", tangential),
        ("stress field", 1100.0 * points + field_fft),
        ("damage", damage),
    ])
}

/// The 2D boundary element pipeline's peak for `dof` boundary unknowns and `interior` field
/// points: the dense H and G (dof x dof each), the assembled system and its LU factors, the
/// contact condensation (a dof x dof block at most), and the interior fields.
///
/// Measured: 35.2 MiB for the gmsh Hertz example (1004 unknowns), 141 MiB for
/// clamp-knife-base (2096 unknowns, 2 steps): ~4 dense matrices (3.2 and 3.8 x 8 dof^2).
///
/// Computed here from the DOF count until the library offers its own estimate (task B's
/// `memory_estimate()`); this function is the one place to call it from then.
pub fn bem(dof: usize, interior: usize) -> Estimate {
    let d = dof as f64;
    Estimate::new(vec![
        ("base", BASE_BYTES),
        ("dense H, G", 2.0 * 8.0 * d * d),
        ("system and LU", 2.0 * 8.0 * d * d),
        ("condensation", 4.0 * d * d),
        ("interior fields", 800.0 * interior as f64),
    ])
}

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
    Err(CliError::field(
        "memory",
        estimate.describe(),
        format!(
            "the case needs more than the {} allowed by {source}; reduce grid.n, the field's n \
             or the mesh (or raise --max-memory)",
            human(limit)
        ),
    ))
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
        assert_eq!(human(100 << 20), "100.0 MiB");
        assert_eq!(human(512), "512 B");
    }

    #[test]
    fn bem_grows_with_the_square_of_the_unknowns() {
        let a = bem(1000, 0).bytes as f64 - BASE_BYTES;
        let b = bem(2000, 0).bytes as f64 - BASE_BYTES;
        assert!((b / a - 4.0).abs() < 1e-9);
        // 3000 quadratic elements, 12000 unknowns: 4.8 GiB, refused under 4 GiB.
        let e = bem(12000, 0);
        assert!(e.bytes > 4 << 30 && e.bytes < 6 << 30, "{}", e.describe());
        assert!(check(&e, Some(4 << 30)).is_err());
        assert!(check(&e, Some(8 << 30)).is_ok());
    }
}
