//! Pair geometry (projection of the slave nodes, initial gaps, the traction transfer) and
//! the element and node helpers it uses; see the module docs of [`super`].

use super::*;

/// The elements of segment `seg` in model-local coordinates (`RegionMesh::local_elements`:
/// the pair geometry, gaps and transfer are formed there, free of the rounding of large
/// absolute coordinates).
pub(super) fn seg_elements(problem: &BemProblem, seg: usize) -> Vec<Element> {
    let owner = problem.mesh.segments[seg].owner;
    problem.mesh.regions[owner]
        .local_elements
        .iter()
        .filter(|e| e.segment == seg)
        .copied()
        .collect()
}

/// Closest point of the master elements to `p`: (element index, xi), or None where the
/// closest point is an end of the segment and `p` lies beyond it.
pub(super) fn project(elements: &[Element], p: [f64; 2]) -> Option<(usize, f64)> {
    let mut best: Option<(f64, usize, f64)> = None;
    for (k, e) in elements.iter().enumerate() {
        let xi = nearest_xi(e, p);
        let f = e.point(xi);
        let d = (f[0] - p[0]).hypot(f[1] - p[1]);
        if best.is_none_or(|b| d < b.0) {
            best = Some((d, k, xi));
        }
    }
    let (_, k, xi) = best?;
    let last = elements.len() - 1;
    let at_end = (k == 0 && xi <= -1.0 + 1e-12) || (k == last && xi >= 1.0 - 1e-12);
    if at_end {
        let e = &elements[k];
        let f = e.point(xi);
        let t = e.tangent(xi);
        let tl = t[0].hypot(t[1]);
        let off = ((p[0] - f[0]) * t[0] + (p[1] - f[1]) * t[1]) / tl;
        if off.abs() > 1e-9 * e.chord_length() {
            return None;
        }
    }
    Some((k, xi))
}

/// The segment of node `node` of region `r`.
pub(super) fn self_segment(problem: &BemProblem, r: usize, node: usize) -> usize {
    problem.mesh.regions[r].nodes[node].segment
}

/// int N_k ds over the segment's elements, per segment node (owner order).
pub(super) fn node_weights(problem: &BemProblem, seg: usize) -> Vec<f64> {
    let info = &problem.mesh.segments[seg];
    let local: HashMap<usize, usize> = info
        .owner_nodes
        .iter()
        .enumerate()
        .map(|(k, &o)| (o, k))
        .collect();
    let (gx, gw) = gauss_legendre(8);
    let mut w = vec![0.0; info.owner_nodes.len()];
    for e in seg_elements(problem, seg) {
        for (&xi, &wq) in gx.iter().zip(&gw) {
            let (_, jac) = e.normal_jacobian(xi);
            let nsh = e.field_shape(xi);
            for a in 0..3 {
                w[local[&e.nodes[a]]] += wq * jac * nsh[a];
            }
        }
    }
    w
}

/// Validation of names and roles (the first phase of [`ContactProblem::from_problem`]):
/// every pair's slave and master and every rigid segment name a segment of the model that is
/// no bonded interface and has no other role, no boundary condition names one of them, and
/// the friction coefficients are finite and >= 0.
pub(super) fn claim_roles(
    mesh: &BemMesh,
    bcs: &BoundaryConditions,
    pairs: &[ContactPair],
    rigid: &[&str],
) -> Result<Roles> {
    let mut role: HashMap<usize, String> = HashMap::new();
    let mut claim = |name: &str, what: String, field: &str| -> Result<usize> {
        let s = mesh.segment_index(name).ok_or_else(|| {
            Error::invalid(field.to_string(), name, "names no segment of the model")
        })?;
        if mesh.segments[s].partner.is_some() {
            return Err(Error::invalid(
                field.to_string(),
                name,
                "is a bonded interface between regions; it cannot be a contact or rigid segment",
            ));
        }
        if let Some(prev) = role.get(&s) {
            return Err(Error::invalid(
                field.to_string(),
                name,
                format!("the segment is already used as {prev}"),
            ));
        }
        role.insert(s, what);
        Ok(s)
    };
    let mut pair_segs = Vec::new();
    for (k, p) in pairs.iter().enumerate() {
        let fname = format!("contact_pair[{k}]");
        if !(p.friction.is_finite() && p.friction >= 0.0) {
            return Err(Error::invalid(
                format!("{fname}.friction"),
                p.friction,
                "the friction coefficient must be finite and >= 0",
            ));
        }
        let s = claim(
            &p.slave,
            format!("the slave of contact pair {k}"),
            &format!("{fname}.slave"),
        )?;
        let m = claim(
            &p.master,
            format!("the master of contact pair {k}"),
            &format!("{fname}.master"),
        )?;
        pair_segs.push((s, m));
    }
    let mut rigid_segs = Vec::new();
    for (j, name) in rigid.iter().enumerate() {
        let s = claim(name, format!("rigid segment {j}"), "rigid_segment")?;
        rigid_segs.push((name.to_string(), s));
    }
    for (name, _, _) in &bcs.entries {
        if let Some(s) = mesh.segment_index(name) {
            if let Some(what) = role.get(&s) {
                return Err(Error::invalid(
                    "boundary_condition.segment",
                    name,
                    format!("is {what}; it takes no boundary condition"),
                ));
            }
        }
    }
    Ok(Roles {
        role,
        pair_segs,
        rigid_segs,
    })
}

/// Slave and master of every pair in different bodies (self-contact is not supported).
pub(super) fn check_pair_bodies(
    mesh: &BemMesh,
    pairs: &[ContactPair],
    pair_segs: &[(usize, usize)],
    body_of: &[usize],
) -> Result<()> {
    for (k, &(s, m)) in pair_segs.iter().enumerate() {
        if body_of[mesh.segments[s].owner] == body_of[mesh.segments[m].owner] {
            return Err(Error::invalid(
                format!("contact_pair[{k}]"),
                format!("'{}' / '{}'", pairs[k].slave, pairs[k].master),
                "slave and master belong to the same body (self-contact is not supported)",
            ));
        }
    }
    Ok(())
}

/// DOF classification: contact segments traction-type, rigid segments displacement-type
/// (both with zero values; their values are parameters). Returns the DOFs of every region
/// node and the number of columns.
pub(super) fn classify_dofs(
    problem: &BemProblem,
    bcs: &BoundaryConditions,
    roles: &Roles,
) -> Result<(Vec<Vec<[Dof; 2]>>, usize)> {
    let mesh = &problem.mesh;
    let mut full = bcs.clone();
    for &(s, m) in &roles.pair_segs {
        full = full
            .set(&mesh.segments[s].name, SegmentBc::Free)
            .set(&mesh.segments[m].name, SegmentBc::Free);
    }
    for (name, _) in &roles.rigid_segs {
        full = full.set(name, SegmentBc::fixed());
    }
    problem.dofs(&full)
}

/// Load groups: column 0 ungrouped, 1 + g for named group g. Returns the named groups (in
/// the order of their first use) and the column of every segment.
pub(super) fn load_groups(
    mesh: &BemMesh,
    bcs: &BoundaryConditions,
) -> Result<(Vec<String>, Vec<usize>)> {
    let groups = bcs.groups();
    let mut seg_group = vec![0; mesh.segments.len()];
    for (name, _, g) in &bcs.entries {
        if let Some(g) = g {
            if g.trim().is_empty() {
                return Err(Error::invalid(
                    format!("boundary_condition '{name}'.group"),
                    "\"\"",
                    "a load group name must not be empty",
                ));
            }
            if let Some(s) = mesh.segment_index(name) {
                seg_group[s] = 1 + groups.iter().position(|x| x == g).unwrap_or(0);
            }
        }
    }
    Ok((groups, seg_group))
}

/// The model's stress scale (the largest shear modulus, Pa) and length scale (the larger
/// side of the nodes' bounding box, m).
pub(super) fn model_scales(mesh: &BemMesh) -> (f64, f64) {
    let scale = mesh
        .regions
        .iter()
        .map(|r| r.kernels.shear_modulus())
        .fold(0.0_f64, f64::max);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for r in &mesh.regions {
        for x in &r.local_positions {
            for d in 0..2 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
    }
    let length = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    (scale, length)
}

/// Pair geometry (a phase of [`ContactProblem::from_problem`]): per pair the slave nodes'
/// projections and initial gaps and the traction transfer ([`pair_data`]), the pairs' nodes
/// numbered in order.
pub(super) fn pair_geometry(
    problem: &BemProblem,
    pairs: &[ContactPair],
    pair_segs: &[(usize, usize)],
) -> Result<Vec<PairData>> {
    let mut pdata: Vec<PairData> = Vec::new();
    let mut offset = 0;
    for (k, &(s, m)) in pair_segs.iter().enumerate() {
        let p = pair_data(problem, k, &pairs[k], s, m, offset)?;
        offset += p.nodes.len();
        pdata.push(p);
    }
    Ok(pdata)
}

/// Segment-local numbering of a segment's nodes (owner order).
fn local_index(owner_nodes: &[usize]) -> HashMap<usize, usize> {
    owner_nodes
        .iter()
        .enumerate()
        .map(|(a, &o)| (o, a))
        .collect()
}

/// The geometry of pair `k` (slave segment `s`, master `m`), its nodes numbered from
/// `offset`: projection and initial gaps ([`slave_nodes`]), the transfer integrals
/// ([`SlaveTransfer`]), the weighted gap rule, the master projection ([`master_projection`]).
fn pair_data(
    problem: &BemProblem,
    k: usize,
    pair: &ContactPair,
    s: usize,
    m: usize,
    offset: usize,
) -> Result<PairData> {
    let mesh = &problem.mesh;
    let (sseg, mseg) = (&mesh.segments[s], &mesh.segments[m]);
    let selems = seg_elements(problem, s);
    let melems = seg_elements(problem, m);
    let m_local = local_index(&mseg.owner_nodes);
    let s_local = local_index(&sseg.owner_nodes);
    let mut nodes = slave_nodes(problem, k, pair, s, &melems, &m_local)?;
    // Transfer: D (master x slave) on the slave elements, M on the master elements.
    let (nm, ns) = (mseg.owner_nodes.len(), sseg.owner_nodes.len());
    let tr = SlaveTransfer::new(&selems, &melems, &s_local, &m_local, nm, ns);
    if pair.rule == GapRule::Weighted {
        tr.apply_weighted_rule(k, pair, &mut nodes)?;
    }
    let (proj, master_weights) = master_projection(k, &melems, &m_local, &tr.dmat)?;
    Ok(PairData {
        pair: pair.clone(),
        slave_seg: s,
        master_seg: m,
        offset,
        nodes,
        proj,
        slave_weights: tr.slave_weights,
        dmat: tr.dmat,
        smass: tr.smass,
        master_weights,
    })
}

/// The slave nodes of pair `k` (slave segment `s`) projected onto the master elements:
/// foot point, master normal and tangent, initial gap (model-local coordinates). Errors:
/// initial penetration beyond 1e-6 of the slave's smallest element; no node projects.
fn slave_nodes(
    problem: &BemProblem,
    k: usize,
    pair: &ContactPair,
    s: usize,
    melems: &[Element],
    m_local: &HashMap<usize, usize>,
) -> Result<Vec<SlaveNode>> {
    let mesh = &problem.mesh;
    let sseg = &mesh.segments[s];
    let sregion = &mesh.regions[sseg.owner];
    let hmin = seg_elements(problem, s)
        .iter()
        .map(|e| e.chord_length())
        .fold(f64::INFINITY, f64::min);

    let mut nodes = Vec::new();
    let mut any = false;
    for &o in &sseg.owner_nodes {
        let node = &sregion.nodes[o];
        // Model-local position for the geometry; the global one for the results.
        let x = sregion.local_positions[o];
        let mut sn = SlaveNode {
            region_node: o,
            position: node.position,
            param: node.param,
            normal: [0.0, 0.0],
            tangent: [0.0, 0.0],
            gap0: f64::INFINITY,
            master: None,
        };
        if let Some((ke, xi)) = project(melems, x) {
            let e = &melems[ke];
            let f = e.point(xi);
            let (n, _) = e.normal_jacobian(xi);
            let g0 = (x[0] - f[0]) * n[0] + (x[1] - f[1]) * n[1];
            if g0 < -1e-6 * hmin {
                return Err(Error::invalid(
                    format!("contact_pair[{k}]"),
                    format!(
                        "initial gap {g0:.3e} m at ({:.6e}, {:.6e})",
                        node.position[0], node.position[1]
                    ),
                    "the bodies overlap: a slave node lies inside the master body \
                     (initial penetration beyond 1e-6 of the slave's smallest element)",
                ));
            }
            sn.normal = n;
            sn.tangent = [-n[1], n[0]];
            sn.gap0 = g0;
            sn.master = Some((e.nodes.map(|q| m_local[&q]), e.field_shape(xi)));
            any = true;
        }
        nodes.push(sn);
    }
    if !any {
        return Err(Error::invalid(
            format!("contact_pair[{k}]"),
            format!("'{}' / '{}'", pair.slave, pair.master),
            "no slave node projects onto the master segment",
        ));
    }
    Ok(nodes)
}

/// The transfer integrals of a pair on the slave elements (covered part): D = int
/// N_m(foot(x)) N_s(x)^T ds (master x slave), the slave mass, the slave force weights over
/// the covered part and over the whole segment, and the weighted initial gaps.
struct SlaveTransfer {
    dmat: Mat<f64>,
    smass: Mat<f64>,
    slave_weights: Vec<f64>,
    full_weights: Vec<f64>,
    weighted_gap: Vec<f64>,
}

impl SlaveTransfer {
    fn new(
        selems: &[Element],
        melems: &[Element],
        s_local: &HashMap<usize, usize>,
        m_local: &HashMap<usize, usize>,
        nm: usize,
        ns: usize,
    ) -> Self {
        let (gx, gw) = gauss_legendre(8);
        let mut dmat = Mat::<f64>::zeros(nm, ns);
        let mut smass = Mat::<f64>::zeros(ns, ns);
        let mut slave_weights = vec![0.0; ns];
        let mut full_weights = vec![0.0; ns];
        let mut weighted_gap = vec![0.0; ns];

        for e in selems {
            // Split the slave element where master element ends project onto it: the
            // master shape functions have kinks there, which Gauss rules integrate
            // poorly (measured: 4 % pressure spikes on the Hertz case without the split).
            let mut cuts = vec![-1.0, 1.0];
            for em in melems {
                for q in [em.geometry[0], em.geometry[2]] {
                    let xi = nearest_xi(e, q);
                    let f = e.point(xi);
                    if xi > -1.0 + 1e-9
                        && xi < 1.0 - 1e-9
                        && (f[0] - q[0]).hypot(f[1] - q[1]) < e.chord_length()
                    {
                        cuts.push(xi);
                    }
                }
            }
            cuts.sort_by(f64::total_cmp);
            cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
            let points: Vec<(f64, f64)> = cuts
                .windows(2)
                .flat_map(|c| {
                    let (lo, hi) = (c[0], c[1]);
                    gx.iter().zip(&gw).map(move |(&t, &w)| {
                        (0.5 * (lo + hi) + 0.5 * (hi - lo) * t, 0.5 * (hi - lo) * w)
                    })
                })
                .collect();
            for (xi, w) in points {
                let x = e.point(xi);
                let (_, jac) = e.normal_jacobian(xi);
                let nsh = e.field_shape(xi);
                for b in 0..3 {
                    full_weights[s_local[&e.nodes[b]]] += w * jac * nsh[b];
                }
                if let Some((ke, xm)) = project(melems, x) {
                    let em = &melems[ke];
                    let nmsh = em.field_shape(xm);
                    let f = em.point(xm);
                    let (nn, _) = em.normal_jacobian(xm);
                    let g0 = (x[0] - f[0]) * nn[0] + (x[1] - f[1]) * nn[1];
                    for b in 0..3 {
                        let bl = s_local[&e.nodes[b]];
                        slave_weights[bl] += w * jac * nsh[b];
                        weighted_gap[bl] += w * jac * nsh[b] * g0;
                        for a in 0..3 {
                            let al = m_local[&em.nodes[a]];
                            dmat[(al, bl)] += w * jac * nmsh[a] * nsh[b];
                        }
                        for c in 0..3 {
                            let cl = s_local[&e.nodes[c]];
                            smass[(bl, cl)] += w * jac * nsh[b] * nsh[c];
                        }
                    }
                }
            }
        }
        SlaveTransfer {
            dmat,
            smass,
            slave_weights,
            full_weights,
            weighted_gap,
        }
    }

    /// [`GapRule::Weighted`]: the gap of a node is its initial gap weighted with its shape
    /// function; only nodes whose whole support is covered by the master take part.
    fn apply_weighted_rule(
        &self,
        k: usize,
        pair: &ContactPair,
        nodes: &mut [SlaveNode],
    ) -> Result<()> {
        // Only nodes whose whole support is covered by the master take part.
        for (b, sn) in nodes.iter_mut().enumerate() {
            let full = self.full_weights[b];
            if sn.master.is_some() && full > 0.0 && self.slave_weights[b] >= (1.0 - 1e-9) * full {
                sn.gap0 = self.weighted_gap[b] / self.slave_weights[b];
            } else {
                sn.master = None;
                sn.gap0 = f64::INFINITY;
            }
        }
        if nodes.iter().all(|sn| sn.master.is_none()) {
            return Err(Error::invalid(
                format!("contact_pair[{k}]"),
                format!("'{}' / '{}'", pair.slave, pair.master),
                "no slave node's support lies on the master segment",
            ));
        }
        Ok(())
    }
}

/// The L2 projection of the slave traction onto the master's traction space, M_m^{-1} D
/// (master x slave), and the master force weights int N_a ds.
fn master_projection(
    k: usize,
    melems: &[Element],
    m_local: &HashMap<usize, usize>,
    dmat: &Mat<f64>,
) -> Result<(Mat<f64>, Vec<f64>)> {
    let (gx, gw) = gauss_legendre(8);
    let (nm, ns) = (dmat.nrows(), dmat.ncols());

    let mut mass = Mat::<f64>::zeros(nm, nm);
    let mut master_weights = vec![0.0; nm];
    for e in melems {
        for (&xi, &w) in gx.iter().zip(&gw) {
            let (_, jac) = e.normal_jacobian(xi);
            let nsh = e.field_shape(xi);
            for a in 0..3 {
                let al = m_local[&e.nodes[a]];
                master_weights[al] += w * jac * nsh[a];
                for b in 0..3 {
                    let bl = m_local[&e.nodes[b]];
                    mass[(al, bl)] += w * jac * nsh[a] * nsh[b];
                }
            }
        }
    }
    let proj = mass.partial_piv_lu().solve(dmat);
    if (0..nm).any(|a| (0..ns).any(|b| !proj[(a, b)].is_finite())) {
        return Err(Error::Numerical {
            context: "2D BEM contact",
            detail: format!(
                "the traction transfer of contact pair {k} is singular (master mass matrix)"
            ),
        });
    }
    Ok((proj, master_weights))
}

/// The body parameters (contact tractions per node component of the pairs' segments, rigid
/// translations, free-mode amplitudes), and the map z -> parameters (a phase of
/// [`ContactProblem::from_problem`]). Sets each free body's first parameter index.
pub(super) fn parameters(
    mesh: &BemMesh,
    pdata: &[PairData],
    nrig: usize,
    free: &mut [FreeBody],
    n: usize,
    nz: usize,
) -> Params {
    let mut params: Vec<Param> = Vec::new();
    let mut param_of: HashMap<(usize, usize, usize), usize> = HashMap::new();
    let mut add_seg = |seg: usize, params: &mut Vec<Param>| {
        let info = &mesh.segments[seg];
        for &o in &info.owner_nodes {
            for d in 0..2 {
                param_of.insert((info.owner, o, d), params.len());
                params.push(Param::Traction {
                    region: info.owner,
                    node: o,
                    d,
                });
            }
        }
    };
    for p in pdata {
        add_seg(p.slave_seg, &mut params);
        add_seg(p.master_seg, &mut params);
    }
    let rigid_base = params.len();
    for j in 0..nrig / 2 {
        for d in 0..2 {
            params.push(Param::Rigid { j, d });
        }
    }
    for (f, fb) in free.iter_mut().enumerate() {
        fb.param0 = params.len();
        for _ in 0..fb.modes.len() {
            params.push(Param::Free { f });
        }
    }
    let mut pin_of: HashMap<(usize, usize, usize), (usize, usize)> = HashMap::new();
    for (f, fb) in free.iter().enumerate() {
        for (q, pin) in fb.pins.iter().enumerate() {
            pin_of.insert((pin.region, pin.node, pin.d), (f, q));
        }
    }
    let np = params.len();
    let mut pz = Mat::<f64>::zeros(np, nz);
    for p in pdata {
        let sinfo = &mesh.segments[p.slave_seg];
        let minfo = &mesh.segments[p.master_seg];
        for (b, sn) in p.nodes.iter().enumerate() {
            let i = p.offset + b;
            for d in 0..2 {
                let row = param_of[&(sinfo.owner, sn.region_node, d)];
                pz[(row, i)] = sn.normal[d];
                pz[(row, n + i)] = sn.tangent[d];
                for (a, &o) in minfo.owner_nodes.iter().enumerate() {
                    let w = p.proj[(a, b)];
                    if w != 0.0 {
                        let mrow = param_of[&(minfo.owner, o, d)];
                        pz[(mrow, i)] -= w * sn.normal[d];
                        pz[(mrow, n + i)] -= w * sn.tangent[d];
                    }
                }
            }
        }
    }
    for j in 0..nrig {
        pz[(rigid_base + j, 2 * n + j)] = 1.0;
    }
    for fb in free.iter() {
        for k in 0..fb.modes.len() {
            pz[(fb.param0 + k, fb.zcol + k)] = 1.0;
        }
    }
    Params {
        params,
        param_of,
        pin_of,
        rigid_base,
        pz,
    }
}

/// The largest prescribed traction of each load group at factor 1 (a prescribed displacement
/// counted as shear modulus * u / model size, `scales` = (shear modulus, size) of
/// [`model_scales`]), Pa: the load scale of a step.
pub(super) fn group_loads(
    mesh: &BemMesh,
    dofs: &[Vec<[Dof; 2]>],
    roles: &Roles,
    seg_group: &[usize],
    free: &[FreeBody],
    next: usize,
    scales: (f64, f64),
) -> Vec<f64> {
    let (scale, length) = scales;
    let mut group_load = vec![0.0_f64; next];
    for (r, region) in mesh.regions.iter().enumerate() {
        for (o, node) in region.nodes.iter().enumerate() {
            if roles.role.contains_key(&node.segment) {
                continue;
            }
            let g = seg_group[node.segment];
            for d in 0..2 {
                let v = match dofs[r][o][d] {
                    Dof::U { t, .. } => t.abs(),
                    Dof::T { u, .. } => scale * u.abs() / length,
                    Dof::Interface { .. } => 0.0,
                };
                group_load[g] = group_load[g].max(v);
            }
        }
    }
    for fb in free {
        for pin in &fb.pins {
            group_load[pin.group] = group_load[pin.group].max(pin.t.abs());
        }
    }
    group_load
}
