//! The back effect of bulk loading on the contact (the paper's Sec. 3, (18), Fig. 2a): at a
//! fixed rigid approach of roller and shaft, a bulk stress sigma moves the shaft surface by
//! u_z (18) and so changes the contact force.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::bulk::{hertz_force_ratio, BulkLoad};
use crate::material::ElasticMaterial;
use crate::solvers::normal::{
    normal_compliance_operator, solve_normal_cg_with, NormalContactParams, NormalLoading,
};

/// One point of the curve of Fig. 2a.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BackEffectPoint {
    /// The bulk load.
    pub load: BulkLoad,
    /// Axial stress at the contact, Pa.
    pub stress: f64,
    /// Change of the elastic approach u_z (18), m.
    pub approach_change: f64,
    /// Contact force from the numerical solution, N.
    pub normal_load: f64,
    /// F / F(sigma = 0), numerical.
    pub force_ratio: f64,
    /// F / F(sigma = 0) by the Hertz estimate `(1 + u_z / delta_0)^(3/2)`.
    pub force_ratio_hertz: f64,
    /// CG iterations of this point.
    pub iterations: usize,
}

/// The contact at a fixed rigid approach `initial_approach` (m) under the bulk loads
/// `loads`: the contact force for each (approach control at `delta_0 + u_z`), relative to
/// the force without bulk load. One FFT operator serves all points.
///
/// `initial_gap` is sampled on `grid` (m), `composite_modulus` is E* (Pa), `shaft` and
/// `shaft_radius` (m) define u_z by (18).
#[allow(clippy::too_many_arguments)]
pub fn back_effect_curve(
    grid: &SurfaceGrid,
    initial_gap: &[f64],
    composite_modulus: f64,
    shaft: &ElasticMaterial,
    shaft_radius: f64,
    initial_approach: f64,
    loads: &[BulkLoad],
    params: &NormalContactParams,
) -> Result<Vec<BackEffectPoint>> {
    back_effect_curve_observed(
        grid,
        initial_gap,
        composite_modulus,
        shaft,
        shaft_radius,
        initial_approach,
        loads,
        params,
        &mut |_, _| {},
    )
}

/// [`back_effect_curve`] with a progress observer, called as `progress(done, total)` after
/// the reference solution and after each point (`total = loads.len() + 1`), e.g. to drive
/// a progress bar.
#[allow(clippy::too_many_arguments)]
pub fn back_effect_curve_observed(
    grid: &SurfaceGrid,
    initial_gap: &[f64],
    composite_modulus: f64,
    shaft: &ElasticMaterial,
    shaft_radius: f64,
    initial_approach: f64,
    loads: &[BulkLoad],
    params: &NormalContactParams,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<BackEffectPoint>> {
    let total = loads.len() + 1;
    if !(initial_approach.is_finite() && initial_approach > 0.0) {
        return Err(Error::invalid(
            "contact.approach",
            initial_approach,
            "must be finite and > 0 (m)",
        ));
    }
    let operator = normal_compliance_operator(grid, composite_modulus);
    let mut workspace = operator.workspace();
    let reference = solve_normal_cg_with(
        &operator,
        &mut workspace,
        initial_gap,
        NormalLoading::Approach(initial_approach),
        params,
        &mut |_, _| {},
    )?;
    progress(1, total);
    loads
        .iter()
        .enumerate()
        .map(|(k, load)| {
            let change = load.approach_change(shaft, shaft_radius)?;
            let approach = initial_approach + change;
            let (normal_load, iterations) = if approach <= 0.0 {
                (0.0, 0)
            } else {
                match solve_normal_cg_with(
                    &operator,
                    &mut workspace,
                    initial_gap,
                    NormalLoading::Approach(approach),
                    params,
                    &mut |_, _| {},
                ) {
                    Ok(s) => (s.normal_load, s.iterations),
                    Err(Error::NoContact { .. }) => (0.0, 0),
                    Err(e) => return Err(e),
                }
            };
            progress(k + 2, total);
            Ok(BackEffectPoint {
                load: *load,
                stress: load.surface_stress(),
                approach_change: change,
                normal_load,
                force_ratio: normal_load / reference.normal_load,
                force_ratio_hertz: hertz_force_ratio(change, initial_approach),
                iterations,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_observer_sees_every_solution_and_zero_stress_is_the_reference() {
        // A sphere-like gap h = (x^2 + y^2) / (2 R), R = 10 mm, steel.
        let steel = ElasticMaterial::new(2.01e11, 0.3).unwrap();
        let grid = SurfaceGrid::centred(16, 16, 4e-4, 4e-4).unwrap();
        let gap = grid.sample(|x, y| (x * x + y * y) / 0.02);
        let loads = [
            BulkLoad::Bending {
                surface_stress: 0.0,
            },
            BulkLoad::TensionCompression { stress: 3e8 },
        ];
        let mut seen = Vec::new();
        let points = back_effect_curve_observed(
            &grid,
            &gap,
            1.1e11,
            &steel,
            0.01,
            4e-6,
            &loads,
            &NormalContactParams::default(),
            &mut |done, total| seen.push((done, total)),
        )
        .unwrap();
        assert_eq!(seen, [(1, 3), (2, 3), (3, 3)]);
        assert!((points[0].force_ratio - 1.0).abs() < 1e-9);
        // Tension lowers the force (u_z < 0).
        assert!(points[1].approach_change < 0.0 && points[1].force_ratio < 1.0);
    }
}
