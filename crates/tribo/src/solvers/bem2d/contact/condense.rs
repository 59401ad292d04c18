//! Condensation of the factored bodies onto the contact unknowns; see "Condensation" in
//! the module docs of [`super`].

use super::*;

impl ContactProblem {
    /// Response of the displacement component (region, node, d) as (external, per body
    /// parameter) coefficients: the body and its row.
    #[allow(
        clippy::expect_used,
        reason = "the bodies partition the regions and hold their columns by construction (from_problem): a failure is a bug, not bad input"
    )]
    pub(super) fn displacement_row(&self, region: usize, node: usize, d: usize) -> (usize, usize) {
        let col = match self.dofs[region][node][d] {
            Dof::U { col, .. } => col,
            _ => unreachable!("contact nodes carry traction-type DOFs"),
        };
        let b = self
            .bodies
            .iter()
            .position(|b| b.regions.iter().any(|&(r, _)| r == region))
            .expect("every region is in a body");
        let row = self.bodies[b]
            .cols
            .binary_search(&col)
            .expect("column of the body");
        (b, row)
    }

    /// Builds W_n, W_t, K and the external-load responses.
    #[allow(
        clippy::expect_used,
        reason = "the bodies partition the regions and hold their columns by construction (from_problem): a failure is a bug, not bad input"
    )]
    pub(super) fn condense(&mut self) {
        let n = self.n;
        let nz = self.pz.ncols();
        let next = self.next();
        // A row in parameter space (length np) + external coefficients (per load group), for
        // a displacement.
        let urow =
            |this: &Self, region: usize, node: usize, d: usize| -> (Vec<f64>, Vec<(usize, f64)>) {
                let (b, row) = this.displacement_row(region, node, d);
                let body = &this.bodies[b];
                let ext = (0..next).map(|g| body.x[(row, g)]).collect();
                let coef = body
                    .params
                    .iter()
                    .enumerate()
                    .map(|(k, &gp)| (gp, body.x[(row, next + k)]))
                    .collect();
                (ext, coef)
            };
        // Relative displacement rows in parameter space.
        let np = self.params.len();
        let mut rel = Mat::<f64>::zeros(2 * n, np);
        let mut rel_ext = Mat::<f64>::zeros(2 * n, next);
        for p in &self.pairs {
            let sinfo = &self.problem.mesh.segments[p.slave_seg];
            let minfo = &self.problem.mesh.segments[p.master_seg];
            for (b, sn) in p.nodes.iter().enumerate() {
                let Some((mn, sh)) = sn.master else { continue };
                let i = p.offset + b;
                if p.pair.rule == GapRule::Weighted {
                    // (sum_b' Ms[b][b'] u_s(b') - sum_a D[a][b] u_m(a)) / int N_b ds.
                    let wb = p.slave_weights[b];
                    for d in 0..2 {
                        for (b2, &o) in sinfo.owner_nodes.iter().enumerate() {
                            let m = p.smass[(b, b2)];
                            if m == 0.0 {
                                continue;
                            }
                            let (e, c) = urow(self, sinfo.owner, o, d);
                            for g in 0..next {
                                rel_ext[(2 * i + d, g)] += m / wb * e[g];
                            }
                            for (gp, v) in c {
                                rel[(2 * i + d, gp)] += m / wb * v;
                            }
                        }
                        for (a, &o) in minfo.owner_nodes.iter().enumerate() {
                            let m = p.dmat[(a, b)];
                            if m == 0.0 {
                                continue;
                            }
                            let (e, c) = urow(self, minfo.owner, o, d);
                            for g in 0..next {
                                rel_ext[(2 * i + d, g)] -= m / wb * e[g];
                            }
                            for (gp, v) in c {
                                rel[(2 * i + d, gp)] -= m / wb * v;
                            }
                        }
                    }
                    continue;
                }
                for d in 0..2 {
                    let (e, c) = urow(self, sinfo.owner, sn.region_node, d);
                    for g in 0..next {
                        rel_ext[(2 * i + d, g)] += e[g];
                    }
                    for (gp, v) in c {
                        rel[(2 * i + d, gp)] += v;
                    }
                    for a in 0..3 {
                        let o = minfo.owner_nodes[mn[a]];
                        let (e, c) = urow(self, minfo.owner, o, d);
                        for g in 0..next {
                            rel_ext[(2 * i + d, g)] -= sh[a] * e[g];
                        }
                        for (gp, v) in c {
                            rel[(2 * i + d, gp)] -= sh[a] * v;
                        }
                    }
                }
            }
        }
        let relz = &rel * &self.pz;
        let mut wn = Mat::<f64>::zeros(n, nz);
        let mut wt = Mat::<f64>::zeros(n, nz);
        let mut gn_ext = Mat::<f64>::zeros(n, next);
        let mut st_ext = Mat::<f64>::zeros(n, next);
        for p in &self.pairs {
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                for d in 0..2 {
                    for g in 0..next {
                        gn_ext[(i, g)] += sn.normal[d] * rel_ext[(2 * i + d, g)];
                        st_ext[(i, g)] += sn.tangent[d] * rel_ext[(2 * i + d, g)];
                    }
                    for c in 0..nz {
                        wn[(i, c)] += sn.normal[d] * relz[(2 * i + d, c)];
                        wt[(i, c)] += sn.tangent[d] * relz[(2 * i + d, c)];
                    }
                }
            }
        }
        // Rigid force rows: F_d = sum_node w_node * t_d(node).
        let nrig = 2 * self.rigid.len();
        let mut frow = Mat::<f64>::zeros(nrig, np);
        let mut f_ext = Mat::<f64>::zeros(nrig, next);
        for (j, (_, seg)) in self.rigid.iter().enumerate() {
            let info = &self.problem.mesh.segments[*seg];
            let weights = node_weights(&self.problem, *seg);
            for (k, &o) in info.owner_nodes.iter().enumerate() {
                for d in 0..2 {
                    let col = match self.dofs[info.owner][o][d] {
                        Dof::T { col, .. } => col,
                        _ => unreachable!("rigid nodes carry displacement-type DOFs"),
                    };
                    let b = self
                        .bodies
                        .iter()
                        .position(|b| b.regions.iter().any(|&(r, _)| r == info.owner))
                        .expect("body");
                    let body = &self.bodies[b];
                    let row = body.cols.binary_search(&col).expect("column");
                    let w = weights[k] * self.scale;
                    for g in 0..next {
                        f_ext[(2 * j + d, g)] += w * body.x[(row, g)];
                    }
                    for (kk, &gp) in body.params.iter().enumerate() {
                        frow[(2 * j + d, gp)] += w * body.x[(row, next + kk)];
                    }
                }
            }
        }
        self.kf = &frow * &self.pz;
        self.wn = wn;
        self.wt = wt;
        self.gn_ext = gn_ext;
        self.st_ext = st_ext;
        self.f_ext = f_ext;
    }
}

/// The inputs of the body factorizations (a phase of [`ContactProblem::from_problem`]).
pub(super) struct BodyAssembly<'a> {
    pub(super) problem: &'a BemProblem,
    pub(super) dofs: &'a [Vec<[Dof; 2]>],
    /// The body (root region) of every region.
    pub(super) body_of: &'a [usize],
    pub(super) prm: &'a Params,
    pub(super) free: &'a [FreeBody],
    pub(super) rigid_segs: &'a [(String, usize)],
    pub(super) seg_group: &'a [usize],
    /// Column scale of the traction unknowns (the largest shear modulus), Pa.
    pub(super) scale: f64,
    /// Number of load-group columns.
    pub(super) next: usize,
}

/// One body's system A x = b: its regions with their row offsets, its global columns
/// (body-local index -> global column), its parameters, the matrix and the right-hand
/// sides (load groups, then unit parameters).
struct BodySystem {
    regions: Vec<(usize, usize)>,
    cols: Vec<usize>,
    bparams: Vec<usize>,
    a: Mat<f64>,
    rhs: Mat<f64>,
}

impl BodyAssembly<'_> {
    /// Bodies: assemble, factor once, solve for the external load and the unit parameters.
    /// Returns the bodies and the largest relative residual of their solves.
    pub(super) fn factor_bodies(&self) -> Result<(Vec<Body>, f64)> {
        let nr = self.problem.mesh.regions.len();
        let mut roots: Vec<usize> = self.body_of.to_vec();
        roots.sort_unstable();
        roots.dedup();
        let mut bodies = Vec::new();
        let mut lu_residual = 0.0_f64;
        for &root in &roots {
            let members: Vec<usize> = (0..nr).filter(|&r| self.body_of[r] == root).collect();
            let sys = self.assemble(&members, root)?;
            let (body, worst) = self.solve(&members, sys)?;
            lu_residual = lu_residual.max(worst);
            bodies.push(body);
        }
        Ok((bodies, lu_residual))
    }

    /// The system of the body `root` (regions `members`): BEM rows H u = G t of its regions
    /// with the DOFs' known values on the right, the external load per group column and a
    /// column per unit body parameter.
    fn assemble(&self, members: &[usize], root: usize) -> Result<BodySystem> {
        let (problem, dofs, next, scale) = (self.problem, self.dofs, self.next, self.scale);
        let (body_of, free, rigid_segs) = (self.body_of, self.free, self.rigid_segs);
        let mesh = &problem.mesh;
        let np = self.prm.params.len();
        let mut regions = Vec::new();
        let mut rows = 0;
        let mut cols = Vec::new();
        for &r in members {
            regions.push((r, rows));
            rows += problem.operators[r].h.nrows();
            for d in &dofs[r] {
                for dof in d {
                    match *dof {
                        Dof::U { col, .. } | Dof::T { col, .. } => cols.push(col),
                        Dof::Interface { u_col, t_col, .. } => {
                            cols.push(u_col);
                            cols.push(t_col);
                        }
                    }
                }
            }
        }
        cols.sort_unstable();
        cols.dedup();
        let local: HashMap<usize, usize> = cols.iter().enumerate().map(|(i, &c)| (c, i)).collect();
        if cols.len() != rows {
            return Err(Error::Numerical {
                context: "2D BEM contact",
                detail: format!("body system is {rows} x {} (not square)", cols.len()),
            });
        }
        let bparams: Vec<usize> = (0..np)
            .filter(|&k| match self.prm.params[k] {
                Param::Traction { region, .. } => body_of[region] == root,
                Param::Rigid { j, .. } => body_of[mesh.segments[rigid_segs[j].1].owner] == root,
                Param::Free { f, .. } => body_of[free[f].regions[0]] == root,
            })
            .collect();
        let bp_index: HashMap<usize, usize> =
            bparams.iter().enumerate().map(|(i, &k)| (k, i)).collect();
        let what = format!("the 2D BEM contact body system ({rows} x {rows})");
        let mut a = try_zeros(&what, rows, rows)?;
        let mut rhs = try_zeros(&what, rows, next + bparams.len())?;
        for &(r, off) in &regions {
            let ops = &problem.operators[r];
            let n2 = ops.h.nrows();
            for (node, d) in dofs[r].iter().enumerate() {
                // Columns of the node's components: the global axes, or the directions of
                // a support's frame (H u = H_x u_x + H_y u_y with u = sum_j u_j f_j).
                let frame = node_frame(free, r, node);
                for (dir, dof) in d.iter().enumerate() {
                    let c = 2 * node + dir;
                    let column = |m: &Mat<f64>| -> Vec<f64> {
                        match frame {
                            None => (0..n2).map(|row| m[(row, c)]).collect(),
                            Some(f) => (0..n2)
                                .map(|row| {
                                    f[dir][0] * m[(row, 2 * node)]
                                        + f[dir][1] * m[(row, 2 * node + 1)]
                                })
                                .collect(),
                        }
                    };
                    let (hc, gc) = (column(&ops.h), column(&ops.g));
                    let seg = self_segment(problem, r, node);
                    let grp = self.seg_group[seg];
                    match *dof {
                        Dof::U { col, t } => {
                            let lc = local[&col];
                            let pk = self.prm.param_of.get(&(r, node, dir)).map(|k| bp_index[k]);
                            for row in 0..n2 {
                                a[(off + row, lc)] += hc[row];
                                rhs[(off + row, grp)] += gc[row] * t;
                                if let Some(pk) = pk {
                                    rhs[(off + row, next + pk)] += gc[row];
                                }
                            }
                        }
                        Dof::T { col, u } => {
                            let lc = local[&col];
                            let rj = rigid_segs.iter().position(|&(_, s)| s == seg);
                            for row in 0..n2 {
                                a[(off + row, lc)] -= gc[row] * scale;
                                rhs[(off + row, grp)] -= hc[row] * u;
                            }
                            if let Some(j) = rj {
                                let pk = bp_index[&(self.prm.rigid_base + 2 * j + dir)];
                                for row in 0..n2 {
                                    rhs[(off + row, next + pk)] -= hc[row];
                                }
                            }
                            if let Some(&(f, q)) = self.prm.pin_of.get(&(r, node, dir)) {
                                let fb = &free[f];
                                for (k, &v) in fb.pins[q].row.iter().enumerate() {
                                    let pk = bp_index[&(fb.param0 + k)];
                                    for row in 0..n2 {
                                        rhs[(off + row, next + pk)] -= hc[row] * v;
                                    }
                                }
                            }
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            let (lu_, lt) = (local[&u_col], local[&t_col]);
                            for row in 0..n2 {
                                a[(off + row, lu_)] += hc[row];
                                a[(off + row, lt)] -= sign * gc[row] * scale;
                            }
                        }
                    }
                }
            }
        }
        // Body forces are external loads: their term H u_p - G t_p joins column 0.
        for &(r, off) in &regions {
            for (row, v) in problem.body_force_rhs(r).into_iter().flatten().enumerate() {
                rhs[(off + row, 0)] += v;
            }
        }
        Ok(BodySystem {
            regions,
            cols,
            bparams,
            a,
            rhs,
        })
    }

    /// Factors and solves one body's system; checks the residual (relative, on the load
    /// column and two parameter columns) and the finiteness of every solution. Returns the
    /// body and its residual.
    fn solve(&self, members: &[usize], sys: BodySystem) -> Result<(Body, f64)> {
        let mesh = &self.problem.mesh;
        let next = self.next;
        let BodySystem {
            regions,
            cols,
            bparams,
            a,
            rhs,
        } = sys;
        let rows = a.nrows();
        // The LU's copy of the matrix and the solution, allocated inside faer.
        probe_memory(
            &format!("the LU factorization of the 2D BEM contact body system ({rows} x {rows})"),
            matrix_bytes(rows, rows + next + bparams.len()),
        )?;
        let lu = a.partial_piv_lu();
        let x = lu.solve(&rhs);
        // Accuracy check on the external-load column and two parameter columns (a
        // full check would cost as much as the solves), plus finiteness of all.
        let k = rhs.ncols().min(3);
        let xs = Mat::from_fn(rows, k, |i, j| x[(i, j)]);
        let bs = Mat::from_fn(rows, k, |i, j| rhs[(i, j)]);
        let res = &a * &xs - &bs;
        let na = (0..rows)
            .map(|i| (0..rows).map(|c| a[(i, c)].abs()).sum::<f64>())
            .fold(0.0_f64, nan_max);
        let mut worst = 0.0_f64;
        for j in 0..k {
            let (mut nr_, mut nx, mut nb) = (0.0_f64, 0.0_f64, 0.0_f64);
            for i in 0..rows {
                nr_ = nan_max(nr_, res[(i, j)].abs());
                nx = nan_max(nx, xs[(i, j)].abs());
                nb = nan_max(nb, bs[(i, j)].abs());
            }
            worst = nan_max(worst, nr_ / nan_max(na * nx + nb, f64::MIN_POSITIVE));
        }
        let finite = (0..x.ncols()).all(|j| (0..rows).all(|i| x[(i, j)].is_finite()));
        if !finite {
            worst = f64::INFINITY;
        }
        if worst.is_nan() || worst >= 1e-8 {
            let names: Vec<&str> = members
                .iter()
                .map(|&r| mesh.regions[r].name.as_str())
                .collect();
            return Err(Error::Numerical {
                context: "2D BEM contact",
                detail: format!(
                    "the LU solve of body [{}] failed (relative residual {worst:.3e})",
                    names.join(", ")
                ),
            });
        }
        Ok((
            Body {
                regions,
                cols,
                params: bparams,
                x,
            },
            worst,
        ))
    }
}
