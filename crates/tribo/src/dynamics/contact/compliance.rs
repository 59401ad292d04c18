//! The condensed contact compliance `C(s)` as a [`LaplaceResponse`]: inputs the contact
//! unknowns (p, q per slave node) and the load factors, outputs the relative and slave
//! displacements of the slave nodes and the work-conjugate displacements of the loads (see
//! "Condensation" in the module docs of [`super`]).

// Index loops over the two directions read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use faer::c64;

use crate::dynamics::cq::LaplaceResponse;
use crate::dynamics::laplace::LaplaceBem;
use crate::error::{Error, Result};
use crate::kernels::quadrature::gauss_legendre;
use crate::operators::bem2d::mesh::RegionMesh;
use crate::solvers::bem2d::contact::PairGeometry;

/// A sparse linear combination: (index, coefficient).
pub(super) type Combination = Vec<(usize, f64)>;

/// One contact node (a slave node projected on its master), in the global numbering of the
/// contact unknowns.
#[derive(Debug, Clone)]
pub(super) struct NodeData {
    /// Pair index.
    pub pair: usize,
    /// Slave and master regions.
    pub slave_region: usize,
    pub master_region: usize,
    pub position: [f64; 2],
    pub normal: [f64; 2],
    pub tangent: [f64; 2],
    pub initial_gap: f64,
    /// Slave force weight int N ds (covered part), m.
    pub weight: f64,
    pub friction: f64,
}

/// A load column: the prescribed values of the known DOFs that follow one time function in
/// one body, with their work rows.
#[derive(Debug, Clone)]
pub(super) struct LoadColumn {
    /// Index of the time function (`loads.len()` for the default step).
    pub function: usize,
    /// Body (index into the body list).
    pub body: usize,
    /// Force resultant of the column's prescribed tractions at factor 1, N/m.
    pub force: [f64; 2],
    /// `sum w v . v_body` of the prescribed tractions (m/s N/m per unit factor): the rigid
    /// motion's part of the work-conjugate displacement per unit time.
    pub rigid_rate: f64,
}

/// The contact compliance of a Laplace-domain BEM (module docs).
#[derive(Debug, Clone)]
pub(super) struct ContactCompliance {
    pub bem: LaplaceBem,
    /// Known-value vector (sparse, over the BEM inputs) of each input column.
    pub columns: Vec<Combination>,
    /// Each output row as a combination of BEM outputs.
    pub rows: Vec<Combination>,
}

impl LaplaceResponse for ContactCompliance {
    fn inputs(&self) -> usize {
        self.columns.len()
    }

    fn outputs(&self) -> usize {
        self.rows.len()
    }

    fn respond(&self, s: c64, inputs: &[c64]) -> Result<Vec<c64>> {
        let mut known = vec![c64::ZERO; self.bem.inputs()];
        for (col, y) in self.columns.iter().zip(inputs) {
            for &(k, v) in col {
                known[k] += *y * v;
            }
        }
        let x = self.bem.respond_columns(s, &[known])?;
        Ok(self.project(&x[0]))
    }

    fn transfer_matrix(&self, s: c64) -> Result<Vec<c64>> {
        let nk = self.bem.inputs();
        let known: Vec<Vec<c64>> = self
            .columns
            .iter()
            .map(|col| {
                let mut v = vec![c64::ZERO; nk];
                for &(k, c) in col {
                    v[k] += c64::new(c, 0.0);
                }
                v
            })
            .collect();
        let xs = self.bem.respond_columns(s, &known)?;
        let (ni, no) = (self.columns.len(), self.rows.len());
        let mut out = vec![c64::ZERO; ni * no];
        for (j, x) in xs.iter().enumerate() {
            for (i, v) in self.project(x).into_iter().enumerate() {
                out[i * ni + j] = v;
            }
        }
        Ok(out)
    }
}

impl ContactCompliance {
    /// The output rows of the BEM unknowns `x`.
    fn project(&self, x: &[c64]) -> Vec<c64> {
        self.rows
            .iter()
            .map(|row| row.iter().map(|&(k, c)| x[k] * c).sum())
            .collect()
    }
}

/// int N_k ds per node of a region (its field shape functions over its elements), m.
pub(super) fn node_weights(region: &RegionMesh) -> Vec<f64> {
    let (gx, gw) = gauss_legendre(8);
    let mut w = vec![0.0; region.nodes.len()];
    for e in &region.local_elements {
        for (&xi, &wq) in gx.iter().zip(&gw) {
            let (_, jac) = e.normal_jacobian(xi);
            let nsh = e.field_shape(xi);
            for a in 0..3 {
                w[e.nodes[a]] += wq * jac * nsh[a];
            }
        }
    }
    w
}

/// The area of a region, `int x n_x ds` over its boundary (divergence theorem; exact for
/// the quadratic geometry with 8 Gauss points), m^2.
pub(super) fn region_area(region: &RegionMesh) -> f64 {
    let (gx, gw) = gauss_legendre(8);
    let mut a = 0.0;
    for e in &region.local_elements {
        for (&xi, &wq) in gx.iter().zip(&gw) {
            let (n, jac) = e.normal_jacobian(xi);
            a += wq * jac * e.point(xi)[0] * n[0];
        }
    }
    a
}

/// The input columns of the contact unknowns (p_i then q_i) and the output rows
/// (relative normal, relative tangential, slave normal, slave tangential displacement per
/// node) of the pairs' geometry on `bem`. Errors: a contact DOF that is not a known
/// traction of the BEM (a condition on a contact segment).
pub(super) fn contact_maps(
    bem: &LaplaceBem,
    geometry: &[PairGeometry],
) -> Result<(Vec<NodeData>, Vec<Combination>, Vec<Combination>)> {
    let input_of: HashMap<(usize, usize, usize), usize> = bem
        .known_dofs()
        .iter()
        .enumerate()
        .filter(|(_, k)| !k.displacement)
        .map(|(i, k)| ((k.region, k.node, k.direction), i))
        .collect();
    let input = |r: usize, node: usize, d: usize, field: &str| -> Result<usize> {
        input_of.get(&(r, node, d)).copied().ok_or_else(|| {
            Error::invalid(
                field.to_string(),
                format!("node {node} of region {r}"),
                "a contact node must be traction-free in the boundary conditions",
            )
        })
    };
    let output = |r: usize, node: usize, d: usize| -> Result<usize> {
        bem.unknown_output(r, node, d)
            .ok_or_else(|| Error::Numerical {
                context: "dynamic contact",
                detail: format!("no unknown for node {node} of region {r}"),
            })
    };
    let mut nodes = Vec::new();
    let mut pcols = Vec::new();
    let mut qcols = Vec::new();
    let mut rel = [Vec::new(), Vec::new()];
    let mut slave = [Vec::new(), Vec::new()];
    for (k, pg) in geometry.iter().enumerate() {
        let field = format!("contact_pair[{k}]");
        let (rs, rm) = (pg.slave_region, pg.master_region);
        for sn in &pg.nodes {
            for (dir, cols) in [(sn.normal, &mut pcols), (sn.tangent, &mut qcols)] {
                let mut col: Combination = Vec::new();
                for d in 0..2 {
                    col.push((input(rs, sn.region_node, d, &field)?, dir[d]));
                    for (a, &mnode) in pg.master_nodes.iter().enumerate() {
                        let c = pg.transfer[a * pg.slave_count + sn.segment_index];
                        if c != 0.0 {
                            col.push((input(rm, mnode, d, &field)?, -c * dir[d]));
                        }
                    }
                }
                cols.push(col);
            }
            for (m, dir) in [sn.normal, sn.tangent].into_iter().enumerate() {
                let mut r: Combination = Vec::new();
                let mut s: Combination = Vec::new();
                for d in 0..2 {
                    let o = output(rs, sn.region_node, d)?;
                    r.push((o, dir[d]));
                    s.push((o, dir[d]));
                    let (mn, sh) = sn.master;
                    for a in 0..3 {
                        r.push((output(rm, mn[a], d)?, -sh[a] * dir[d]));
                    }
                }
                rel[m].push(r);
                slave[m].push(s);
            }
            nodes.push(NodeData {
                pair: k,
                slave_region: rs,
                master_region: rm,
                position: sn.position,
                normal: sn.normal,
                tangent: sn.tangent,
                initial_gap: sn.initial_gap,
                weight: sn.weight,
                friction: pg.pair.friction,
            });
        }
    }
    let [rn, rt] = rel;
    let [sn, st] = slave;
    let columns = pcols.into_iter().chain(qcols).collect();
    let rows = rn.into_iter().chain(rt).chain(sn).chain(st).collect();
    Ok((nodes, columns, rows))
}
