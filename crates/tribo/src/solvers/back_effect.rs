//! The back effect of bulk loading on the contact (the paper's Sec. 3, (18), Fig. 2a): at a
//! fixed rigid approach of roller and shaft, a bulk stress sigma moves the shaft surface by
//! u_z (18) and so changes the contact force.

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::grid::SurfaceGrid;
use crate::kernels::bulk::{hertz_force_ratio, BulkLoad};
use crate::material::ElasticMaterial;
use crate::operators::ConvolutionOperator;
use crate::solvers::normal::{
    normal_compliance_operator, solve_normal, NormalContactParams, NormalContactProblem,
    NormalLoading, NormalMethod,
};
use crate::solvers::{SolveError, SolveResult};

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

/// The back-effect problem: the contact at a fixed rigid approach under a list of bulk
/// loads.
#[derive(Debug, Clone, Copy)]
pub struct BackEffectProblem<'a> {
    /// The surface window.
    pub grid: &'a SurfaceGrid,
    /// Initial separation h(x, y) at element centres, m (grid layout).
    pub initial_gap: &'a [f64],
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
    /// The shaft's material (u_z of (18)).
    pub shaft: ElasticMaterial,
    /// The shaft's radius, m.
    pub shaft_radius: f64,
    /// The rigid approach delta_0 without bulk load, m (> 0).
    pub initial_approach: f64,
    /// The bulk loads, one curve point each.
    pub loads: &'a [BulkLoad],
}

/// The contact at the fixed rigid approach `problem.initial_approach` under each of
/// `problem.loads`: the contact force (approach control at `delta_0 + u_z`, u_z by (18)),
/// relative to the force without bulk load. One FFT operator serves all points: `operator`
/// is [`normal_compliance_operator`]`(grid, composite_modulus)` where the caller has one,
/// `None` builds it. `params` are those of each normal solve (the conjugate gradient; the
/// method field is not used). `observer(done, total)` is called after the reference solution
/// and after each point (`total = loads.len() + 1`), e.g. to drive a progress bar.
///
/// Errors: those of the normal solves (a point without contact has force 0, no error); the
/// output holds the points solved before the failing one.
pub fn back_effect_curve(
    problem: &BackEffectProblem<'_>,
    params: &NormalContactParams,
    operator: Option<&ConvolutionOperator>,
    observer: Option<&mut dyn FnMut(usize, usize)>,
) -> SolveResult<Vec<BackEffectPoint>> {
    let BackEffectProblem {
        grid,
        initial_gap,
        composite_modulus,
        shaft,
        shaft_radius,
        initial_approach,
        loads,
    } = *problem;
    let mut silent = |_: usize, _: usize| {};
    let progress = observer.unwrap_or(&mut silent);
    let total = loads.len() + 1;
    if !(initial_approach.is_finite() && initial_approach > 0.0) {
        return Err(Error::invalid(
            "contact.approach",
            initial_approach,
            "must be finite and > 0 (m)",
        )
        .into());
    }
    let built;
    let operator = match operator {
        Some(op) => op,
        None => {
            built = normal_compliance_operator(grid, composite_modulus);
            &built
        }
    };
    let params = NormalContactParams {
        method: NormalMethod::ConjugateGradient,
        ..*params
    };
    let solve = |approach: f64| {
        solve_normal(
            &NormalContactProblem {
                grid,
                initial_gap,
                composite_modulus,
                loading: NormalLoading::Approach(approach),
            },
            &params,
            Some(operator),
            None,
        )
        .map_err(|e| e.kind)
    };
    let reference = solve(initial_approach)?;
    progress(1, total);
    let mut points = Vec::with_capacity(loads.len());
    for (k, load) in loads.iter().enumerate() {
        let point = (|| {
            let change = load.approach_change(&shaft, shaft_radius)?;
            let approach = initial_approach + change;
            let (normal_load, iterations) = if approach <= 0.0 {
                (0.0, 0)
            } else {
                match solve(approach) {
                    Ok(s) => (s.normal_load, s.iterations),
                    Err(Error::NoContact { .. }) => (0.0, 0),
                    Err(e) => return Err(e),
                }
            };
            Ok(BackEffectPoint {
                load: *load,
                stress: load.surface_stress(),
                approach_change: change,
                normal_load,
                force_ratio: normal_load / reference.normal_load,
                force_ratio_hertz: hertz_force_ratio(change, initial_approach),
                iterations,
            })
        })();
        match point {
            Ok(p) => points.push(p),
            Err(kind) => return Err(SolveError::with_output(kind, points)),
        }
        progress(k + 2, total);
    }
    Ok(points)
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
        let points = back_effect_curve(
            &BackEffectProblem {
                grid: &grid,
                initial_gap: &gap,
                composite_modulus: 1.1e11,
                shaft: steel,
                shaft_radius: 0.01,
                initial_approach: 4e-6,
                loads: &loads,
            },
            &NormalContactParams::default(),
            None,
            Some(&mut |done, total| seen.push((done, total))),
        )
        .unwrap();
        assert_eq!(seen, [(1, 3), (2, 3), (3, 3)]);
        assert!((points[0].force_ratio - 1.0).abs() < 1e-9);
        // Tension lowers the force (u_z < 0).
        assert!(points[1].approach_change < 0.0 && points[1].force_ratio < 1.0);
    }
}
