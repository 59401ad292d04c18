//! Dynamic frictional contact marched with Runge-Kutta convolution quadrature (Radau IIA,
//! 2 or 3 stages; Lubich & Ostermann 1993; Banjai & Lubich 2011; docs/theory/DYNAMICS.md
//! sec. 5.10).
//!
//! # Stage marching
//!
//! The RK-CQ discrete convolution acts on the stage values: entry n (the step from t_n to
//! t_(n+1)) has S samples at the stage times `t_n + c_i dt` (the last, `c_S = 1`, at
//! t_(n+1)), and with the weights `W_j` of the condensed map `[C E]` (S x S blocks of
//! `outputs x inputs` maps, [`cq_weights`] on stage-major vectors)
//!
//! ```text
//! U^n = W_0 Y^n + sum_(j=1..n) W_j Y^(n-j),   Y^n = (z^(n,1), f^(n,1), ..., z^(n,S), f^(n,S))
//! ```
//!
//! (the history by [`CqHistory`] over stage-stacked inputs, never truncated). Each step is
//! one contact problem for the S stage tractions at once (2 n_c S unknowns) with the block
//! compliance `W_0 = C(A^(-1)/dt)` (real, through the complex eigenvalues of the Butcher
//! matrix's inverse): normal complementarity on each stage's gap and Coulomb's law on the
//! slip increment between consecutive stages (the first stage's from the previous step's
//! end), solved by the static primal-dual active set method generalised to the block system
//! (one state per node and stage; `radau_step`). The method is stiffly accurate: the last
//! stage is the step's end, so the step records (what the case writes) are the last
//! stages.
//!
//! # Energy
//!
//! As the multistep march (module docs of [`super`], "Energy"), with the backward
//! differences and the trapezoidal load work taken over the sub-intervals between
//! consecutive stage times; the momentum by the method's own quadrature (the RK-CQ of
//! `1/s`): `P(t_n + c_i dt) = P_n + dt sum_j a_ij F^(n,j)`, `P_(n+1) = P_n + dt sum_j b_j
//! F^(n,j)`.

// Index loops over the stages and directions read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::radau_step::BlockStepProblem;
use super::{
    BodyEnergy, DynamicContact, DynamicContactEnergy, DynamicContactNode, DynamicContactParams,
    DynamicContactResult, DynamicContactStep, DynamicPairState,
};
use crate::dynamics::cq::{cq_weights, weights_memory_estimate, CqHistory, CqWeights};
use crate::dynamics::history::ContactSample;
use crate::error::{Error, Result};
use crate::solvers::bem2d::contact::ContactState;

/// A march with every sample of its convolution quadrature: what the recovery of the full
/// state (probes, fields) convolves.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledMarch {
    /// The step ends t_n = n dt, n = 0..=M (n = 0 the state at t = 0).
    pub result: DynamicContactResult,
    /// The state at every CQ sample ([`crate::dynamics::cq::CqGrid::sample_times`]): for
    /// the multistep methods the steps themselves; for Radau IIA every stage of every step,
    /// entry-major (sample `n S + i` at `(n + c_i) dt`, n = 0..M-1, with `step` = n + 1 and
    /// `time` the stage time; its last stage is step n + 1 of `result`).
    pub samples: Vec<DynamicContactStep>,
}

fn zero_sample() -> ContactSample {
    ContactSample {
        length: 0.0,
        normal_force: 0.0,
        tangential_force: 0.0,
        stick_length: 0.0,
        slip_length: 0.0,
    }
}

impl DynamicContact {
    /// Bytes a Runge-Kutta march allocates for the weights (with their contour spectra) and
    /// the stage history; None where the size overflows or the parameters are invalid.
    pub(super) fn stage_memory_estimate(&self, params: &DynamicContactParams) -> Option<usize> {
        let (rows, cols) = self.weight_shape();
        let s = params.method.stages();
        let w = weights_memory_estimate(params.method, cols, rows, params.steps, &params.cq)?;
        w.checked_add(
            params
                .steps
                .checked_mul(s)?
                .checked_mul(cols)?
                .checked_mul(8)?,
        )
    }

    /// Marches `params.steps` steps with any method ([`DynamicContact::march`]) and keeps
    /// the state at every CQ sample: for BDF1/BDF2 the steps, for Radau IIA 2/3 every
    /// stage (module docs). `observer` sees every step end as it is solved.
    ///
    /// Errors: as [`DynamicContact::march`]; a Radau IIA step whose block active set does
    /// not converge is [`Error::NotConverged`] with the complementarity residual over all
    /// stages (relative to the largest stage pressure).
    pub fn march_samples(
        &self,
        params: &DynamicContactParams,
        observer: &mut dyn FnMut(&DynamicContactStep),
    ) -> Result<SampledMarch> {
        if !params.method.is_runge_kutta() {
            let result = self.march(params, observer)?;
            let samples = result.steps.clone();
            return Ok(SampledMarch { result, samples });
        }
        if !self.rigid.is_empty() {
            // The rigid-segment columns (rigid.rs) are built for the multistep march only.
            return Err(Error::invalid(
                "method",
                params.method.name(),
                "Radau IIA does not march rigid segments (their columns are built for the \
                 multistep rule): use BDF2 with rigid segments",
            ));
        }
        super::check_march(
            params,
            self.stage_memory_estimate(params),
            "the dynamic contact Radau IIA weights and history",
        )?;
        // Runge-Kutta CQ: one entry per step (the stages inside it).
        let weights = cq_weights(
            &self.compliance,
            params.method,
            params.dt,
            params.steps,
            &params.cq,
        )?;
        self.march_stages_with(weights, params, observer)
    }

    /// The state at t = 0: at rest (plus the rigid velocities), no contact traction.
    fn initial_step(&self, initial_kinetic: &[f64]) -> DynamicContactStep {
        let mut pairs: Vec<DynamicPairState> = (0..self.npairs)
            .map(|_| DynamicPairState {
                nodes: Vec::new(),
                force: [0.0; 2],
                sample: zero_sample(),
            })
            .collect();
        for d in &self.nodes {
            pairs[d.pair].nodes.push(DynamicContactNode {
                position: d.position,
                pressure: 0.0,
                shear: 0.0,
                gap: d.initial_gap,
                slip: 0.0,
                state: ContactState::Open,
            });
        }
        let bodies = (0..self.bodies.len())
            .map(|b| {
                let v = self.velocity[b];
                let pm = [self.mass[b] * v[0], self.mass[b] * v[1]];
                BodyEnergy {
                    mechanical: initial_kinetic[b],
                    momentum: self.free[b].then_some(pm),
                    translational_kinetic: self.free[b].then_some(initial_kinetic[b]),
                }
            })
            .collect();
        let k0: f64 = initial_kinetic.iter().sum();
        DynamicContactStep {
            step: 0,
            time: 0.0,
            iterations: 0,
            residual: 0.0,
            pairs,
            // Radau refuses rigid segments (march_samples).
            rigid: Vec::new(),
            energy: DynamicContactEnergy {
                initial_kinetic: k0,
                external_work: 0.0,
                normal_contact_work: 0.0,
                dissipation: 0.0,
                mechanical: k0,
                bodies,
            },
        }
    }

    fn march_stages_with(
        &self,
        weights: CqWeights,
        params: &DynamicContactParams,
        observer: &mut dyn FnMut(&DynamicContactStep),
    ) -> Result<SampledMarch> {
        let method = params.method;
        let ns = method.stages();
        let c_nodes = method.nodes();
        let a_rk = method.butcher_a();
        let dt = params.dt;
        let n = self.nodes.len();
        let (rows, cols) = self.weight_shape();
        let wcols = ns * cols;
        let nl = self.load_columns.len();
        let nb = self.bodies.len();
        let w0 = weights.instantaneous().to_vec();
        // The contact block of W_0: stage-major (stage i, contact unknown k) on both sides.
        let m = 2 * n * ns;
        let a: Vec<f64> = (0..m)
            .flat_map(|r| {
                let wr = (r / (2 * n)) * rows + r % (2 * n);
                let w0 = &w0;
                (0..m).map(move |c| w0[wr * wcols + (c / (2 * n)) * cols + c % (2 * n)])
            })
            .collect();
        let friction: Vec<f64> = self.nodes.iter().map(|d| d.friction).collect();
        let rel_v = |k: usize, dir: [f64; 2]| -> f64 {
            let d = &self.nodes[k];
            let (vs, vm) = (
                self.velocity[self.body_of[d.slave_region]],
                self.velocity[self.body_of[d.master_region]],
            );
            (vs[0] - vm[0]) * dir[0] + (vs[1] - vm[1]) * dir[1]
        };
        let slave_v = |k: usize, dir: [f64; 2]| -> f64 {
            let vs = self.velocity[self.body_of[self.nodes[k].slave_region]];
            vs[0] * dir[0] + vs[1] * dir[1]
        };
        let factors = |t: f64| -> Vec<f64> {
            self.load_columns
                .iter()
                .map(|c| self.loads.get(c.function).map_or(1.0, |tf| tf.value(t)))
                .collect()
        };
        let initial_kinetic: Vec<f64> = (0..nb)
            .map(|b| {
                let v = self.velocity[b];
                0.5 * self.mass[b] * (v[0] * v[0] + v[1] * v[1])
            })
            .collect();
        let k0: f64 = initial_kinetic.iter().sum();
        let mut history = CqHistory::new(weights);
        let mut states = vec![ContactState::Open; n];
        let mut s_prev = vec![0.0; n];
        // The previous sample's totals (relative n, t, slave n, t per node), load work
        // outputs and factors; the momentum at the step's start.
        let mut prev_rel = vec![0.0; 4 * n];
        let mut prev_work = vec![0.0; 2 * nl];
        let mut prev_f = factors(0.0);
        let mut momentum: Vec<[f64; 2]> = (0..nb)
            .map(|b| {
                [
                    self.mass[b] * self.velocity[b][0],
                    self.mass[b] * self.velocity[b][1],
                ]
            })
            .collect();
        let (mut external, mut normal_work, mut dissipation) = (0.0, 0.0, 0.0);
        let mut body_work = vec![0.0; nb];
        let first = self.initial_step(&initial_kinetic);
        observer(&first);
        let mut steps = Vec::with_capacity(params.steps + 1);
        steps.push(first);
        let mut samples = Vec::with_capacity(params.steps * ns);
        let mut max_iterations = 0;
        for entry in 0..params.steps {
            let times: Vec<f64> = c_nodes.iter().map(|c| (entry as f64 + c) * dt).collect();
            let f: Vec<Vec<f64>> = times.iter().map(|&t| factors(t)).collect();
            let h = history.history()?;
            // Known part of the stage outputs: history + W_0 on the stage loads.
            let known: Vec<f64> = (0..ns * rows)
                .map(|r| {
                    let row = &w0[r * wcols..(r + 1) * wcols];
                    h[r] + (0..ns)
                        .map(|j| {
                            (0..nl)
                                .map(|c| row[j * cols + 2 * n + c] * f[j][c])
                                .sum::<f64>()
                        })
                        .sum::<f64>()
                })
                .collect();
            let mut g_pred = vec![0.0; ns * n];
            let mut s_pred = vec![0.0; ns * n];
            for i in 0..ns {
                for (k, d) in self.nodes.iter().enumerate() {
                    g_pred[i * n + k] =
                        d.initial_gap + known[i * rows + k] + rel_v(k, d.normal) * times[i];
                    s_pred[i * n + k] = known[i * rows + n + k] + rel_v(k, d.tangent) * times[i];
                }
            }
            let warm: Vec<ContactState> = (0..ns).flat_map(|_| states.iter().copied()).collect();
            let sol = BlockStepProblem {
                a: &a,
                n,
                stages: ns,
                g_pred: &g_pred,
                s_pred: &s_pred,
                s_prev: &s_prev,
                friction: &friction,
            }
            .solve(entry + 1, warm, &params.options)?;
            max_iterations = max_iterations.max(sol.iterations);
            let mut y = Vec::with_capacity(wcols);
            for i in 0..ns {
                y.extend_from_slice(&sol.z[i * 2 * n..(i + 1) * 2 * n]);
                y.extend_from_slice(&f[i]);
            }
            let x0 = history
                .weights()
                .apply(0, &y)
                .ok_or_else(|| Error::Numerical {
                    context: "dynamic contact (Radau IIA)",
                    detail: "weight shape".into(),
                })?;
            history.push(&y)?;
            let out: Vec<f64> = x0.iter().zip(&h).map(|(a, b)| a + b).collect();
            // Per stage: energies by backward differences from the previous sample, the
            // pairs, the resultant forces.
            let mut forces: Vec<Vec<[f64; 2]>> = Vec::with_capacity(ns);
            let mut partial: Vec<(Vec<DynamicPairState>, [f64; 3], Vec<f64>)> =
                Vec::with_capacity(ns);
            for i in 0..ns {
                let t = times[i];
                let o = &out[i * rows..(i + 1) * rows];
                let z = &sol.z[i * 2 * n..(i + 1) * 2 * n];
                let mut rel = vec![0.0; 4 * n];
                for (k, d) in self.nodes.iter().enumerate() {
                    rel[k] = o[k] + rel_v(k, d.normal) * t;
                    rel[n + k] = o[n + k] + rel_v(k, d.tangent) * t;
                    rel[2 * n + k] = o[2 * n + k] + slave_v(k, d.normal) * t;
                    rel[3 * n + k] = o[3 * n + k] + slave_v(k, d.tangent) * t;
                }
                let mut force = vec![[0.0; 2]; nb];
                let mut pairs: Vec<DynamicPairState> = (0..self.npairs)
                    .map(|_| DynamicPairState {
                        nodes: Vec::new(),
                        force: [0.0; 2],
                        sample: zero_sample(),
                    })
                    .collect();
                for (k, d) in self.nodes.iter().enumerate() {
                    let (p, q, w) = (z[k], z[n + k], d.weight);
                    let d_rel = |j: usize| rel[j] - prev_rel[j];
                    normal_work += w * p * d_rel(k);
                    dissipation -= w * q * d_rel(n + k);
                    let ws = w * (p * d_rel(2 * n + k) + q * d_rel(3 * n + k));
                    let wm = w
                        * (p * (d_rel(k) - d_rel(2 * n + k))
                            + q * (d_rel(n + k) - d_rel(3 * n + k)));
                    body_work[self.body_of[d.slave_region]] += ws;
                    body_work[self.body_of[d.master_region]] += wm;
                    let fs = [
                        w * (p * d.normal[0] + q * d.tangent[0]),
                        w * (p * d.normal[1] + q * d.tangent[1]),
                    ];
                    for x in 0..2 {
                        force[self.body_of[d.slave_region]][x] += fs[x];
                        force[self.body_of[d.master_region]][x] -= fs[x];
                    }
                    let pair = &mut pairs[d.pair];
                    for x in 0..2 {
                        pair.force[x] += fs[x];
                    }
                    let st = sol.states[i * n + k];
                    let sample = &mut pair.sample;
                    if !matches!(st, ContactState::Open | ContactState::Outside) {
                        sample.length += w;
                        if st == ContactState::Stick && d.friction > 0.0 {
                            sample.stick_length += w;
                        } else {
                            sample.slip_length += w;
                        }
                    }
                    sample.normal_force += w * p;
                    sample.tangential_force += w * q;
                    pair.nodes.push(DynamicContactNode {
                        position: d.position,
                        pressure: p,
                        shear: q,
                        gap: sol.gap[i * n + k],
                        slip: sol.slip[i * n + k],
                        state: st,
                    });
                }
                // External work (trapezoidal over the sub-interval) and load forces.
                let work = &o[4 * n..];
                for (c, col) in self.load_columns.iter().enumerate() {
                    let yu = work[2 * c] + col.rigid_rate * t;
                    let yt = work[2 * c + 1];
                    let (yu0, yt0) = (prev_work[2 * c], prev_work[2 * c + 1]);
                    let fc = f[i][c];
                    let dw =
                        0.5 * (fc + prev_f[c]) * (yu - yu0) + 0.5 * (yt + yt0) * (fc - prev_f[c]);
                    external += dw;
                    body_work[col.body] += dw;
                    prev_work[2 * c] = yu;
                    prev_work[2 * c + 1] = yt;
                    for x in 0..2 {
                        force[col.body][x] += fc * col.force[x];
                    }
                }
                prev_f.clone_from(&f[i]);
                prev_rel = rel;
                forces.push(force);
                partial.push((
                    pairs,
                    [external, normal_work, dissipation],
                    body_work.clone(),
                ));
            }
            // Momentum at the stages by the collocation integral, records.
            for (i, (pairs, [ext, nw, dis], work)) in partial.into_iter().enumerate() {
                let bodies = (0..nb)
                    .map(|b| {
                        let mut pm = momentum[b];
                        for j in 0..ns {
                            for x in 0..2 {
                                pm[x] += dt * a_rk[i * ns + j] * forces[j][b][x];
                            }
                        }
                        let free = self.free[b];
                        BodyEnergy {
                            mechanical: initial_kinetic[b] + work[b],
                            momentum: free.then_some(pm),
                            translational_kinetic: free
                                .then(|| (pm[0] * pm[0] + pm[1] * pm[1]) / (2.0 * self.mass[b])),
                        }
                    })
                    .collect();
                samples.push(DynamicContactStep {
                    step: entry + 1,
                    time: times[i],
                    iterations: sol.iterations,
                    residual: sol.residual,
                    pairs,
                    rigid: Vec::new(),
                    energy: DynamicContactEnergy {
                        initial_kinetic: k0,
                        external_work: ext,
                        normal_contact_work: nw,
                        dissipation: dis,
                        mechanical: k0 + ext + nw - dis,
                        bodies,
                    },
                });
            }
            // The step's end: the last stage (stiffly accurate; c_S = 1).
            for b in 0..nb {
                for j in 0..ns {
                    for x in 0..2 {
                        momentum[b][x] += dt * a_rk[(ns - 1) * ns + j] * forces[j][b][x];
                    }
                }
            }
            let mut end = samples[samples.len() - 1].clone();
            end.time = (entry + 1) as f64 * dt;
            observer(&end);
            steps.push(end);
            s_prev = sol.slip[(ns - 1) * n..].to_vec();
            states = sol.states[(ns - 1) * n..].to_vec();
        }
        Ok(SampledMarch {
            result: DynamicContactResult {
                steps,
                max_iterations,
            },
            samples,
        })
    }
}
