//! Stresses of the Laplace-domain BEM: interior stress probes in the Laplace domain (whose
//! CQ convolution gives probe stress histories) and the boundary stress of the time
//! histories (docs/theory/DYNAMICS.md sec. 5.2).
//!
//! **Interior (stress probes).** The transformed Somigliana stress identity
//! `sigma_ij(p, s) = int D_kij(s) t_k - int S_kij(s) u_k` (kernels of
//! [`crate::dynamics::kernel::stress`]) is split as the operators are: the static kernels'
//! integrals with the static interior rule (`element_interior`, applied to the real and
//! the imaginary part of the boundary data) plus the bounded differences dD, dS integrated
//! with the adaptive rule over every element cut into `ceil(|s| l/c2)` pieces, their radial
//! functions from one [`crate::dynamics::kernel::stress::StressTable`] per region and
//! frequency (issue 13 "Speed"; equal to the direct kernels to 1e-12). An element far from
//! the probe (Re(s) d/c1 > [`FAR_DECAY`], as in the operators) adds nothing: the full kernels
//! are 0 to rounding there. Outputs in Pa s (the transform of Pa), after the displacement
//! probes ([`LaplaceBem::first_stress_output`]).
//!
//! **Boundary.** Hooke's law is instantaneous, so the boundary stress at a time follows
//! from that time's nodal traction and the tangential derivative of that time's nodal
//! displacements along the element, exactly as the static recovery does
//! ([`crate::solvers::bem2d::BemSolution::segment_results`]): sigma_nn, sigma_nt from the
//! traction, sigma_tt = (2 mu eps_tt + nu' sigma_nn)/(1 - nu'), averaged over the elements
//! that share a node. [`LaplaceBem::boundary_fields`] unpacks one sample of the CQ time
//! series (outputs in column order plus the known inputs) into nodal u and t;
//! [`boundary_stress_history`] does every step.

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use faer::c64;

use super::{
    far, junction_state, probe_sites, region_extent, LaplaceBem, LaplaceState, FAR_DECAY,
    MAX_PIECES,
};
use crate::dynamics::cq::CqSeries;
use crate::dynamics::kernel::stress::StressTable;
use crate::dynamics::kernel::LaplaceKelvin2d;
use crate::error::{Error, Result};
use crate::operators::bem2d::integrate::{adaptive, element_interior};
use crate::operators::bem2d::mesh::Element;
use crate::solvers::bem2d::{element_boundary_stress, Dof, Site, Stress2d};

/// Nodal boundary fields at one time (per region and node, the static solution's layout):
/// displacements (m) and tractions on the region (Pa).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryFields {
    /// Nodal displacements per region and node, m.
    pub displacement: Vec<Vec<[f64; 2]>>,
    /// Nodal tractions per region and node (on that region), Pa.
    pub traction: Vec<Vec<[f64; 2]>>,
}

/// Number of pieces of element `e` for the kernel's length c2/|s| (as the operators).
fn pieces(e: &Element, kernel: &LaplaceKelvin2d, s: c64) -> usize {
    let n = (s.norm() * e.chord_length() / kernel.s_wave_speed()).ceil();
    if n.is_finite() && n >= 1.0 {
        (n as usize).min(MAX_PIECES)
    } else {
        1
    }
}

impl LaplaceBem {
    /// The same model with stress probes at `points` (m): each adds three outputs, the
    /// transformed stresses sigma_xx, sigma_yy, sigma_xy (Pa s), after the displacement
    /// probes ([`LaplaceBem::outputs`]). Each is evaluated as the displacement probes are
    /// (the static field sampler's rule, in the first region holding it): points within the
    /// static solver's boundary layer at that distance inside, points at a segment junction
    /// by the junction rule (module docs).
    ///
    /// Errors: a point outside every region ([`Error::InvalidParameter`], field `probe`).
    pub fn with_stress_probes(mut self, points: &[[f64; 2]]) -> Result<Self> {
        self.stress_probes = probe_sites(&self.problem.mesh, points, &vec![None; points.len()])?;
        Ok(self)
    }

    /// The same model with its displacement probes and its stress probes both at `points`
    /// (m), point i located in region `regions[i]` (None: the first region holding it), the
    /// outputs as [`LaplaceBem::new`]'s probes and [`LaplaceBem::with_stress_probes`]: the
    /// field of a body sampled on its own triangulation, whose boundary nodes may lie on an
    /// interface with another region (each side then evaluated in its own region, as the
    /// static sampler [`crate::analysis::bem_field::sample_region`] does).
    ///
    /// Errors: counts that differ, a region out of range or a point outside its region
    /// ([`Error::InvalidParameter`]).
    pub fn with_field_points(
        mut self,
        points: &[[f64; 2]],
        regions: &[Option<usize>],
    ) -> Result<Self> {
        let sites = probe_sites(&self.problem.mesh, points, regions)?;
        self.probes.clone_from(&sites);
        self.stress_probes = sites;
        Ok(self)
    }

    /// Number of stress probes.
    pub fn stress_probe_count(&self) -> usize {
        self.stress_probes.len()
    }

    /// The region (index in the static problem's mesh) holding stress probe `i`, or `None`
    /// past the last probe: its Hooke's law turns the probe's stresses into strains.
    pub fn stress_probe_region(&self, i: usize) -> Option<usize> {
        self.stress_probes.get(i).map(|q| q.0)
    }

    /// Index of the first stress output (sigma_xx of the first stress probe): the system
    /// unknowns plus two per displacement probe.
    pub fn first_stress_output(&self) -> usize {
        self.ncol + 2 * self.probes.len()
    }

    /// The transformed stresses [sigma_xx, sigma_yy, sigma_xy] (Pa s) at the stress probes
    /// for the solved state `state` at `s` (module docs).
    ///
    /// Errors: a state of another model (wrong shape, [`Error::InvalidParameter`]); a
    /// kernel evaluation failure.
    pub fn probe_stresses(&self, s: c64, state: &LaplaceState) -> Result<Vec<[c64; 3]>> {
        let regions = &self.problem.mesh.regions;
        let fits = state.displacement.len() == regions.len()
            && state.traction.len() == regions.len()
            && regions.iter().enumerate().all(|(r, reg)| {
                state.displacement[r].len() == reg.nodes.len()
                    && state.traction[r].len() == reg.nodes.len()
            });
        if !fits {
            return Err(Error::invalid(
                "state",
                "its node counts",
                "must be a state of this model (one value per region and node)",
            ));
        }
        let tables = self.stress_tables(s)?;
        self.probe_stresses_with(&tables, &state.displacement, &state.traction)
    }

    /// One stress table at `s` per region that holds a stress probe (None for the others).
    pub(super) fn stress_tables(&self, s: c64) -> Result<Vec<Option<StressTable<'_>>>> {
        self.problem
            .mesh
            .regions
            .iter()
            .zip(&self.kernels)
            .enumerate()
            .map(|(r, (region, kernel))| {
                self.stress_probes
                    .iter()
                    .any(|q| q.0 == r && matches!(q.1, Site::Interior(_)))
                    .then(|| kernel.stress_table(s, region_extent(region)))
                    .transpose()
            })
            .collect()
    }

    /// [`LaplaceBem::probe_stresses`] of the boundary state `displacement`, `traction` (per
    /// region and node, of the right shape) with the tables of
    /// [`LaplaceBem::stress_tables`].
    pub(super) fn probe_stresses_with(
        &self,
        tables: &[Option<StressTable<'_>>],
        displacement: &[Vec<[c64; 2]>],
        traction: &[Vec<[c64; 2]>],
    ) -> Result<Vec<[c64; 3]>> {
        let regions = &self.problem.mesh.regions;
        let mut out = Vec::with_capacity(self.stress_probes.len());
        for (r, site) in &self.stress_probes {
            let r = *r;
            let region = &regions[r];
            let p = match site {
                Site::Interior(p) => *p,
                Site::Junction(feet) => {
                    out.push(junction_state(region, feet, &displacement[r], &traction[r]).1);
                    continue;
                }
            };
            let kernel = &self.kernels[r];
            let Some(table) = &tables[r] else {
                return Err(Error::Numerical {
                    context: "LaplaceBem::probe_stresses",
                    detail: format!("no stress table for region {r}"),
                });
            };
            let s = table.s();
            let (u, t) = (&displacement[r], &traction[r]);
            let mut sigma = [c64::ZERO; 3];
            let mut err: Option<Error> = None;
            for e in &region.local_elements {
                // A far element ([`FAR_DECAY`]): the full kernels D(s), S(s) are 0 to
                // rounding there, so the element adds nothing (its static integrals and
                // their differences cancel).
                if far(e, p, kernel, s, FAR_DECAY) {
                    continue;
                }
                // Static kernels: the static interior rule on the real and imaginary parts.
                let ue = e.nodes.map(|m| u[m]);
                let te = e.nodes.map(|m| t[m]);
                for part in 0..2 {
                    let pick = |v: c64| if part == 0 { v.re } else { v.im };
                    let (ur, tr) = (ue.map(|x| x.map(pick)), te.map(|x| x.map(pick)));
                    let (mut du, mut ds) = ([0.0; 2], [0.0; 3]);
                    element_interior(&region.kernels, e, p, &ur, &tr, &mut du, &mut ds);
                    let unit = if part == 0 {
                        c64::ONE
                    } else {
                        c64::new(0.0, 1.0)
                    };
                    for c in 0..3 {
                        sigma[c] += unit * ds[c];
                    }
                }
                // The differences dD, dS on the element's pieces.
                let np = pieces(e, kernel, s);
                for m in 0..np {
                    let a = -1.0 + 2.0 * m as f64 / np as f64;
                    let b = -1.0 + 2.0 * (m + 1) as f64 / np as f64;
                    adaptive(e, p, a, b, 0, &mut |xi, w| {
                        if err.is_some() {
                            return;
                        }
                        let (n, jac) = e.normal_jacobian(xi);
                        let r = e.offset_from(xi, p);
                        let (dd, ds) = match table.differences(r, n) {
                            Ok(v) => v,
                            Err(x) => {
                                err = Some(x);
                                return;
                            }
                        };
                        let nk = e.field_shape(xi);
                        let mut uu = [c64::ZERO; 2];
                        let mut tt = [c64::ZERO; 2];
                        for k in 0..3 {
                            for d in 0..2 {
                                uu[d] += ue[k][d] * nk[k];
                                tt[d] += te[k][d] * nk[k];
                            }
                        }
                        let wj = w * jac;
                        for k in 0..2 {
                            for (c, (i, j)) in [(0, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                                sigma[c] += (dd[k][i][j] * tt[k] - ds[k][i][j] * uu[k]) * wj;
                            }
                        }
                    });
                }
            }
            if let Some(x) = err {
                return Err(x);
            }
            out.push(sigma);
        }
        Ok(out)
    }

    /// The stress probes' stresses (Pa, with sigma_zz of the probe's region) from one
    /// sample of the time series of [`LaplaceBem::outputs`] (e.g. a row of
    /// [`crate::dynamics::cq::convolve`]'s result).
    ///
    /// Errors: `outputs` of the wrong length ([`Error::InvalidParameter`]).
    pub fn stress_probe_values(&self, outputs: &[f64]) -> Result<Vec<Stress2d>> {
        self.check_len("outputs", outputs.len(), self.outputs())?;
        let first = self.first_stress_output();
        Ok(self
            .stress_probes
            .iter()
            .enumerate()
            .map(|(i, &(r, _))| {
                let v = &outputs[first + 3 * i..first + 3 * i + 3];
                let k = &self.problem.mesh.regions[r].kernels;
                Stress2d {
                    xx: v[0],
                    yy: v[1],
                    xy: v[2],
                    zz: k.sigma_zz(v[0], v[1]),
                }
            })
            .collect())
    }

    fn check_len(&self, what: &str, got: usize, expected: usize) -> Result<()> {
        if got == expected {
            Ok(())
        } else {
            Err(Error::invalid(
                what,
                got,
                format!("must give one value per {what} of the model ({expected})"),
            ))
        }
    }

    /// The nodal boundary displacements (m) and tractions (Pa) at one time from that
    /// sample's `outputs` (length [`LaplaceBem::outputs`]: the unknowns in column order,
    /// tractions in Pa) and `inputs` (length [`LaplaceBem::inputs`]: the known values in
    /// input order); the same unpacking as the static solution's (interface tractions
    /// with the partner's sign).
    ///
    /// Errors: a length that is not the model's ([`Error::InvalidParameter`]).
    pub fn boundary_fields(&self, outputs: &[f64], inputs: &[f64]) -> Result<BoundaryFields> {
        self.check_len("outputs", outputs.len(), self.outputs())?;
        self.check_len("inputs", inputs.len(), self.inputs())?;
        let mut known: Vec<Vec<[f64; 2]>> =
            self.dofs.iter().map(|d| vec![[0.0; 2]; d.len()]).collect();
        for (k, v) in self.known.iter().zip(inputs) {
            known[k.region][k.node][k.direction] = *v;
        }
        let mut displacement = Vec::with_capacity(self.dofs.len());
        let mut traction = Vec::with_capacity(self.dofs.len());
        for (d, kn) in self.dofs.iter().zip(&known) {
            let mut u = Vec::with_capacity(d.len());
            let mut t = Vec::with_capacity(d.len());
            for (node, k) in d.iter().zip(kn) {
                let (mut un, mut tn) = ([0.0; 2], [0.0; 2]);
                for dir in 0..2 {
                    match node[dir] {
                        Dof::U { col, .. } => {
                            un[dir] = outputs[col];
                            tn[dir] = k[dir];
                        }
                        Dof::T { col, .. } => {
                            un[dir] = k[dir];
                            tn[dir] = outputs[col];
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            un[dir] = outputs[u_col];
                            tn[dir] = outputs[t_col] * sign;
                        }
                    }
                }
                u.push(un);
                t.push(tn);
            }
            displacement.push(u);
            traction.push(t);
        }
        Ok(BoundaryFields {
            displacement,
            traction,
        })
    }

    /// The boundary stress [sigma_xx, sigma_yy, sigma_xy] (Pa) at every node (per region
    /// and node) of the boundary fields `fields` (module docs; the static recovery, averaged
    /// over the elements sharing the node).
    ///
    /// Errors: fields of another model (wrong shape, [`Error::InvalidParameter`]).
    pub fn boundary_stresses(&self, fields: &BoundaryFields) -> Result<Vec<Vec<[f64; 3]>>> {
        let regions = &self.problem.mesh.regions;
        let fits = fields.displacement.len() == regions.len()
            && fields.traction.len() == regions.len()
            && regions.iter().enumerate().all(|(r, reg)| {
                fields.displacement[r].len() == reg.nodes.len()
                    && fields.traction[r].len() == reg.nodes.len()
            });
        if !fits {
            return Err(Error::invalid(
                "fields",
                "their node counts",
                "must be boundary fields of this model (one value per region and node)",
            ));
        }
        Ok(regions
            .iter()
            .enumerate()
            .map(|(r, region)| {
                let (u, t) = (&fields.displacement[r], &fields.traction[r]);
                let mut sum = vec![[0.0; 3]; region.nodes.len()];
                let mut count = vec![0.0; region.nodes.len()];
                for e in &region.elements {
                    let ue = e.nodes.map(|m| u[m]);
                    let te = e.nodes.map(|m| t[m]);
                    for (k, &m) in e.nodes.iter().enumerate() {
                        let st = element_boundary_stress(&region.kernels, e, &ue, &te, e.local[k]);
                        for c in 0..3 {
                            sum[m][c] += st[c];
                        }
                        count[m] += 1.0;
                    }
                }
                sum.iter()
                    .zip(&count)
                    .map(|(s, &c)| if c > 0.0 { s.map(|v| v / c) } else { *s })
                    .collect()
            })
            .collect())
    }
}

/// The boundary fields at every step time t_n = n dt, n = 0..=steps, of a CQ run of `bem`
/// with the data `data` (as given to [`crate::dynamics::cq::convolve`]: `inputs` values
/// per sample) and its result `series`; the zero initial state at t = 0 where the grid has
/// no sample there (Runge-Kutta).
///
/// Errors: a series or data of another shape ([`Error::InvalidParameter`]).
pub fn boundary_field_history(
    bem: &LaplaceBem,
    data: &[f64],
    series: &CqSeries,
) -> Result<Vec<BoundaryFields>> {
    let (ni, no) = (bem.inputs(), bem.outputs());
    let samples = series.grid.samples();
    if series.channels != no || series.values.len() != samples * no {
        return Err(Error::invalid(
            "series",
            series.channels,
            format!("must be a CQ result of this model ({no} outputs per sample)"),
        ));
    }
    if data.len() != samples * ni {
        return Err(Error::invalid(
            "data",
            data.len(),
            format!("must give {ni} inputs per sample ({samples} samples)"),
        ));
    }
    let zero_out = vec![0.0; no];
    let zero_in = vec![0.0; ni];
    (0..=series.grid.steps())
        .map(|n| match series.grid.step_sample(n) {
            Some(k) => bem.boundary_fields(series.sample(k), &data[k * ni..(k + 1) * ni]),
            None => bem.boundary_fields(&zero_out, &zero_in),
        })
        .collect()
}

/// The boundary stresses (Pa, per step n = 0..=steps, region and node: [sigma_xx,
/// sigma_yy, sigma_xy]) of a CQ run ([`boundary_field_history`],
/// [`LaplaceBem::boundary_stresses`]).
///
/// Errors: as [`boundary_field_history`].
pub fn boundary_stress_history(
    bem: &LaplaceBem,
    data: &[f64],
    series: &CqSeries,
) -> Result<Vec<Vec<Vec<[f64; 3]>>>> {
    boundary_field_history(bem, data, series)?
        .iter()
        .map(|f| bem.boundary_stresses(f))
        .collect()
}

#[cfg(test)]
#[path = "stress_tests.rs"]
mod tests;
