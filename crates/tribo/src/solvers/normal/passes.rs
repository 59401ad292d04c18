//! The element-wise passes of the Polonsky-Keer conjugate gradient
//! (`super::conjugate_gradient`), fused and parallel.
//!
//! One iteration used to make about a dozen serial sweeps over the N elements beside its one
//! FFT application; at 1024^2 they cost as much as the application. Here each phase of an
//! iteration is one parallel sweep that also returns the reductions the next phase needs.
//! Reductions are taken over fixed chunks of [`CHUNK`] elements and the chunk results are
//! combined in order, so the result does not depend on the number of threads (runs repeat
//! bit for bit on any machine).

use rayon::prelude::*;

use crate::solvers::nan_max;

/// Elements per chunk of a parallel sweep (fixed, for thread-independent sums): 16 Ki
/// values are 128 KiB per array, a chunk of work large beside the cost of a rayon task.
const CHUNK: usize = 1 << 14;

/// What the gap sweep returns.
#[derive(Debug, Clone, Copy)]
pub(super) struct GapStats {
    /// Elements in contact (p > 0).
    pub n_contact: usize,
    /// Sum of the gap over the contact set, m.
    pub gap_sum: f64,
    /// Largest |displacement|, m (NaN if any is NaN).
    pub displacement_max: f64,
    /// Largest pressure, Pa (NaN if any is NaN).
    pub pressure_max: f64,
}

/// `gap = displacement + h` (before the approach is subtracted), with the contact count,
/// the gap sum over the contact set and the two scales of the residual.
pub(super) fn gap_sweep(
    displacement: &[f64],
    h: &[f64],
    pressure: &[f64],
    gap: &mut [f64],
) -> GapStats {
    let parts: Vec<GapStats> = gap
        .par_chunks_mut(CHUNK)
        .zip(displacement.par_chunks(CHUNK))
        .zip(h.par_chunks(CHUNK))
        .zip(pressure.par_chunks(CHUNK))
        .map(|(((g, u), h), p)| {
            let mut s = GapStats {
                n_contact: 0,
                gap_sum: 0.0,
                displacement_max: 0.0,
                pressure_max: 0.0,
            };
            for i in 0..g.len() {
                g[i] = u[i] + h[i];
                s.displacement_max = nan_max(s.displacement_max, u[i].abs());
                s.pressure_max = nan_max(s.pressure_max, p[i]);
                if p[i] > 0.0 {
                    s.n_contact += 1;
                    s.gap_sum += g[i];
                }
            }
            s
        })
        .collect();
    parts.into_iter().fold(
        GapStats {
            n_contact: 0,
            gap_sum: 0.0,
            displacement_max: 0.0,
            pressure_max: 0.0,
        },
        |a, b| GapStats {
            n_contact: a.n_contact + b.n_contact,
            gap_sum: a.gap_sum + b.gap_sum,
            displacement_max: nan_max(a.displacement_max, b.displacement_max),
            pressure_max: nan_max(a.pressure_max, b.pressure_max),
        },
    )
}

/// `gap -= approach`, returning the complementarity residual (the definition of
/// [`super::complementarity_residual`], with the scales of [`gap_sweep`]) and the squared
/// norm of the gap over the contact set.
pub(super) fn shift_sweep(
    gap: &mut [f64],
    pressure: &[f64],
    approach: f64,
    pressure_max: f64,
    displacement_scale: f64,
) -> (f64, f64) {
    let scales_valid = pressure_max > 0.0 && displacement_scale > 0.0;
    let parts: Vec<(f64, f64)> = gap
        .par_chunks_mut(CHUNK)
        .zip(pressure.par_chunks(CHUNK))
        .map(|(g, p)| {
            let (mut residual, mut norm) = (0.0f64, 0.0);
            for i in 0..g.len() {
                g[i] -= approach;
                let r = if p[i].is_nan() || g[i].is_nan() {
                    f64::NAN
                } else {
                    (p[i] / pressure_max).min(g[i] / displacement_scale).abs()
                };
                residual = nan_max(residual, r);
                if p[i] > 0.0 {
                    norm += g[i] * g[i];
                }
            }
            (residual, norm)
        })
        .collect();
    let (residual, norm) = parts
        .into_iter()
        .fold((0.0f64, 0.0), |a, b| (nan_max(a.0, b.0), a.1 + b.1));
    // As complementarity_residual: undefined scales are never "converged".
    (
        if scales_valid {
            residual
        } else {
            f64::INFINITY
        },
        norm,
    )
}

/// The conjugate direction `t = g + beta t` on the contact set (0 elsewhere), returning
/// `(sum g t, sum t)` over the contact set.
pub(super) fn direction_sweep(
    direction: &mut [f64],
    gap: &[f64],
    pressure: &[f64],
    beta: f64,
) -> (f64, f64) {
    let parts: Vec<(f64, f64)> = direction
        .par_chunks_mut(CHUNK)
        .zip(gap.par_chunks(CHUNK))
        .zip(pressure.par_chunks(CHUNK))
        .map(|((t, g), p)| {
            let (mut gt, mut ts) = (0.0, 0.0);
            for i in 0..t.len() {
                if p[i] > 0.0 {
                    t[i] = g[i] + beta * t[i];
                    gt += g[i] * t[i];
                    ts += t[i];
                } else {
                    t[i] = 0.0;
                }
            }
            (gt, ts)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// `(sum r, sum r t)` over the contact set, `r = K t` the response.
pub(super) fn response_sweep(response: &[f64], direction: &[f64], pressure: &[f64]) -> (f64, f64) {
    let parts: Vec<(f64, f64)> = response
        .par_chunks(CHUNK)
        .zip(direction.par_chunks(CHUNK))
        .zip(pressure.par_chunks(CHUNK))
        .map(|((r, t), p)| {
            let (mut rs, mut rt) = (0.0, 0.0);
            for i in 0..r.len() {
                if p[i] > 0.0 {
                    rs += r[i];
                    rt += r[i] * t[i];
                }
            }
            (rs, rt)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// The residual the preconditioner acts on: the gap on the contact set, its negative part
/// outside it (the points that overlap and re-enter), 0 elsewhere.
pub(super) fn masked_residual_sweep(gap: &[f64], pressure: &[f64], residual: &mut [f64]) {
    residual
        .par_chunks_mut(CHUNK)
        .zip(gap.par_chunks(CHUNK))
        .zip(pressure.par_chunks(CHUNK))
        .for_each(|((r, g), p)| {
            for i in 0..r.len() {
                r[i] = if p[i] > 0.0 { g[i] } else { g[i].min(0.0) };
            }
        });
}

/// What [`preconditioned_sums`] returns: sums over the contact set.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PreconditionedSums {
    /// `sum z`, Pa.
    pub z: f64,
    /// `sum g z`, m Pa.
    pub gap_z: f64,
    /// `sum g`, m.
    pub gap: f64,
    /// `sum g t` with the previous direction `t`, m Pa.
    pub gap_direction: f64,
}

/// `sum z`, `sum g z`, `sum g` and `sum g t` over the contact set, `z` the preconditioned
/// residual and `t` the previous direction.
pub(super) fn preconditioned_sums(
    preconditioned: &[f64],
    gap: &[f64],
    pressure: &[f64],
    direction: &[f64],
) -> PreconditionedSums {
    let parts: Vec<PreconditionedSums> = preconditioned
        .par_chunks(CHUNK)
        .zip(gap.par_chunks(CHUNK))
        .zip(pressure.par_chunks(CHUNK).zip(direction.par_chunks(CHUNK)))
        .map(|((z, g), (p, t))| {
            let mut s = PreconditionedSums::default();
            for i in 0..z.len() {
                if p[i] > 0.0 {
                    s.z += z[i];
                    s.gap_z += g[i] * z[i];
                    s.gap += g[i];
                    s.gap_direction += g[i] * t[i];
                }
            }
            s
        })
        .collect();
    parts
        .into_iter()
        .fold(PreconditionedSums::default(), |a, b| PreconditionedSums {
            z: a.z + b.z,
            gap_z: a.gap_z + b.gap_z,
            gap: a.gap + b.gap,
            gap_direction: a.gap_direction + b.gap_direction,
        })
}

/// The preconditioned conjugate direction `t = (z - z_mean) + beta t` on the contact set
/// (0 elsewhere), returning `(sum g t, sum t)` over the contact set.
pub(super) fn preconditioned_direction_sweep(
    direction: &mut [f64],
    preconditioned: &[f64],
    z_mean: f64,
    gap: &[f64],
    pressure: &[f64],
    beta: f64,
) -> (f64, f64) {
    let parts: Vec<(f64, f64)> = direction
        .par_chunks_mut(CHUNK)
        .zip(preconditioned.par_chunks(CHUNK))
        .zip(gap.par_chunks(CHUNK).zip(pressure.par_chunks(CHUNK)))
        .map(|((t, z), (g, p))| {
            let (mut gt, mut ts) = (0.0, 0.0);
            for i in 0..t.len() {
                if p[i] > 0.0 {
                    t[i] = (z[i] - z_mean) + beta * t[i];
                    gt += g[i] * t[i];
                    ts += t[i];
                } else {
                    t[i] = 0.0;
                }
            }
            (gt, ts)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// What the step sweep returns.
#[derive(Debug, Default)]
pub(super) struct StepStats {
    /// Sum of the new pressure, Pa.
    pub pressure_sum: f64,
    /// Whether a point outside the contact set re-entered it.
    pub overlap: bool,
    /// Elements where the new pressure departs from the linear step `p - step t`.
    pub changes: usize,
    /// `(element, p_new - (p - step t))` for the first `max_corrections + 1` of them in
    /// element order (enough to tell whether there are more than `max_corrections`).
    pub corrections: Vec<(usize, f64)>,
}

/// Polonsky & Keer's step: `p <- p - step t` on the contact set, projected onto p >= 0;
/// points outside it with negative gap re-enter with `p = -step e` where that is positive,
/// `e` the re-entry field: the gap itself in Polonsky & Keer's method (`p = -step g`), the
/// preconditioned residual in the preconditioned one (so that `step e` is a pressure).
pub(super) fn step_sweep(
    pressure: &mut [f64],
    direction: &[f64],
    gap: &[f64],
    reentry: &[f64],
    step: f64,
    max_corrections: usize,
) -> StepStats {
    let parts: Vec<StepStats> = pressure
        .par_chunks_mut(CHUNK)
        .zip(direction.par_chunks(CHUNK))
        .zip(gap.par_chunks(CHUNK).zip(reentry.par_chunks(CHUNK)))
        .enumerate()
        .map(|(chunk, ((p, t), (g, e)))| {
            let mut s = StepStats::default();
            let offset = chunk * CHUNK;
            for i in 0..p.len() {
                if p[i] > 0.0 {
                    let v = p[i] - step * t[i];
                    if v < 0.0 {
                        p[i] = 0.0;
                        s.changes += 1;
                        if s.corrections.len() <= max_corrections {
                            s.corrections.push((offset + i, -v));
                        }
                    } else {
                        p[i] = v;
                    }
                } else if g[i] < 0.0 && -step * e[i] > 0.0 {
                    p[i] = -step * e[i];
                    s.overlap = true;
                    s.changes += 1;
                    if s.corrections.len() <= max_corrections {
                        s.corrections.push((offset + i, p[i]));
                    }
                }
                s.pressure_sum += p[i];
            }
            s
        })
        .collect();
    let mut total = StepStats::default();
    for s in parts {
        total.pressure_sum += s.pressure_sum;
        total.overlap |= s.overlap;
        total.changes += s.changes;
        for c in s.corrections {
            if total.corrections.len() <= max_corrections {
                total.corrections.push(c);
            }
        }
    }
    total
}

/// The Jacobi re-entry of the points outside the contact set that overlap: `p_i = -g_i / d`
/// where `p_i = 0` and `g_i < 0`, `d` the operator's diagonal (m/Pa): the pressure that
/// closes the point's own interpenetration. Returns the number of points entered.
pub(super) fn jacobi_reentry_sweep(pressure: &mut [f64], gap: &[f64], diagonal: f64) -> usize {
    pressure
        .par_chunks_mut(CHUNK)
        .zip(gap.par_chunks(CHUNK))
        .map(|(p, g)| {
            let mut entered = 0usize;
            for i in 0..p.len() {
                if p[i] <= 0.0 && g[i] < 0.0 {
                    p[i] = -g[i] / diagonal;
                    entered += 1;
                }
            }
            entered
        })
        .sum()
}

/// `p *= scale` and, where the displacement is updated incrementally,
/// `u <- scale (u - step r)` in the same sweep.
pub(super) fn scale_sweep(
    pressure: &mut [f64],
    scale: f64,
    update: Option<(&mut [f64], &[f64], f64)>,
) {
    match update {
        Some((displacement, response, step)) => pressure
            .par_chunks_mut(CHUNK)
            .zip(displacement.par_chunks_mut(CHUNK))
            .zip(response.par_chunks(CHUNK))
            .for_each(|((p, u), r)| {
                for i in 0..p.len() {
                    p[i] *= scale;
                    u[i] = scale * (u[i] - step * r[i]);
                }
            }),
        None if scale != 1.0 => pressure.par_chunks_mut(CHUNK).for_each(|p| {
            for v in p.iter_mut() {
                *v *= scale;
            }
        }),
        None => {}
    }
}
