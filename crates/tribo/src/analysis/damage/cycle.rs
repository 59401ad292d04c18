//! Accumulation of damage over a load cycle, the paper's (23), (24) and (36), and the two
//! load histories of issue 4: a rotating bent shaft under a fixed roller, and rolling.

use rayon::prelude::*;
use serde::Serialize;

use super::mesh::{dangerous_region, DamageMesh, Execution};
use super::quantity::{relative_damage, Limit};
use super::sum::ExactSum;
use crate::analysis::stress_field::StressField;
use crate::error::{Error, Result};
use crate::kernels::bulk::BulkLoad;
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// Trapezoid weights w_k of the times t_0 < t_1 < ... < t_m (s): the integral of f over
/// [t_0, t_m] is approximated by sum_k w_k f(t_k). Errors: fewer than 2 times, not finite,
/// not strictly increasing.
pub fn trapezoid_weights(times: &[f64]) -> Result<Vec<f64>> {
    if times.len() < 2 {
        return Err(Error::invalid(
            "cycle.times",
            format!("{} states", times.len()),
            "needs at least 2 states",
        ));
    }
    if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(Error::invalid(
            "cycle.times",
            "times",
            "must be finite and strictly increasing (s)",
        ));
    }
    let m = times.len() - 1;
    Ok((0..=m)
        .map(|k| {
            let left = if k > 0 { times[k] - times[k - 1] } else { 0.0 };
            let right = if k < m { times[k + 1] - times[k] } else { 0.0 };
            0.5 * (left + right)
        })
        .collect())
}

/// The dangerous region of one state of the cycle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StateDamage {
    /// Time t_k, s.
    pub time: f64,
    /// V_q(t_k): m^3 (3D) or m^2 (2D).
    pub volume: f64,
    /// Psi_q(t_k): m^3 (3D) or m^2 (2D).
    pub damageability: f64,
    /// Largest psi_q at t_k.
    pub psi_max: f64,
}

/// Damage accumulated over one load cycle (23), (24), (36); volumes in m^3 (3D) or m^2 per
/// unit thickness (2D), times in s.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CycleDamage {
    /// The cycle's duration t_m - t_0 (one revolution), s.
    pub period: f64,
    /// Each state's dangerous region.
    pub states: Vec<StateDamage>,
    /// The time integral of the dangerous volume, integral of V_q(t) dt, m^3 s.
    pub volume_time_integral: f64,
    /// The time-mean dangerous volume (1/period) integral of V_q dt, m^3.
    pub mean_volume: f64,
    /// Psi_q^(V, t) = integral over t of the integral over {psi_q(t) >= 1} of psi_q dV dt
    /// (23), (36), m^3 s: the dangerous region is taken at each instant.
    pub damageability_time_integral: f64,
    /// Psi_q^(V_av, t) = Psi_q^(V, t) / mean V_q (24), s; `None` when no state has a
    /// dangerous volume. (The paper's 1/V_ij is read as the dangerous volume, here its
    /// mean over the cycle.)
    pub average: Option<f64>,
    /// Largest time integral of psi_q at a node, d Psi_q^(t) = integral of psi_q dt (23), s.
    pub node_time_integral_max: f64,
    /// Where it is, (x, y, z) m.
    pub node_time_integral_max_at: [f64; 3],
    /// d Psi_q^(t) = integral of psi_q dt at each node (23), s.
    #[serde(skip)]
    pub node_time_integral: Vec<f64>,
}

/// [`CycleDamage`] accumulated over N identical cycles (linear accumulation, no change of
/// the field with damage).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CyclesDamage {
    /// N.
    pub cycles: f64,
    /// N integral of V_q dt, m^3 s.
    pub volume_time_integral: f64,
    /// N Psi_q^(V, t), m^3 s.
    pub damageability_time_integral: f64,
    /// N Psi_q^(V_av, t), s.
    pub average: Option<f64>,
    /// N max d Psi_q^(t), s.
    pub node_time_integral_max: f64,
}

impl CycleDamage {
    /// The totals over `cycles` (> 0, finite) cycles.
    pub fn over_cycles(&self, cycles: f64) -> Result<CyclesDamage> {
        if !(cycles.is_finite() && cycles > 0.0) {
            return Err(Error::invalid(
                "cycles",
                cycles,
                "the number of cycles must be finite and > 0",
            ));
        }
        Ok(CyclesDamage {
            cycles,
            volume_time_integral: cycles * self.volume_time_integral,
            damageability_time_integral: cycles * self.damageability_time_integral,
            average: self.average.map(|a| cycles * a),
            node_time_integral_max: cycles * self.node_time_integral_max,
        })
    }
}

/// Accumulate the relative damage over a cycle of states at `times` (s, increasing):
/// `psi_at(k)` returns the nodal psi of state k. Time integrals by the trapezoid rule;
/// space integrals exact per state ([`dangerous_region`]).
pub fn accumulate_psi(
    mesh: &DamageMesh,
    times: &[f64],
    mut psi_at: impl FnMut(usize) -> Result<Vec<f64>>,
    execution: Execution,
) -> Result<CycleDamage> {
    let weights = trapezoid_weights(times)?;
    let mut node_integral = vec![0.0; mesh.node_count()];
    let (mut vt, mut pt) = (ExactSum::default(), ExactSum::default());
    let mut states = Vec::with_capacity(times.len());
    let mut any_dangerous = false;
    for (k, (&t, &w)) in times.iter().zip(&weights).enumerate() {
        let psi = psi_at(k)?;
        let region = dangerous_region(mesh, &psi, execution)?;
        any_dangerous |= region.volume > 0.0;
        vt.add(w * region.volume);
        pt.add(w * region.damageability);
        // Per node the sum runs in time order whatever the split: deterministic.
        match execution {
            Execution::Serial => node_integral
                .iter_mut()
                .zip(&psi)
                .for_each(|(a, p)| *a += w * p),
            Execution::Parallel => node_integral
                .par_iter_mut()
                .zip(&psi)
                .for_each(|(a, p)| *a += w * p),
        }
        states.push(StateDamage {
            time: t,
            volume: region.volume,
            damageability: region.damageability,
            psi_max: region.psi_max,
        });
    }
    let period = times[times.len() - 1] - times[0];
    let (volume_time_integral, damageability_time_integral) = (vt.value(), pt.value());
    let mean_volume = volume_time_integral / period;
    let mut best = 0;
    for (i, &v) in node_integral.iter().enumerate() {
        if v > node_integral[best] {
            best = i;
        }
    }
    Ok(CycleDamage {
        period,
        states,
        volume_time_integral,
        mean_volume,
        damageability_time_integral,
        average: (any_dangerous && mean_volume > 0.0)
            .then(|| damageability_time_integral / mean_volume),
        node_time_integral_max: node_integral[best],
        node_time_integral_max_at: mesh.nodes()[best],
        node_time_integral: node_integral,
    })
}

/// A sequence of stress states in time on a fixed set of points (the mesh nodes).
pub trait LoadHistory {
    /// The times of the states, s (strictly increasing).
    fn times(&self) -> &[f64];
    /// The nodal stress of state `k`, Pa.
    fn state(&self, k: usize) -> Result<Vec<StressTensor>>;
}

/// Accumulate psi_q = phi_q / phi_q^lim (21) of `limit` over `history` on `mesh`: (23),
/// (24), and (36) for the effective energy.
pub fn accumulate(
    mesh: &DamageMesh,
    history: &impl LoadHistory,
    limit: &Limit,
    material: &ElasticMaterial,
    execution: Execution,
) -> Result<CycleDamage> {
    accumulate_psi(
        mesh,
        history.times(),
        |k| relative_damage(limit, &history.state(k)?, material),
        execution,
    )
}

fn check_positive(field: &str, v: f64, unit: &str) -> Result<()> {
    if !(v.is_finite() && v > 0.0) {
        return Err(Error::invalid(
            field,
            v,
            format!("must be finite and > 0 ({unit})"),
        ));
    }
    Ok(())
}

fn even_times(duration: f64, steps: usize) -> Result<Vec<f64>> {
    if !(2..=100_000).contains(&steps) {
        return Err(Error::invalid(
            "cycle.steps",
            steps,
            "the number of time steps must be in [2, 100000]",
        ));
    }
    Ok((0..=steps)
        .map(|k| duration * k as f64 / steps as f64)
        .collect())
}

/// A rotating shaft bent in a fixed plane, under a roller fixed in space (the issue's
/// scenario): in the frame of the contact the contact field stays as it is, and the bending
/// stress at the contact runs through the tension and the compression zone once per
/// revolution, sigma_b(t) = sigma_a cos(2 pi t / T), linear through the depth
/// ([`BulkLoad::Bending`]: sigma_xx = sigma_b (1 - z/R)). States at t_k = k T / steps,
/// k = 0..steps (both ends, so the trapezoid rule covers one full revolution).
#[derive(Debug, Clone)]
pub struct RotatingBentShaft {
    contact: StressField,
    amplitude: f64,
    shaft_radius: f64,
    times: Vec<f64>,
    period: f64,
}

impl RotatingBentShaft {
    /// `contact`: the contact stress field (Pa); `amplitude` sigma_a (Pa, either sign;
    /// positive starts in the tension zone); `shaft_radius` R (m); `period` T of one revolution
    /// (s); `steps` time steps per revolution (>= 2).
    pub fn new(
        contact: StressField,
        amplitude: f64,
        shaft_radius: f64,
        period: f64,
        steps: usize,
    ) -> Result<Self> {
        if !amplitude.is_finite() {
            return Err(Error::invalid(
                "bending.amplitude",
                amplitude,
                "must be finite (Pa)",
            ));
        }
        check_positive("shaft.radius", shaft_radius, "m")?;
        check_positive("cycle.period", period, "s")?;
        super::quantity::check_stress(&contact.stress)?;
        Ok(Self {
            contact,
            amplitude,
            shaft_radius,
            times: even_times(period, steps)?,
            period,
        })
    }

    /// The bending stress at the contact at time `t`, Pa.
    pub fn bending_stress(&self, t: f64) -> f64 {
        self.amplitude * (2.0 * std::f64::consts::PI * t / self.period).cos()
    }
}

impl LoadHistory for RotatingBentShaft {
    fn times(&self) -> &[f64] {
        &self.times
    }

    fn state(&self, k: usize) -> Result<Vec<StressTensor>> {
        let mut field = self.contact.clone();
        field.add_bulk(
            &BulkLoad::Bending {
                surface_stress: self.bending_stress(self.times[k]),
            },
            self.shaft_radius,
        );
        Ok(field.stress)
    }
}

/// Rolling: the contact field moves along the rolling direction y at speed v, in the frame
/// of the body (a fixed set of material points). The state at time t at point (x, y, z) is
/// the contact field at (x, y - v t, z), linearly interpolated between the field's y lines
/// (exact when v t is a multiple of the spacing on a uniform grid). Points whose source
/// y - v t falls outside the field's window [y_0, y_last] get no contact stress: the window
/// is assumed to hold the whole contact field (its stresses decay away from the contact, so
/// a window a few contact widths wide leaves out little), and the stress that enters the
/// window from outside is taken as zero. An optional bulk load (tension, bending, torsion)
/// is superposed, fixed in time. States at t_k = k duration / steps, k = 0..steps.
#[derive(Debug, Clone)]
pub struct RollingContact {
    contact: StressField,
    speed: f64,
    bulk: Option<(BulkLoad, f64)>,
    times: Vec<f64>,
}

impl RollingContact {
    /// `contact`: the field at t = 0 (Pa) on a grid with strictly increasing y; `speed` v
    /// (m/s, either sign); `duration` of the cycle (s); `steps` (>= 2); `bulk`: a bulk load
    /// and the shaft radius (m), if any.
    pub fn new(
        contact: StressField,
        speed: f64,
        duration: f64,
        steps: usize,
        bulk: Option<(BulkLoad, f64)>,
    ) -> Result<Self> {
        if !speed.is_finite() {
            return Err(Error::invalid(
                "rolling.speed",
                speed,
                "must be finite (m/s)",
            ));
        }
        check_positive("cycle.duration", duration, "s")?;
        if contact.grid.y.windows(2).any(|w| w[1] <= w[0]) {
            return Err(Error::invalid(
                "field.y",
                "coordinates",
                "must be strictly increasing (m)",
            ));
        }
        if let Some((_, r)) = bulk {
            check_positive("shaft.radius", r, "m")?;
        }
        super::quantity::check_stress(&contact.stress)?;
        Ok(Self {
            contact,
            speed,
            bulk,
            times: even_times(duration, steps)?,
        })
    }
}

impl LoadHistory for RollingContact {
    fn times(&self) -> &[f64] {
        &self.times
    }

    fn state(&self, k: usize) -> Result<Vec<StressTensor>> {
        let grid = &self.contact.grid;
        let (nx, ny, nz) = (grid.x.len(), grid.y.len(), grid.z.len());
        let shift = self.speed * self.times[k];
        let y = &grid.y;
        // For each target y line: (source line j, weight of line j + 1) or None.
        let sources: Vec<Option<(usize, f64)>> = y
            .iter()
            .map(|&yt| {
                // Round-off in v t must not drop a point that sits on the window's edge.
                let tol = 1e-12 * (y[ny - 1] - y[0]);
                let ys = yt - shift;
                if ys < y[0] - tol || ys > y[ny - 1] + tol {
                    return None;
                }
                let ys = ys.clamp(y[0], y[ny - 1]);
                let j = y
                    .partition_point(|&v| v <= ys)
                    .saturating_sub(1)
                    .min(ny - 2);
                let w = (ys - y[j]) / (y[j + 1] - y[j]);
                // Snap to a grid line within round-off, so whole-line shifts copy exactly.
                let w = if w < 1e-12 { 0.0 } else { w.min(1.0) };
                Some((j, w))
            })
            .collect();
        let mut out = vec![StressTensor::ZERO; grid.len()];
        for iz in 0..nz {
            let bulk = self.bulk.map_or(StressTensor::ZERO, |(b, r)| {
                b.stress_at_depth(grid.z[iz], r)
            });
            for (iy, src) in sources.iter().enumerate() {
                for ix in 0..nx {
                    let c = match *src {
                        None => StressTensor::ZERO,
                        Some((j, w)) => {
                            let a = self.contact.stress[grid.index(ix, j, iz)];
                            if w == 0.0 {
                                a
                            } else {
                                let b = self.contact.stress[grid.index(ix, j + 1, iz)];
                                a.scale(1.0 - w) + b.scale(w)
                            }
                        }
                    };
                    out[grid.index(ix, iy, iz)] = c + bulk;
                }
            }
        }
        Ok(out)
    }
}
