//! Reference models of the dynamic contact tests and `tribo validate` rows.

use super::DynamicContact;
use crate::error::Result;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::contact::ContactPair;
use crate::solvers::bem2d::BoundaryConditions;

/// The two strips of the impact models (docs/theory/DYNAMICS.md sec. 4), plane strain,
/// E = 1 Pa, nu = 0: the striker on x in [-`length`, 0] (segments `s_bottom`, `s_end` at
/// x = 0, `s_top`, `s_back`) and the target on [0, `length`] (`t_bottom`, `t_back`, `t_top`,
/// `t_end` at x = 0), both `width` high (m), touching along x = 0; `nx` x `ny` quadratic
/// elements along and across each. Used by the tests, the `tribo validate` rows and the
/// impact benchmark.
pub fn two_rods(length: f64, width: f64, nx: usize, ny: usize) -> Result<BemModel> {
    let m = ElasticMaterial::new(1.0, 0.0)?;
    let (l, w) = (length, width);
    let striker = Region::new(
        "striker",
        m,
        vec![
            Segment::line("s_bottom", [-l, 0.0], [0.0, 0.0], nx),
            Segment::line("s_end", [0.0, 0.0], [0.0, w], ny),
            Segment::line("s_top", [0.0, w], [-l, w], nx),
            Segment::line("s_back", [-l, w], [-l, 0.0], ny),
        ],
    );
    let target = Region::new(
        "target",
        m,
        vec![
            Segment::line("t_bottom", [0.0, 0.0], [l, 0.0], nx),
            Segment::line("t_back", [l, 0.0], [l, w], ny),
            Segment::line("t_top", [l, w], [0.0, w], nx),
            Segment::line("t_end", [0.0, w], [0.0, 0.0], ny),
        ],
    );
    Ok(BemModel::new(PlaneCondition::Strain, vec![striker, target]))
}

/// Rod impact (docs/theory/DYNAMICS.md sec. 4): two identical strips L = 1 by W = 0.25
/// (E = 1, nu = 0, rho = 1: c = 1, plane strain), the striker on x in [-L, 0] with velocity
/// `v0` along +x, the target on [0, L] at rest, touching at x = 0 (frictionless pair
/// striker end / target end); `nx` x `ny` quadratic elements along and across each; every
/// face free. Exact: contact stress rho c v0 / 2, duration 2 L / c, then striker at rest
/// and target at v0.
pub(crate) fn rod_impact_model(nx: usize, ny: usize, v0: f64) -> Result<DynamicContact> {
    let model = two_rods(1.0, 0.25, nx, ny)?;
    DynamicContact::new(
        &model,
        &[1.0, 1.0],
        &BoundaryConditions::new(),
        &[ContactPair::new("s_end", "t_end", 0.0)],
        &[],
        &[[v0, 0.0], [0.0, 0.0]],
    )
}

/// The rod impact's measured quantities for v0 = 1 (see [`RodImpact`]).
pub(crate) fn rod_impact(
    method: crate::dynamics::cq::CqMethod,
    dt: f64,
    nx: usize,
    ny: usize,
) -> Result<RodImpact> {
    let problem = rod_impact_model(nx, ny, 1.0)?;
    let steps = (3.0 / dt).round() as usize;
    let params = super::DynamicContactParams::new(dt, steps).with_method(method);
    let res = problem.march(&params, &mut |_| {})?;
    let (mut sum, mut count, mut dev) = (0.0, 0.0, 0.0_f64);
    let (mut start, mut end) = (None, None);
    for s in &res.steps {
        let pr = &s.pairs[0];
        let touching = pr.sample.length > 0.0;
        if touching && start.is_none() {
            start = Some(s.time);
        }
        if !touching && start.is_some() && end.is_none() {
            end = Some(s.time);
        }
        if (0.25..=1.25).contains(&s.time) {
            sum += pr.sample.normal_force / 0.25;
            count += 1.0;
            for n in &pr.nodes {
                dev = dev.max((n.pressure - 0.5).abs());
            }
        }
    }
    let e = &res.steps[res.steps.len() - 1].energy;
    let (bs, bt) = (&e.bodies[0], &e.bodies[1]);
    let nan = f64::NAN;
    let ks = bs.translational_kinetic.unwrap_or(nan);
    let kt = bt.translational_kinetic.unwrap_or(nan);
    Ok(RodImpact {
        stress: sum / count,
        deviation: dev,
        // From the closing step to the last step in contact (the contact opens one step
        // after the release).
        duration: match (start, end) {
            (Some(a), Some(b)) => b - a,
            _ => nan,
        },
        striker_momentum: bs.momentum.map_or(nan, |p| p[0]),
        target_momentum: bt.momentum.map_or(nan, |p| p[0]),
        target_kinetic: kt,
        vibration: bs.mechanical - ks + bt.mechanical - kt,
        mechanical: e.mechanical,
        max_iterations: res.max_iterations,
    })
}

/// What the rod impact gives for v0 = 1 (exact: stress 0.5, duration 2, momenta 0 and
/// m v0 = 0.25, target kinetic energy m v0^2 / 2 = 0.125, vibration 0).
#[derive(Debug, Clone, Copy)]
#[cfg_attr(
    not(test),
    allow(
        dead_code,
        reason = "the unit tests read every field, the validate rows three"
    )
)]
pub(crate) struct RodImpact {
    /// Mean contact stress over 0.25 <= t c/L <= 1.25, Pa.
    pub stress: f64,
    /// Largest nodal deviation of the pressure from 0.5 there, Pa.
    pub deviation: f64,
    /// Contact duration, s.
    pub duration: f64,
    /// Momentum of the striker and the target after separation, N s/m.
    pub striker_momentum: f64,
    pub target_momentum: f64,
    /// Translational kinetic energy of the target after separation, J/m.
    pub target_kinetic: f64,
    /// Energy left in vibration (both bodies), J/m.
    pub vibration: f64,
    /// Total mechanical energy at the end, J/m.
    pub mechanical: f64,
    /// Largest active-set iteration count of a step.
    pub max_iterations: usize,
}
