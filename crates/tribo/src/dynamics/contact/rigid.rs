//! Rigid (guided) segments in the dynamic contact march (issue 13; docs/theory/DYNAMICS.md
//! sec. 5.4, "Rigid segments").
//!
//! A rigid segment moves as a rigid translation `U = (U_x, U_y)` (no rotation: a guided
//! face), each component either force-controlled (the resultant `F_d = int t_d ds` of the
//! traction on the segment prescribed, `U_d` unknown) or displacement-controlled, as in the
//! static solver ([`crate::solvers::bem2d::contact`], "Rigid segment"), with the prescribed
//! values scaled by a time function. In the Laplace-domain BEM the segment is a
//! displacement boundary (u = U on every node); the condensed map gains two input columns
//! per segment (unit translations along x and y) and two output rows (the resultants
//! `F_d = sum_k w_k t_d,k`, `w_k = int N_k ds`). Both are time-local, so they march like the
//! contact unknowns: at step n, with `W_0` the instantaneous weight and `h` the history,
//!
//! ```text
//! F^n = k_F + K_Fz z + K_FF U_F + K_FD U_D
//! ```
//!
//! (`k_F` history plus the loads' part, `U_F` the force-controlled translations, `U_D` the
//! prescribed ones). The force rows give `U_F = u_0 - S z` with `u_0 = K_FF^-1 (F_target -
//! k_F - K_FD U_D)` and `S = K_FF^-1 K_Fz` (`K_FF` is regular: inertia holds the segment at
//! `s_0 = gamma(0)/dt > 0`), which substituted into the contact rows leaves the static-like
//! contact step with the Schur complement `A - B_F S` as its compliance and the predicted
//! gaps moved by `B_D U_D + B_F u_0`. The translations and forces of each step are part of
//! the march's state ([`DynamicRigidState`]) and of the boundary inputs of the recovery
//! ([`super::DynamicContact::boundary_inputs`]). The work of a segment's force on its
//! translation, `dW = (F^n + F^(n-1))/2 . (U^n - U^(n-1))` (trapezoidal, as the loads'),
//! is external work of the owning body; its force enters the body's momentum.

// Index loops over the components read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::compliance::{node_weights, Combination};
use crate::dynamics::laplace::LaplaceBem;
use crate::dynamics::time_function::TimeFunction;
use crate::error::{Error, Result};
use crate::operators::bem2d::{BemModel, LoopItem};
use crate::solvers::bem2d::contact::{ContactPair, Control};
use crate::solvers::bem2d::{BoundaryConditions, SegmentBc};

/// A rigid (guided) segment of a dynamic contact problem: each component force- or
/// displacement-controlled ([`Control`], N/m or m), the values multiplied by the time
/// function `time` (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicRigid {
    /// The segment (it may have no boundary condition and belong to no contact pair).
    pub segment: String,
    /// x component.
    pub x: Control,
    /// y component.
    pub y: Control,
    /// The time function of the prescribed values.
    pub time: TimeFunction,
}

impl DynamicRigid {
    /// Segment `segment` with controls `x`, `y` applied as a step at t = 0 (constant 1).
    pub fn new(segment: &str, x: Control, y: Control) -> Result<Self> {
        Ok(Self {
            segment: segment.to_string(),
            x,
            y,
            time: TimeFunction::constant(1.0)?,
        })
    }

    /// The same with the time function `time`.
    pub fn with_time(mut self, time: TimeFunction) -> Self {
        self.time = time;
        self
    }
}

/// One rigid segment at one step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DynamicRigidState {
    /// Translation, m.
    pub translation: [f64; 2],
    /// Resultant of the traction on the segment (the force the segment exerts on the
    /// body), N/m.
    pub force: [f64; 2],
}

/// A rigid segment of the march: its body and controls.
#[derive(Debug, Clone)]
pub(super) struct RigidData {
    pub body: usize,
    pub controls: [Control; 2],
    pub time: TimeFunction,
}

/// `bcs` with every rigid segment fixed (its displacement is the marched translation).
/// Errors ([`Error::InvalidParameter`], `rigid_segment[j]`): an empty or repeated name, a
/// name of no segment owned by a region of `model`, a segment of a contact pair, a control
/// value that is not finite.
pub(super) fn fixed_conditions(
    model: &BemModel,
    bcs: &BoundaryConditions,
    pairs: &[ContactPair],
    rigid: &[DynamicRigid],
) -> Result<BoundaryConditions> {
    let mut out = bcs.clone();
    for (j, r) in rigid.iter().enumerate() {
        let field = format!("rigid_segment[{j}]");
        if r.segment.trim().is_empty() || rigid[..j].iter().any(|o| o.segment == r.segment) {
            return Err(Error::invalid(
                field,
                &r.segment,
                "a rigid segment must be named once",
            ));
        }
        let mut owned = model.regions.iter().flat_map(|r| r.loops.iter().flatten());
        if !owned.any(|item| matches!(item, LoopItem::Segment(seg) if seg.name == r.segment)) {
            return Err(Error::invalid(
                field,
                &r.segment,
                "names no segment of the model",
            ));
        }
        if pairs
            .iter()
            .any(|p| p.slave == r.segment || p.master == r.segment)
        {
            return Err(Error::invalid(
                field,
                &r.segment,
                "the segment is used by a contact pair",
            ));
        }
        for (c, name) in [(r.x, "x"), (r.y, "y")] {
            let v = match c {
                Control::Force(v) | Control::Displacement(v) => v,
            };
            if !v.is_finite() {
                return Err(Error::invalid(
                    format!("{field}.{name}"),
                    v,
                    "a rigid control must be finite (N/m or m)",
                ));
            }
        }
        out = out.set(&r.segment, SegmentBc::fixed());
    }
    Ok(out)
}

/// The input columns (unit translations, x then y per segment) and output rows (force
/// resultants) of the rigid segments on `bem` (built with [`fixed_conditions`]), and their
/// data. Errors: a name of no segment, a bonded interface.
pub(super) fn rigid_maps(
    bem: &LaplaceBem,
    rigid: &[DynamicRigid],
    body_of: &[usize],
) -> Result<(Vec<RigidData>, Vec<Combination>, Vec<Combination>)> {
    let mesh = &bem.static_problem().mesh;
    let input_of: HashMap<(usize, usize, usize), usize> = bem
        .known_dofs()
        .iter()
        .enumerate()
        .filter(|(_, k)| k.displacement)
        .map(|(i, k)| ((k.region, k.node, k.direction), i))
        .collect();
    let mut data = Vec::with_capacity(rigid.len());
    let mut columns = Vec::with_capacity(2 * rigid.len());
    let mut rows = Vec::with_capacity(2 * rigid.len());
    for (j, r) in rigid.iter().enumerate() {
        let field = format!("rigid_segment[{j}]");
        let s = mesh
            .segment_index(&r.segment)
            .ok_or_else(|| Error::invalid(&field, &r.segment, "names no segment of the model"))?;
        let info = &mesh.segments[s];
        if info.partner.is_some() {
            return Err(Error::invalid(
                field,
                &r.segment,
                "is a bonded interface between regions; it cannot be a rigid segment",
            ));
        }
        let region = info.owner;
        let weights = node_weights(&mesh.regions[region]);
        for d in 0..2 {
            let mut col: Combination = Vec::with_capacity(info.owner_nodes.len());
            let mut row: Combination = Vec::with_capacity(info.owner_nodes.len());
            for &node in &info.owner_nodes {
                let k =
                    input_of
                        .get(&(region, node, d))
                        .copied()
                        .ok_or_else(|| Error::Numerical {
                            context: "dynamic contact, rigid segment",
                            detail: format!(
                                "node {node} of region {region} is not displacement-type"
                            ),
                        })?;
                let o = bem
                    .unknown_output(region, node, d)
                    .ok_or_else(|| Error::Numerical {
                        context: "dynamic contact, rigid segment",
                        detail: format!("no unknown for node {node} of region {region}"),
                    })?;
                col.push((k, 1.0));
                row.push((o, weights[node]));
            }
            columns.push(col);
            rows.push(row);
        }
        data.push(RigidData {
            body: body_of[region],
            controls: [r.x, r.y],
            time: r.time.clone(),
        });
    }
    Ok((data, columns, rows))
}

/// The rigid segments' part of each step (module docs): the Schur complement of the
/// force-controlled translations, the prediction and the recovered translations.
pub(super) struct RigidStep<'a> {
    data: &'a [RigidData],
    /// Contact unknowns (2 n), first rigid output row, first rigid input column, row length.
    nz: usize,
    row0: usize,
    col0: usize,
    cols: usize,
    /// Force-controlled component indices (into 0..2 segments).
    force: Vec<usize>,
    /// `S = K_FF^-1 K_Fz` (force components x nz, row-major).
    s: Vec<f64>,
    /// `K_FF^-1` (row-major, square of the force components).
    kff_inv: Vec<f64>,
    /// Previous translations and forces.
    prev_u: Vec<f64>,
    prev_f: Vec<f64>,
}

impl<'a> RigidStep<'a> {
    /// The step data of `data` for the instantaneous weight `w0` (row-major, `cols`
    /// columns) with `nz` contact unknowns, the rigid rows from `row0` and columns from
    /// `col0`. Error ([`Error::Numerical`]): a singular `K_FF`.
    pub fn new(
        data: &'a [RigidData],
        w0: &[f64],
        cols: usize,
        nz: usize,
        row0: usize,
        col0: usize,
    ) -> Result<Self> {
        let force: Vec<usize> = (0..2 * data.len())
            .filter(|&j| matches!(data[j / 2].controls[j % 2], Control::Force(_)))
            .collect();
        let nf = force.len();
        let mut kff = Mat::<f64>::zeros(nf, nf);
        let mut kfz = Mat::<f64>::zeros(nf, nz);
        for (a, &i) in force.iter().enumerate() {
            let row = &w0[(row0 + i) * cols..(row0 + i + 1) * cols];
            for (b, &j) in force.iter().enumerate() {
                kff[(a, b)] = row[col0 + j];
            }
            for c in 0..nz {
                kfz[(a, c)] = row[c];
            }
        }
        let (mut s, mut kff_inv) = (Vec::new(), Vec::new());
        if nf > 0 {
            let lu = kff.partial_piv_lu();
            let inv = lu.solve(Mat::<f64>::identity(nf, nf));
            let sm = lu.solve(&kfz);
            s = (0..nf)
                .flat_map(|a| (0..nz).map(move |c| (a, c)))
                .map(|(a, c)| sm[(a, c)])
                .collect();
            kff_inv = (0..nf)
                .flat_map(|a| (0..nf).map(move |b| (a, b)))
                .map(|(a, b)| inv[(a, b)])
                .collect();
            if !(s.iter().chain(&kff_inv).all(|v| v.is_finite())) {
                return Err(Error::Numerical {
                    context: "dynamic contact, rigid segments",
                    detail: "the instantaneous stiffness of the force-controlled rigid \
                             translations is singular"
                        .into(),
                });
            }
        }
        Ok(Self {
            data,
            nz,
            row0,
            col0,
            cols,
            force,
            s,
            kff_inv,
            prev_u: vec![0.0; 2 * data.len()],
            prev_f: vec![0.0; 2 * data.len()],
        })
    }

    /// The contact block `a` (nz x nz, row-major, the contact rows of `w0`) with the
    /// force-controlled translations eliminated: `A - B_F S`.
    pub fn condensed(&self, w0: &[f64], mut a: Vec<f64>) -> Vec<f64> {
        let nz = self.nz;
        for i in 0..nz {
            for (f, &j) in self.force.iter().enumerate() {
                let b = w0[i * self.cols + self.col0 + j];
                if b != 0.0 {
                    for c in 0..nz {
                        a[i * nz + c] -= b * self.s[f * nz + c];
                    }
                }
            }
        }
        a
    }

    /// The translations' known part at time `t` (prescribed ones, `u_0` for the
    /// force-controlled ones), with the contact rows of `known` (history and loads) moved
    /// by `B U`.
    pub fn predict(&self, w0: &[f64], known: &mut [f64], t: f64) -> Vec<f64> {
        let r = 2 * self.data.len();
        let target = |j: usize| -> f64 {
            let d = &self.data[j / 2];
            match d.controls[j % 2] {
                Control::Force(v) | Control::Displacement(v) => v * d.time.value(t),
            }
        };
        let mut u = vec![0.0; r];
        for j in 0..r {
            if !self.force.contains(&j) {
                u[j] = target(j);
            }
        }
        // rhs_F = F_target - k_F - K_FD U_D
        let rhs: Vec<f64> = self
            .force
            .iter()
            .map(|&i| {
                let row = &w0[(self.row0 + i) * self.cols..(self.row0 + i + 1) * self.cols];
                let kd: f64 = (0..r).map(|j| row[self.col0 + j] * u[j]).sum();
                target(i) - known[self.row0 + i] - kd
            })
            .collect();
        let nf = self.force.len();
        for (a, &i) in self.force.iter().enumerate() {
            u[i] = (0..nf).map(|b| self.kff_inv[a * nf + b] * rhs[b]).sum();
        }
        for i in 0..self.nz {
            let row = &w0[i * self.cols..(i + 1) * self.cols];
            known[i] += (0..r).map(|j| row[self.col0 + j] * u[j]).sum::<f64>();
        }
        u
    }

    /// The translations of the step from the prediction `u` and the contact unknowns `z`:
    /// `U_F = u_0 - S z`.
    pub fn translations(&self, mut u: Vec<f64>, z: &[f64]) -> Vec<f64> {
        let nz = self.nz;
        for (f, &j) in self.force.iter().enumerate() {
            u[j] -= (0..nz).map(|c| self.s[f * nz + c] * z[c]).sum::<f64>();
        }
        u
    }

    /// The step's states from its translations `u` and outputs `out`; adds each segment's
    /// work to `work[body]` and its force to `force[body]`; returns the states and the
    /// total work of the step.
    pub fn record(
        &mut self,
        u: &[f64],
        out: &[f64],
        work: &mut [f64],
        force: &mut [[f64; 2]],
    ) -> (Vec<DynamicRigidState>, f64) {
        let mut states = Vec::with_capacity(self.data.len());
        let mut total = 0.0;
        for (k, d) in self.data.iter().enumerate() {
            let f = [out[self.row0 + 2 * k], out[self.row0 + 2 * k + 1]];
            let tr = [u[2 * k], u[2 * k + 1]];
            let mut dw = 0.0;
            for c in 0..2 {
                dw += 0.5 * (f[c] + self.prev_f[2 * k + c]) * (tr[c] - self.prev_u[2 * k + c]);
                force[d.body][c] += f[c];
                self.prev_f[2 * k + c] = f[c];
                self.prev_u[2 * k + c] = tr[c];
            }
            work[d.body] += dw;
            total += dw;
            states.push(DynamicRigidState {
                translation: tr,
                force: f,
            });
        }
        (states, total)
    }
}
