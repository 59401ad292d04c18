//! Free bodies: their rigid-body modes, artificial supports and motion; see "Loads,
//! rigid-body modes and steps" in the module docs of [`super`].

use super::*;

/// The displacement of node component d at `p` per unit amplitude of the rigid modes
/// (translation x, translation y, rotation about `c` scaled by `size`: amplitude = size *
/// angle, so that all three are lengths).
pub(super) fn rigid_row(d: usize, p: [f64; 2], c: [f64; 2], size: f64) -> [f64; 3] {
    if d == 0 {
        [1.0, 0.0, -(p[1] - c[1]) / size]
    } else {
        [0.0, 1.0, (p[0] - c[0]) / size]
    }
}

/// [`rigid_row`] of the component along direction `frame[j]` (global axis j where `frame`
/// is None).
pub(super) fn local_rigid_row(
    frame: Option<[[f64; 2]; 2]>,
    j: usize,
    p: [f64; 2],
    c: [f64; 2],
    size: f64,
) -> [f64; 3] {
    match frame {
        None => rigid_row(j, p, c, size),
        Some(f) => {
            let (r0, r1) = (rigid_row(0, p, c, size), rigid_row(1, p, c, size));
            [0, 1, 2].map(|i| f[j][0] * r0[i] + f[j][1] * r1[i])
        }
    }
}

/// The component frame of node `o` of region `r` ([`Pin::frame`]): None where its
/// components are along the global axes.
pub(super) fn node_frame(free: &[FreeBody], r: usize, o: usize) -> Option<[[f64; 2]; 2]> {
    free.iter()
        .flat_map(|fb| &fb.pins)
        .find(|p| p.region == r && p.node == o)
        .and_then(|p| p.frame)
}

/// A model-local point (relative to [`BemMesh::origin`](crate::operators::bem2d::BemMesh))
/// in global coordinates, m.
pub(super) fn to_global(mesh: &crate::operators::bem2d::BemMesh, x: [f64; 2]) -> [f64; 2] {
    [x[0] + mesh.origin[0], x[1] + mesh.origin[1]]
}

/// The rigid modes (tx, ty, size * rotation about `c`) that the prescribed displacement
/// components `rows` (direction, position) leave free: an orthonormal basis of the null space
/// of the constraint matrix (eigenvalues of its Gram matrix below 1e-12 per row, i.e. the
/// 1e-6 of the BEM restraint check), built from the projections of tx, ty and the rotation in
/// turn (largest first), so that a single free translation or rotation comes out as itself.
/// [`Error::Numerical`] where the eigendecomposition fails (non-finite positions).
pub(super) fn free_modes(
    rows: &[(usize, [f64; 2])],
    c: [f64; 2],
    size: f64,
) -> Result<Vec<[f64; 3]>> {
    let mut gram = vec![vec![0.0; 3]; 3];
    for (d, p) in rows {
        let r = rigid_row(*d, *p, c, size);
        for i in 0..3 {
            for j in 0..3 {
                gram[i][j] += r[i] * r[j];
            }
        }
    }
    let (vals, vecs) = symmetric_eigen(&gram, "2D BEM contact: free rigid-body modes")?;
    let tol = 1e-12 * rows.len().max(1) as f64;
    let null: Vec<[f64; 3]> = (0..3)
        .filter(|&k| vals[k] <= tol)
        .map(|k| [vecs[0][k], vecs[1][k], vecs[2][k]])
        .collect();
    let mut basis: Vec<[f64; 3]> = Vec::new();
    for _ in 0..null.len() {
        let mut best = (0.0, [0.0; 3]);
        for e in 0..3 {
            let mut w = [0.0; 3];
            for nv in &null {
                for i in 0..3 {
                    w[i] += nv[e] * nv[i];
                }
            }
            for b in &basis {
                let d = dot3(w, *b);
                for i in 0..3 {
                    w[i] -= d * b[i];
                }
            }
            let nw = dot3(w, w).sqrt();
            if nw > best.0 + 1e-12 {
                best = (nw, w.map(|x| x / nw));
            }
        }
        basis.push(best.1);
    }
    Ok(basis)
}

/// A rigid motion (tx, ty, size * rotation about `c`) in words.
pub(super) fn describe_mode(mode: [f64; 3], c: [f64; 2], size: f64) -> String {
    let nrm = dot3(mode, mode).sqrt().max(f64::MIN_POSITIVE);
    let [a, b, r] = mode.map(|x| x / nrm);
    if r.abs() < 1e-6 {
        if b.abs() < 1e-6 {
            "translation in x".to_string()
        } else if a.abs() < 1e-6 {
            "translation in y".to_string()
        } else {
            let h = a.hypot(b);
            format!("translation along ({:.4}, {:.4})", a / h, b / h)
        }
    } else {
        // u = (a - theta (y - cy), b + theta (x - cx)) vanishes at the centre.
        let theta = r / size;
        format!(
            "rotation about ({:.6e}, {:.6e}) m",
            c[0] - b / theta,
            c[1] + a / theta
        )
    }
}

/// Arc-length centroid of a body's boundary (its regions' elements off bonded interfaces)
/// and the largest distance of a boundary point from it, m.
pub(super) fn boundary_centroid(problem: &BemProblem, members: &[usize]) -> ([f64; 2], f64) {
    let mesh = &problem.mesh;
    let (gx, gw) = gauss_legendre(8);
    let (mut len, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for &r in members {
        for e in &mesh.regions[r].local_elements {
            if mesh.segments[e.segment].partner.is_some() {
                continue;
            }
            for (&xi, &w) in gx.iter().zip(&gw) {
                let x = e.point(xi);
                let (_, jac) = e.normal_jacobian(xi);
                len += w * jac;
                sx += w * jac * x[0];
                sy += w * jac * x[1];
            }
        }
    }
    let c = [sx / len, sy / len];
    let mut size = 0.0_f64;
    for &r in members {
        for e in &mesh.regions[r].local_elements {
            for g in &e.geometry {
                size = size.max((g[0] - c[0]).hypot(g[1] - c[1]));
            }
        }
    }
    (c, size.max(f64::MIN_POSITIVE))
}

/// int N ds of node `o` of region `r` (over the elements that hold it), m.
pub(super) fn node_weight(problem: &BemProblem, r: usize, o: usize) -> f64 {
    let (gx, gw) = gauss_legendre(8);
    let mut w = 0.0;
    for e in &problem.mesh.regions[r].local_elements {
        if let Some(a) = e.nodes.iter().position(|&q| q == o) {
            for (&xi, &wq) in gx.iter().zip(&gw) {
                let (_, jac) = e.normal_jacobian(xi);
                w += wq * jac * e.field_shape(xi)[a];
            }
        }
    }
    w
}

/// What both support searches of a free body ([`covariant_pins`], [`pivoted_pins`]) read: the
/// body's regions, the segment roles and load groups, its contact nodes (model-local
/// positions, m), its free rigid modes, and the centre (m) and size (m) the modes are scaled by.
#[derive(Clone, Copy)]
struct PinSearch<'a> {
    problem: &'a BemProblem,
    members: &'a [usize],
    role: &'a HashMap<usize, String>,
    seg_group: &'a [usize],
    contact: &'a [[f64; 2]],
    modes: &'a [[f64; 3]],
    center: [f64; 2],
    size: f64,
}

/// The free rigid-body modes of a body that takes part in a contact pair, and its artificial
/// supports: for each free mode one traction-type node component off the contact and rigid
/// segments, chosen by pivoting (the component whose rigid-mode row has the largest part
/// orthogonal to the rows chosen before; among near ties, the one farthest from the contact),
/// so that the supports are statically determinate and far apart. The chosen components
/// become displacement unknowns-as-parameters in `dofs`. None where the body is restrained.
pub(super) fn free_body(
    problem: &BemProblem,
    dofs: &mut [Vec<[Dof; 2]>],
    members: &[usize],
    role: &HashMap<usize, String>,
    seg_group: &[usize],
) -> Result<Option<FreeBody>> {
    let mesh = &problem.mesh;
    let (center, size) = boundary_centroid(problem, members);
    let mut rows = Vec::new();
    for &r in members {
        for (x, d) in mesh.regions[r].local_positions.iter().zip(&dofs[r]) {
            for (dir, dof) in d.iter().enumerate() {
                if matches!(dof, Dof::T { .. }) {
                    rows.push((dir, *x));
                }
            }
        }
    }
    let modes = free_modes(&rows, center, size)?;
    if modes.is_empty() {
        return Ok(None);
    }
    let names: Vec<&str> = members
        .iter()
        .map(|&r| mesh.regions[r].name.as_str())
        .collect();
    let field = format!("body [{}]", names.join(", "));
    let contact: Vec<[f64; 2]> = members
        .iter()
        .flat_map(|&r| {
            let region = &mesh.regions[r];
            region.nodes.iter().zip(&region.local_positions)
        })
        .filter(|(n, _)| role.contains_key(&n.segment))
        .map(|(_, x)| *x)
        .collect();
    let search = PinSearch {
        problem,
        members,
        role,
        seg_group,
        contact: &contact,
        modes: &modes,
        center,
        size,
    };
    let covariant = if modes.len() == 3 {
        covariant_pins(&search, dofs)
    } else {
        None
    };
    let pins = match covariant {
        Some(pins) => pins,
        None => pivoted_pins(&search, dofs, &field)?,
    };
    Ok(Some(FreeBody {
        name: mesh.regions[members[0]].name.clone(),
        field,
        regions: members.to_vec(),
        center,
        size,
        modes,
        zcol: 0,
        param0: 0,
        pins,
    }))
}

/// The supports of a body with all three rigid modes free, chosen so that they turn with the
/// body: node A supported in both components (its whole displacement, a frame-free
/// condition) and node B along the normal to AB (a direction fixed in the body), so that the
/// supports' reactions (the BEM's equilibrium defect, see the module docs) act along the
/// same body directions wherever the model is turned (supports along the global axes made
/// the contact tractions of a turned model differ by up to 2.7e-4 of p_max). A and B are the
/// pair of traction-loaded nodes off the contact, rigid and interface segments that
/// maximizes far(A) far(B) |AB| (far: distance from the nearest contact node; the first
/// pair in node order within 1e-9 of the maximum, so that near ties of symmetric bodies are
/// broken the same way at any position). B's two DOFs are taken in the frame (normal,
/// along AB) ([`Pin::frame`]). None where no such pair exists (then [`pivoted_pins`]
/// reports the unsupported mode).
fn covariant_pins(search: &PinSearch<'_>, dofs: &mut [Vec<[Dof; 2]>]) -> Option<Vec<Pin>> {
    let PinSearch {
        problem,
        members,
        role,
        seg_group,
        contact,
        modes,
        center,
        size,
    } = *search;
    let mesh = &problem.mesh;
    // (region, node, position, far, prescribed traction, columns)
    let mut cand = Vec::new();
    for &r in members {
        for (o, node) in mesh.regions[r].nodes.iter().enumerate() {
            if role.contains_key(&node.segment) || mesh.segments[node.segment].partner.is_some() {
                continue;
            }
            let (Dof::U { col: c0, t: t0 }, Dof::U { col: c1, t: t1 }) =
                (dofs[r][o][0], dofs[r][o][1])
            else {
                continue;
            };
            let x = mesh.regions[r].local_positions[o];
            let far = contact
                .iter()
                .map(|p| (p[0] - x[0]).hypot(p[1] - x[1]))
                .fold(f64::INFINITY, f64::min);
            if !far.is_finite() {
                continue;
            }
            cand.push((r, o, x, far, [t0, t1], [c0, c1]));
        }
    }
    let score = |i: usize, j: usize| {
        let (a, b) = (&cand[i], &cand[j]);
        a.3 * b.3 * (b.2[0] - a.2[0]).hypot(b.2[1] - a.2[1])
    };
    let mut best = 0.0_f64;
    for i in 0..cand.len() {
        for j in i + 1..cand.len() {
            best = best.max(score(i, j));
        }
    }
    if !(best > 0.0 && best.is_finite()) {
        return None;
    }
    let (ia, ib) = (0..cand.len())
        .flat_map(|i| (i + 1..cand.len()).map(move |j| (i, j)))
        .find(|&(i, j)| score(i, j) >= (1.0 - 1e-9) * best)?;
    let (ra, oa, xa, _, ta, ca) = cand[ia];
    let (rb, ob, xb, _, tb, cb) = cand[ib];
    let len = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
    let s = [(xb[0] - xa[0]) / len, (xb[1] - xa[1]) / len];
    let nrm = [-s[1], s[0]];
    let frame = [nrm, s];
    let row_of = |frame: Option<[[f64; 2]; 2]>, d: usize, x: [f64; 2]| -> Vec<f64> {
        let rr = local_rigid_row(frame, d, x, center, size);
        modes.iter().map(|m| dot3(rr, *m)).collect()
    };
    let mut pins = Vec::new();
    for d in 0..2 {
        dofs[ra][oa][d] = Dof::T { col: ca[d], u: 0.0 };
        pins.push(Pin {
            region: ra,
            node: oa,
            d,
            t: ta[d],
            group: seg_group[mesh.regions[ra].nodes[oa].segment],
            row: row_of(None, d, xa),
            weight: node_weight(problem, ra, oa),
            frame: None,
        });
    }
    dofs[rb][ob][0] = Dof::T { col: cb[0], u: 0.0 };
    dofs[rb][ob][1] = Dof::U {
        col: cb[1],
        t: tb[0] * s[0] + tb[1] * s[1],
    };
    pins.push(Pin {
        region: rb,
        node: ob,
        d: 0,
        t: tb[0] * nrm[0] + tb[1] * nrm[1],
        group: seg_group[mesh.regions[rb].nodes[ob].segment],
        row: row_of(Some(frame), 0, xb),
        weight: node_weight(problem, rb, ob),
        frame: Some(frame),
    });
    Some(pins)
}

/// The supports by pivoting (bodies with one or two free modes, whose free modes are set by
/// displacement conditions along the global axes): for each free mode one traction-type
/// node component off the contact and rigid segments, along a global axis, chosen by
/// pivoting (see [`free_body`]).
fn pivoted_pins(
    search: &PinSearch<'_>,
    dofs: &mut [Vec<[Dof; 2]>],
    field: &str,
) -> Result<Vec<Pin>> {
    let PinSearch {
        problem,
        members,
        role,
        seg_group,
        contact,
        modes,
        center,
        size,
    } = *search;
    let mesh = &problem.mesh;
    let mut cand: Vec<PinCandidate> = Vec::new();
    for &r in members {
        for (o, node) in mesh.regions[r].nodes.iter().enumerate() {
            if role.contains_key(&node.segment) || mesh.segments[node.segment].partner.is_some() {
                continue;
            }
            for d in 0..2 {
                if let Dof::U { .. } = dofs[r][o][d] {
                    let x = mesh.regions[r].local_positions[o];
                    let rr = rigid_row(d, x, center, size);
                    let row: Vec<f64> = modes.iter().map(|m| dot3(rr, *m)).collect();
                    let far = contact
                        .iter()
                        .map(|p| (p[0] - x[0]).hypot(p[1] - x[1]))
                        .fold(f64::INFINITY, f64::min);
                    cand.push(PinCandidate {
                        region: r,
                        node: o,
                        d,
                        row,
                        far,
                    });
                }
            }
        }
    }
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut pins = Vec::new();
    for step in 0..modes.len() {
        let resid: Vec<Vec<f64>> = cand
            .iter()
            .map(|c| {
                let mut v = c.row.clone();
                for b in &basis {
                    let dt: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
                    v.iter_mut().zip(b).for_each(|(x, y)| *x -= dt * y);
                }
                v
            })
            .collect();
        let norms: Vec<f64> = resid
            .iter()
            .map(|v| v.iter().map(|x| x * x).sum::<f64>().sqrt())
            .collect();
        let best = norms.iter().cloned().fold(0.0_f64, f64::max);
        if best < 1e-6 {
            return Err(Error::invalid(
                field.to_string(),
                format!(
                    "free rigid-body {}",
                    describe_mode(
                        modes[step.min(modes.len() - 1)],
                        to_global(mesh, center),
                        size
                    )
                ),
                "the body is held only by contact, and it has no traction-loaded boundary node off \
                 its contact segments to carry the artificial support of this mode",
            ));
        }
        let mut pick = usize::MAX;
        for i in 0..cand.len() {
            if norms[i] >= 0.999 * best && (pick == usize::MAX || cand[i].far > cand[pick].far) {
                pick = i;
            }
        }
        basis.push(resid[pick].iter().map(|x| x / norms[pick]).collect());
        let PinCandidate {
            region: r,
            node: o,
            d,
            row,
            ..
        } = cand.swap_remove(pick);
        let (col, t) = match dofs[r][o][d] {
            Dof::U { col, t } => (col, t),
            _ => unreachable!("candidates are traction-type"),
        };
        dofs[r][o][d] = Dof::T { col, u: 0.0 };
        pins.push(Pin {
            region: r,
            node: o,
            d,
            t,
            group: seg_group[mesh.regions[r].nodes[o].segment],
            row,
            weight: node_weight(problem, r, o),
            frame: None,
        });
    }
    Ok(pins)
}

impl ContactProblem {
    /// A combination of free-mode amplitudes (unit vector over all free bodies' amplitudes)
    /// that the contact rows of the current sets do not hold, if any: the eigenvector of the
    /// smallest eigenvalue of M^T M, M = the amplitude columns of the gap rows of the nodes in
    /// contact and of the stick rows (f > 0), where its singular value is below 1e-8 (the
    /// entries are dimensionless, O(1): a translation moves every node by its amplitude).
    /// [`Error::Numerical`] where the eigendecomposition fails (non-finite weights).
    pub(super) fn unheld_mode(
        &self,
        states: &[ContactState],
        fric: &[f64],
    ) -> Result<Option<Vec<f64>>> {
        let Some(first) = self.free.first() else {
            return Ok(None);
        };
        let c0 = first.zcol;
        let nz = self.pz.ncols();
        let m = nz - c0;
        let mut gram = vec![vec![0.0; m]; m];
        let mut add = |row: &dyn Fn(usize) -> f64| {
            for a in 0..m {
                let ra = row(c0 + a);
                if ra == 0.0 {
                    continue;
                }
                for b in 0..m {
                    gram[a][b] += ra * row(c0 + b);
                }
            }
        };
        for (i, st) in states.iter().enumerate() {
            if matches!(st, ContactState::Open | ContactState::Outside) {
                continue;
            }
            add(&|c| self.wn[(i, c)]);
            if fric[i] > 0.0 && *st == ContactState::Stick {
                add(&|c| self.wt[(i, c)]);
            }
        }
        let (vals, vecs) = symmetric_eigen(&gram, "2D BEM contact: free-mode holding")?;
        let Some(k) = (0..m).min_by(|&a, &b| vals[a].total_cmp(&vals[b])) else {
            return Ok(None);
        };
        // Relative to the largest eigenvalue: the smallest of a rank-deficient Gram matrix
        // is round-off of the largest, whose scale is that of the weights (an absolute
        // threshold took a mode held by one node's normal and tangential rows together
        // with another as held, or not, by the rounding of the geometry).
        let largest = vals.iter().cloned().fold(0.0_f64, nan_max);
        if largest.is_nan() || largest <= 0.0 || vals[k].max(0.0).sqrt() < 1e-7 * largest.sqrt() {
            Ok(Some((0..m).map(|i| vecs[i][k]).collect()))
        } else {
            Ok(None)
        }
    }

    /// The free body and rigid motion that dominate amplitude combination `v`.
    pub(super) fn name_mode(&self, v: &[f64]) -> (&FreeBody, String) {
        let c0 = self.free[0].zcol;
        let mut best = (0.0, 0);
        for (f, fb) in self.free.iter().enumerate() {
            let a = fb.zcol - c0;
            let w: f64 = (0..fb.modes.len()).map(|k| v[a + k] * v[a + k]).sum();
            if w > best.0 {
                best = (w, f);
            }
        }
        let fb = &self.free[best.1];
        let a = fb.zcol - c0;
        let mut mode = [0.0; 3];
        for (k, m) in fb.modes.iter().enumerate() {
            for c in 0..3 {
                mode[c] += v[a + k] * m[c];
            }
        }
        let c = to_global(&self.problem.mesh, fb.center);
        (fb, describe_mode(mode, c, fb.size))
    }

    /// The least-squares rigid motion of each free body's boundary displacement and its
    /// support reactions.
    pub(super) fn free_results(
        &self,
        solution: &BemSolution,
        lamv: &[f64],
        pin_traction: &[Vec<f64>],
    ) -> Vec<FreeBodyResult> {
        let mesh = &self.problem.mesh;
        let (gx, gw) = gauss_legendre(8);
        let mut out = Vec::new();
        for (f, fb) in self.free.iter().enumerate() {
            let c = fb.center;
            let (mut len, mut ru2, mut rxu) = (0.0, 0.0, 0.0);
            let mut um = [0.0; 2];
            for &r in &fb.regions {
                for e in &mesh.regions[r].local_elements {
                    if mesh.segments[e.segment].partner.is_some() {
                        continue;
                    }
                    for (&xi, &w) in gx.iter().zip(&gw) {
                        let x = e.point(xi);
                        let (_, jac) = e.normal_jacobian(xi);
                        let nsh = e.field_shape(xi);
                        let mut u = [0.0; 2];
                        for a in 0..3 {
                            for d in 0..2 {
                                u[d] += nsh[a] * solution.displacement[r][e.nodes[a]][d];
                            }
                        }
                        let ds = w * jac;
                        let rv = [x[0] - c[0], x[1] - c[1]];
                        len += ds;
                        um[0] += u[0] * ds;
                        um[1] += u[1] * ds;
                        ru2 += (rv[0] * rv[0] + rv[1] * rv[1]) * ds;
                        rxu += (rv[0] * u[1] - rv[1] * u[0]) * ds;
                    }
                }
            }
            let mut support = [0.0; 2];
            for (q, pin) in fb.pins.iter().enumerate() {
                let reaction = pin.weight * (pin_traction[f][q] - lamv[pin.group] * pin.t);
                let dir = pin.direction();
                support[0] += reaction * dir[0];
                support[1] += reaction * dir[1];
            }
            out.push(FreeBodyResult {
                body: fb.name.clone(),
                translation: [um[0] / len, um[1] / len],
                rotation: rxu / ru2.max(f64::MIN_POSITIVE),
                reference_point: to_global(mesh, c),
                free_modes: fb
                    .modes
                    .iter()
                    .map(|m| describe_mode(*m, to_global(mesh, fb.center), fb.size))
                    .collect(),
                support_force: support,
            });
        }
        out
    }
}

/// Restraint: a body in no contact pair must be restrained by its displacement conditions
/// (an error otherwise); a body in a pair may leave rigid modes free, held by contact: its
/// free modes and artificial supports ([`free_body`]), the supports made displacement DOFs
/// in `dofs`.
pub(super) fn find_free_bodies(
    problem: &BemProblem,
    dofs: &mut [Vec<[Dof; 2]>],
    roles: &Roles,
    seg_group: &[usize],
) -> Result<Vec<FreeBody>> {
    let mesh = &problem.mesh;
    let mut in_pair = vec![false; mesh.regions.len()];
    for &(s, m) in &roles.pair_segs {
        in_pair[mesh.segments[s].owner] = true;
        in_pair[mesh.segments[m].owner] = true;
    }
    let mut free: Vec<FreeBody> = Vec::new();
    for members in problem.bodies() {
        if !members.iter().any(|&r| in_pair[r]) {
            problem.check_body_restraint(dofs, &members)?;
            continue;
        }
        if let Some(fb) = free_body(problem, dofs, &members, &roles.role, seg_group)? {
            free.push(fb);
        }
    }
    Ok(free)
}

/// Free-body equilibrium (a phase of [`ContactProblem::from_problem`]): for each free mode
/// r_k, the virtual work of the boundary tractions, sum_i (int N_i r_k ds) . t_i = 0, over
/// the prescribed tractions (the supports' included) and the contact tractions (the
/// parameters): the rows (eq_param, eq_ext) of the parameters and of the load groups.
pub(super) fn free_body_equilibrium(
    problem: &BemProblem,
    free: &[FreeBody],
    dofs: &[Vec<[Dof; 2]>],
    seg_group: &[usize],
    prm: &Params,
    next: usize,
) -> (Mat<f64>, Mat<f64>) {
    let mesh = &problem.mesh;
    let origin = mesh.origin;
    let (gx, gw) = gauss_legendre(8);
    let np = prm.params.len();
    let mtot: usize = free.iter().map(|fb| fb.modes.len()).sum();
    let mut eq_param = Mat::<f64>::zeros(mtot, np);
    let mut eq_ext = Mat::<f64>::zeros(mtot, next);
    let mut row0 = 0;
    for fb in free {
        for &r in &fb.regions {
            for e in &mesh.regions[r].local_elements {
                if mesh.segments[e.segment].partner.is_some() {
                    continue;
                }
                for (&xi, &w) in gx.iter().zip(&gw) {
                    let x = e.point(xi);
                    let (_, jac) = e.normal_jacobian(xi);
                    let nsh = e.field_shape(xi);
                    for a in 0..3 {
                        let o = e.nodes[a];
                        let frame = node_frame(free, r, o);
                        for d in 0..2 {
                            let rr = local_rigid_row(frame, d, x, fb.center, fb.size);
                            for (k, mode) in fb.modes.iter().enumerate() {
                                let wk = w * jac * nsh[a] * dot3(rr, *mode);
                                if let Some(&(f, q)) = prm.pin_of.get(&(r, o, d)) {
                                    let pin = &free[f].pins[q];
                                    eq_ext[(row0 + k, pin.group)] += wk * pin.t;
                                } else if let Some(&pk) = prm.param_of.get(&(r, o, d)) {
                                    eq_param[(row0 + k, pk)] += wk;
                                } else if let Dof::U { t, .. } = dofs[r][o][d] {
                                    let g = seg_group[self_segment(problem, r, o)];
                                    eq_ext[(row0 + k, g)] += wk * t;
                                }
                            }
                        }
                    }
                }
            }
        }
        // Body forces (ungrouped column 0): int_V b . r_k dV = -int_S t_p . r_k ds
        // (div sigma_p = -b and r_k a rigid mode: Gauss's theorem), over every region
        // boundary of the body, interfaces included (t_p jumps there).
        for &r in &fb.regions {
            let region = &mesh.regions[r];
            if region.body_force.is_none() {
                continue;
            }
            for e in &region.local_elements {
                for (&xi, &w) in gx.iter().zip(&gw) {
                    let x = e.point(xi);
                    let (n, jac) = e.normal_jacobian(xi);
                    let (_, sp) = region.particular_at([x[0] + origin[0], x[1] + origin[1]]);
                    let tp = [sp[0] * n[0] + sp[2] * n[1], sp[2] * n[0] + sp[1] * n[1]];
                    for d in 0..2 {
                        let rr = rigid_row(d, x, fb.center, fb.size);
                        for (k, mode) in fb.modes.iter().enumerate() {
                            eq_ext[(row0 + k, 0)] -= w * jac * tp[d] * dot3(rr, *mode);
                        }
                    }
                }
            }
        }
        row0 += fb.modes.len();
    }
    (eq_param, eq_ext)
}
