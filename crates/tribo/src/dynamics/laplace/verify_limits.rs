//! A limit of the collocation BEM found by the verification (docs/theory/DYNAMICS.md sec.
//! 5.6, "Stability"): very coarse regions have spurious exponentially growing modes (poles
//! of the semi-discrete transfer function in Re s > 0). A CQ run shows them when its
//! numerical dissipation at their frequencies is weaker than their growth: the 2-stage
//! Radau IIA method at c1 dt/h = 0.25 and 0.05, BDF2 at 0.05 and, slowly, 0.25 (not at 1,
//! 4). On the
//! unit square clamped at the bottom (2000 steps, growth per transit time h/c1): 1 element
//! per side (4 around): Radau IIA +2.7e-2 (0.25), +1.9e-1 (0.05), BDF2 +1.6e-1 (0.05),
//! +2.5e-3 (0.25, from 2e-6 of the early maximum after 10^4 steps);
//! 2 per side (8 around): Radau IIA +1.6e-2, BDF2 +9.8e-2; 4 per side (16 around): Radau
//! IIA +2.3e-6 (late/early maximum 0.99), BDF2 +4.0e-4 (1.15), bounded; 8 per side: Radau
//! IIA -1.9e-4 (0.97). The criterion below flags the regions under that measured threshold,
//! for a pipeline to warn.

use crate::dynamics::cq::CqMethod;
use crate::dynamics::laplace::LaplaceBem;

/// The fewest boundary elements of a region for which the runs were bounded (16 = 4 per
/// side of the square; 8 grew).
pub const MIN_ELEMENTS: usize = 16;

/// c1 dt / h from which BDF1/BDF2 damp the spurious modes of a coarse region (on the square
/// with one element per side, 10^4 steps, BDF2 decayed at 1 and 4 and grew at 0.25 and
/// 0.05).
pub const MIN_BDF_STEP_RATIO: f64 = 1.0;

/// A region below [`MIN_ELEMENTS`] run with a method and step that showed growth there.
#[derive(Debug, Clone, PartialEq)]
pub struct CoarseRegion {
    /// The region's name.
    pub region: String,
    /// Its boundary elements (holes included).
    pub elements: usize,
    /// c1 dt / h with h its longest element chord (m) and c1 its P-wave speed (m/s).
    pub step_ratio: f64,
}

impl std::fmt::Display for CoarseRegion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "region '{}' has {} boundary elements (fewer than {MIN_ELEMENTS}) and \
             c1 dt/h = {:.3}: spurious growing modes of the collocation BEM were measured on \
             such coarse regions with Radau IIA at any step and with BDF2 below \
             c1 dt/h = {MIN_BDF_STEP_RATIO} (docs/theory/DYNAMICS.md sec. 5.6); refine the region",
            self.region, self.elements, self.step_ratio
        )
    }
}

/// The regions of `bem` with fewer than [`MIN_ELEMENTS`] boundary elements run with
/// `method` at the step `dt` (s) where the growth was measured: a Runge-Kutta method at any
/// step, BDF1/BDF2 at c1 dt/h < [`MIN_BDF_STEP_RATIO`].
pub fn coarse_regions(bem: &LaplaceBem, method: CqMethod, dt: f64) -> Vec<CoarseRegion> {
    let problem = bem.static_problem();
    problem
        .mesh
        .regions
        .iter()
        .zip(bem.kernels())
        .filter(|(r, _)| r.local_elements.len() < MIN_ELEMENTS)
        .filter_map(|(r, kernel)| {
            let h = r
                .local_elements
                .iter()
                .map(|e| e.chord_length())
                .fold(0.0, f64::max);
            let step_ratio = kernel.p_wave_speed() * dt / h;
            (method.is_runge_kutta() || step_ratio < MIN_BDF_STEP_RATIO).then(|| CoarseRegion {
                region: r.name.clone(),
                elements: r.local_elements.len(),
                step_ratio,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

    /// The clamped square of the stability runs with 1, 2 elements per side is flagged for
    /// Radau IIA (where it grew) and for BDF2 at c1 dt/h = 0.05 and 0.25, not 1; with 4 per
    /// side it is not flagged (where the runs stayed bounded).
    #[test]
    fn coarse_regions_match_the_measured_threshold() {
        let bcs = BoundaryConditions::new()
            .set("bottom", SegmentBc::fixed())
            .set("top", SegmentBc::Pressure(Profile::Uniform(1.0)));
        for (n, flagged) in [(1, true), (2, true), (4, false)] {
            let model = crate::validation::dyn_verify::rectangle(1.0, 1.0, n, n).unwrap();
            let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[]).unwrap();
            let h = 1.0 / n as f64;
            let dt = |ratio: f64| ratio * h / 3.0_f64.sqrt();
            let c = coarse_regions(&bem, CqMethod::RadauIia2, dt(0.25));
            assert_eq!(!c.is_empty(), flagged, "{n} per side: {c:?}");
            if flagged {
                assert_eq!(c[0].elements, 4 * n);
                assert!((c[0].step_ratio - 0.25).abs() < 1e-12, "{c:?}");
                assert!(c[0].to_string().contains("region 'block'"));
            }
            for ratio in [0.05, 0.25] {
                let bdf = coarse_regions(&bem, CqMethod::Bdf2, dt(ratio));
                assert_eq!(!bdf.is_empty(), flagged, "{n} per side, {ratio}: {bdf:?}");
            }
            assert!(coarse_regions(&bem, CqMethod::Bdf2, dt(1.0)).is_empty());
        }
    }
}
