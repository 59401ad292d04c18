//! Energy of linear dynamic runs from the boundary histories: the input work
//!
//! ```text
//! W(t) = int_0^t oint_G t . du/dt dG dt'     (J/m per unit thickness)
//! ```
//!
//! of the tractions on the bodies (the BEM's nodal tractions, Pa) through the boundary
//! velocities, the `input_work` of [`crate::dynamics::history::EnergyHistory`]: loads on
//! loaded boundaries, reactions on supported ones (zero where the
//! support holds the displacement fixed, du = 0), and nothing on bonded interfaces (the
//! two sides' tractions are opposite on equal displacements, so their terms cancel).
//!
//! **Time rule (trapezoid).** Between the step times t_(n-1), t_n the Stieltjes integral
//! `int t . du` is taken with t and u linear in time:
//! `W_n = W_(n-1) + oint (t_n + t_(n-1))/2 . (u_n - u_(n-1)) dG`, exact for piecewise
//! linear histories and second order for smooth ones; no velocity is formed (the CQ
//! velocity would be first/second order by the method too, and the difference of
//! displacements is what the CQ gives most accurately). For a constant load
//! `t = p` it is exactly `W = oint p . u(t) dG`: work of a dead load.
//!
//! **Space rule.** `oint a . b dG = sum_e sum_(k,m) M^e_km a_k . b_m` with the element
//! "mass" matrices `M^e_km = int_e N_k N_m J dxi` of the quadratic fields, by 6-point
//! Gauss-Legendre (exact for straight elements, whose integrand is a quartic polynomial;
//! on arcs the Jacobian's variation leaves ~1e-10 relative for the meshes used).
//!
//! The strain and kinetic energies are not boundary quantities for a dynamic state (no
//! static Clapeyron identity holds): they stay `None` in [`EnergySample`] until a domain
//! integration exists. For a linear run from rest they sum to W at all times (no
//! dissipation); the tests check W against the 1D column's closed form, where
//! `U + K = W = p0 A u(0, t)` is known exactly.

use crate::dynamics::cq::CqSeries;
use crate::dynamics::history::EnergySample;
use crate::dynamics::laplace::stress::{boundary_field_history, BoundaryFields};
use crate::dynamics::laplace::LaplaceBem;
use crate::error::{Error, Result};
use crate::kernels::quadrature::gauss_legendre;

/// One element's nodes and its mass matrix `int N_k N_m J dxi` (m).
type ElementMass = ([usize; 3], [[f64; 3]; 3]);

/// The boundary bilinear form `oint a . b dG` of a model (see the module docs): per region
/// and element, the nodes and the 3 x 3 matrix `int N_k N_m J dxi` (m).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryForm {
    /// Per region: (element nodes, mass matrix) per element.
    regions: Vec<Vec<ElementMass>>,
    /// Node count per region.
    nodes: Vec<usize>,
}

impl BoundaryForm {
    /// The form of `bem`'s mesh (every element of every region).
    pub fn new(bem: &LaplaceBem) -> Self {
        let (x, w) = gauss_legendre(6);
        let mesh = &bem.static_problem().mesh;
        let regions = mesh
            .regions
            .iter()
            .map(|region| {
                region
                    .elements
                    .iter()
                    .map(|e| {
                        let mut m = [[0.0; 3]; 3];
                        for (&xi, &wi) in x.iter().zip(&w) {
                            let (_, jac) = e.normal_jacobian(xi);
                            let n = e.field_shape(xi);
                            for (k, row) in m.iter_mut().enumerate() {
                                for (l, v) in row.iter_mut().enumerate() {
                                    *v += wi * jac * n[k] * n[l];
                                }
                            }
                        }
                        (e.nodes, m)
                    })
                    .collect()
            })
            .collect();
        let nodes = mesh.regions.iter().map(|r| r.nodes.len()).collect();
        Self { regions, nodes }
    }

    /// `oint a . b dG` (units of a times b times m) for nodal vectors per region and node.
    ///
    /// Errors: fields of another shape ([`Error::InvalidParameter`]).
    pub fn apply(&self, a: &[Vec<[f64; 2]>], b: &[Vec<[f64; 2]>]) -> Result<f64> {
        let fits = |f: &[Vec<[f64; 2]>]| {
            f.len() == self.nodes.len() && f.iter().zip(&self.nodes).all(|(v, n)| v.len() == *n)
        };
        if !(fits(a) && fits(b)) {
            return Err(Error::invalid(
                "fields",
                "their node counts",
                "must be nodal fields of this model (one value per region and node)",
            ));
        }
        let mut sum = 0.0;
        for ((elements, a), b) in self.regions.iter().zip(a).zip(b) {
            for (nodes, m) in elements {
                for (k, &p) in nodes.iter().enumerate() {
                    for (l, &q) in nodes.iter().enumerate() {
                        sum += m[k][l] * (a[p][0] * b[q][0] + a[p][1] * b[q][1]);
                    }
                }
            }
        }
        Ok(sum)
    }
}

/// The input work W(t_n) (J/m) at the step times of a sequence of boundary fields
/// (module docs: trapezoid in time, W_0 = 0 from rest).
///
/// Errors: fields of another model ([`Error::InvalidParameter`]).
pub fn input_work_of_fields(form: &BoundaryForm, fields: &[BoundaryFields]) -> Result<Vec<f64>> {
    let mut work = Vec::with_capacity(fields.len());
    let mut w = 0.0;
    for (n, f) in fields.iter().enumerate() {
        if n > 0 {
            let prev = &fields[n - 1];
            let mean: Vec<Vec<[f64; 2]>> = f
                .traction
                .iter()
                .zip(&prev.traction)
                .map(|(a, b)| {
                    a.iter()
                        .zip(b)
                        .map(|(x, y)| [0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])])
                        .collect()
                })
                .collect();
            let du: Vec<Vec<[f64; 2]>> = f
                .displacement
                .iter()
                .zip(&prev.displacement)
                .map(|(a, b)| {
                    a.iter()
                        .zip(b)
                        .map(|(x, y)| [x[0] - y[0], x[1] - y[1]])
                        .collect()
                })
                .collect();
            w += form.apply(&mean, &du)?;
        } else {
            // Check the shape of the first state too.
            form.apply(&f.traction, &f.displacement)?;
        }
        work.push(w);
    }
    Ok(work)
}

/// The input work W(t_n) (J/m), n = 0..=steps, of a linear CQ run of `bem` with the data
/// `data` and the result `series` (as [`crate::dynamics::laplace::stress::boundary_field_history`]).
///
/// Errors: as there.
pub fn input_work(bem: &LaplaceBem, data: &[f64], series: &CqSeries) -> Result<Vec<f64>> {
    let fields = boundary_field_history(bem, data, series)?;
    input_work_of_fields(&BoundaryForm::new(bem), &fields)
}

/// The energy samples of a linear run: the input work only (the other terms are not
/// computed, module docs).
pub fn energy_samples(work: &[f64]) -> Vec<EnergySample> {
    work.iter()
        .map(|&w| EnergySample {
            input_work: Some(w),
            ..Default::default()
        })
        .collect()
}

#[cfg(test)]
#[path = "energy_tests.rs"]
mod tests;
