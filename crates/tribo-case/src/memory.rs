//! Memory before solving: an estimate of a case's peak memory, so that a front end can refuse
//! a case that would not fit before solving (the `tribo` command line: exit 2, nothing
//! written). Out of memory is otherwise an abort (the allocator) or a panic deep in a solver,
//! after minutes of work.
//!
//! The estimates are linear models in the sizes that dominate, calibrated against the peak
//! resident set (VmHWM, `/usr/bin/time -v`'s "Maximum resident set size") of release runs; the
//! test `memory_estimate_is_within_a_factor_of_two_of_the_peak` in tests/cli.rs checks the
//! factor on mid-size cases. They are deliberately on the high side (within a factor 2).

use crate::case::{FieldMethod, FieldPoints, HalfSpaceCase};

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
/// writer's buffers; per damage criterion a value per point; with `field.edge_refinement`
/// = N > 1, the refined tractions and the field's FFT buffers on the N^2 times larger grid.
pub fn half_space(case: &HalfSpaceCase) -> Estimate {
    let elements = (case.n[0] as f64) * (case.n[1] as f64);
    // Measured: 10.4 MiB at 21 x 21, 11.1 MiB at 64 x 64, 14.8 MiB at 128 x 128 (normal
    // contact with all outputs): ~280 B per element above a 10.4 MiB base. Plus the normal
    // solver's Fourier preconditioner (crates/tribo/src/solvers/normal/preconditioner.rs):
    // an unpadded periodic operator (its spectrum, 4 B, and kernel table, 8 B per element),
    // its workspace (24 B) and the preconditioned residual (8 B): ~48 B per element.
    let per_element = 400.0 + 48.0;
    let tangential = if case.friction.is_some() {
        800.0 * elements
    } else {
        0.0
    };
    let (points, field_fft, refinement) = match &case.field {
        None => (0.0, 0.0, 0.0),
        Some(f) if f.edge_refinement > 1 => {
            let p = f.n.iter().map(|&k| k as f64).product::<f64>();
            // The field's tractions on the grid N times finer per side: the reconstruction's
            // samples and the refined arrays (6 doubles per refined element); on the FFT paths
            // the per-depth buffers on the refined grid (the transformed tractions, kernels
            // and components, 10 + 3 complex arrays on the 4 times larger padded grid, twice
            // for the widening to the field box), which then dominate. Measured: sliding
            // sphere 64 x 64, x8, field 39 x 39 x 20 (FFT): peak 566 MiB, estimated 477 MiB.
            let refined = elements * (f.edge_refinement * f.edge_refinement) as f64;
            let directions = if case.friction.is_some() { 3.0 } else { 1.0 };
            let fft = match (f.points, f.method) {
                (FieldPoints::Uniform, FieldMethod::Direct) => 0.0,
                _ => (10.0 + directions) * 4.0 * 16.0 * 2.0 * refined,
            };
            (p, fft, 48.0 * refined)
        }
        Some(f) => {
            let p = f.n.iter().map(|&k| k as f64).product::<f64>();
            let fft = match f.points {
                // Per depth: six stress components on the padded grid, complex.
                FieldPoints::Centres => 6.0 * 4.0 * 16.0 * elements * 2.0,
                FieldPoints::Uniform => 0.0,
            };
            (p, fft, 0.0)
        }
    };
    let damage = case
        .damage
        .as_ref()
        .map_or(0.0, |d| (d.criteria.len() as f64 + 2.0) * 64.0 * points);
    // Rough surfaces: per rough body its heights on the grid (8 B) and, while it is drawn,
    // the generator's complex transform (16 B); the composite and its PSD transform (8 + 16
    // B); the patch labels and the flood fill's stack (4 + 8 B); the elements with material
    // (1 B, for the roughness on a roller, or on any surface). A sweep keeps the previous
    // pressure (8 B) beside the solver's arrays. A rough roller's roughness is a rough body
    // like a rough ball's.
    let rough_bodies = [&case.body1, &case.body2]
        .iter()
        .filter(|b| b.roughness.is_some())
        .count() as f64;
    let rough = if rough_bodies > 0.0 || case.periodic || case.load_steps > 1 {
        (24.0 * rough_bodies + 24.0 + 12.0 + 8.0 + 1.0) * elements
    } else {
        0.0
    };
    // Measured maps: the heights as read, the detrended residual and the scaled copy (8 B
    // each per point of the map), whatever the grid.
    let measured: f64 = [&case.body1, &case.body2]
        .iter()
        .filter_map(|b| match &b.roughness {
            Some(crate::case::Roughness::Measured(m)) => {
                Some(24.0 * m.topography.nx() as f64 * m.topography.ny() as f64)
            }
            _ => None,
        })
        .sum();
    Estimate::new(vec![
        ("rough surfaces and sweep", rough),
        ("measured maps", measured),
        ("base", BASE_BYTES),
        ("contact grid", per_element * elements),
        ("tangential", tangential),
        ("stress field", 1100.0 * points + field_fft),
        ("edge refinement", refinement),
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

/// The estimate of a 2D case over its boundary mesh: [`bem`] with the interior points of
/// the default triangle size (1/40 of the model's extent), about 3200 per region and step.
pub fn bem_case(
    case: &crate::bem::case::BemCase,
    mesh: &tribo::operators::bem2d::BemMesh,
) -> Estimate {
    bem(
        mesh.dof(),
        3200 * mesh.regions.len() * case.steps.len().max(1),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn human_sizes() {
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
    }
}
