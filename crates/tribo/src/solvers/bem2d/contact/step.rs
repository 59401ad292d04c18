//! Load steps: the primal-dual active set solver and the results; see "Solver" in the
//! module docs of [`super`].

use super::*;

impl ContactProblem {
    /// Solves the load steps in order, continuing from the state left by earlier calls
    /// (use [`ContactProblem::reset`] to start again from the unloaded state).
    ///
    /// Errors: a step that misses or repeats a rigid segment, or names an unknown one, or a
    /// non-finite load, or names an unknown load group or one twice
    /// ([`Error::InvalidParameter`]); a free rigid-body mode that neither contact nor
    /// friction holds ([`Error::InvalidParameter`] naming the body and the mode); a free
    /// body whose loads do not press it onto a contact ([`Error::NoContact`]); [`Error::NotConverged`] with the
    /// complementarity residual when the active sets cycle or the iteration limit is
    /// reached; [`Error::NoContact`] when no node is in contact and a force-controlled body
    /// floats; [`Error::Numerical`] for a singular step system (a rigid-body mode that
    /// neither contact, friction nor a displacement control restrains);
    /// [`Error::ContactReachesWindow`] when the contact reaches a slave node whose
    /// projection misses the master segment.
    pub fn solve_steps(
        &mut self,
        steps: &[LoadStep],
        options: &ContactOptions,
    ) -> Result<Vec<ContactStepResult>> {
        if options.max_iterations == 0 {
            return Err(Error::invalid(
                "contact_options.max_iterations",
                0,
                "must be at least 1",
            ));
        }
        if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
            return Err(Error::invalid(
                "contact_options.tolerance",
                options.tolerance,
                "must be finite and > 0",
            ));
        }
        let mut out = Vec::with_capacity(steps.len());
        for (k, step) in steps.iter().enumerate() {
            out.push(self.solve_step(k, step, options)?);
        }
        Ok(out)
    }

    /// The rigid controls of a step and its load factors per load-group column.
    pub(super) fn controls(&self, k: usize, step: &LoadStep) -> Result<(Vec<Control>, Vec<f64>)> {
        let field = format!("load_step[{k}]");
        if !step.external.is_finite() {
            return Err(Error::invalid(
                format!("{field}.external"),
                step.external,
                "must be finite",
            ));
        }
        let mut lamv = vec![0.0; self.next()];
        lamv[0] = step.external;
        let mut seen = vec![false; self.groups.len()];
        for (name, f) in &step.groups {
            let g = self.groups.iter().position(|x| x == name).ok_or_else(|| {
                Error::invalid(
                    format!("{field}.groups"),
                    name,
                    format!(
                        "names no load group of the boundary conditions (groups: [{}])",
                        self.groups.join(", ")
                    ),
                )
            })?;
            if seen[g] {
                return Err(Error::invalid(
                    format!("{field}.groups"),
                    name,
                    "is given twice in the step",
                ));
            }
            if !f.is_finite() {
                return Err(Error::invalid(
                    format!("{field}.groups '{name}'"),
                    f,
                    "the factor must be finite",
                ));
            }
            seen[g] = true;
            lamv[1 + g] = *f;
        }
        let mut ctl: Vec<Option<Control>> = vec![None; 2 * self.rigid.len()];
        for rc in &step.rigid {
            let j = self
                .rigid
                .iter()
                .position(|(name, _)| *name == rc.segment)
                .ok_or_else(|| {
                    Error::invalid(
                        format!("{field}.rigid"),
                        &rc.segment,
                        "is not a rigid segment of the contact problem",
                    )
                })?;
            if ctl[2 * j].is_some() {
                return Err(Error::invalid(
                    format!("{field}.rigid"),
                    &rc.segment,
                    "is controlled twice in the step",
                ));
            }
            for (d, c) in [rc.x, rc.y].into_iter().enumerate() {
                let v = match c {
                    Control::Force(v) | Control::Displacement(v) => v,
                };
                if !v.is_finite() {
                    return Err(Error::invalid(
                        format!("{field}.rigid '{}'", rc.segment),
                        v,
                        "the load must be finite",
                    ));
                }
                ctl[2 * j + d] = Some(c);
            }
        }
        let ctl = ctl
            .into_iter()
            .enumerate()
            .map(|(i, c)| {
                c.ok_or_else(|| {
                    Error::invalid(
                        format!("{field}.rigid"),
                        &self.rigid[i / 2].0,
                        "every rigid segment needs a control in every step",
                    )
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok((ctl, lamv))
    }

    pub(super) fn friction_of(&self) -> Vec<f64> {
        let mut f = vec![0.0; self.n];
        for p in &self.pairs {
            for b in 0..p.nodes.len() {
                f[p.offset + b] = p.pair.friction;
            }
        }
        f
    }

    /// One load step (see "Solver" in the module docs): the primal-dual active set
    /// iteration, then the results ([`Self::pair_results`], [`Self::rigid_results`], the
    /// boundary state and the free bodies' motion).
    ///
    /// Longer than 150 lines on purpose: the iteration is one loop whose state (the sets,
    /// z, the history of sets for cycle detection, the single-change fallback, the holding
    /// of free modes, the complementarity residual) every branch reads and updates; split
    /// into functions it would pass most of that state to each, hiding the control flow
    /// that the loop shows in one place.
    pub(super) fn solve_step(
        &mut self,
        k: usize,
        step: &LoadStep,
        options: &ContactOptions,
    ) -> Result<ContactStepResult> {
        let (ctl, lamv) = self.controls(k, step)?;
        let n = self.n;
        let nz = self.pz.ncols();
        let nrig = 2 * self.rigid.len();
        let next = self.next();
        let ext = |m: &Mat<f64>, i: usize| -> f64 { (0..next).map(|g| lamv[g] * m[(i, g)]).sum() };
        let gl: Vec<f64> = (0..n).map(|i| ext(&self.gn_ext, i)).collect();
        let sl: Vec<f64> = (0..n).map(|i| ext(&self.st_ext, i)).collect();
        let fric = self.friction_of();
        // The step's load scale (Pa): prescribed tractions, displacements and rigid controls.
        let mut load_scale = (0..next)
            .map(|g| lamv[g].abs() * self.group_load[g])
            .fold(0.0_f64, f64::max);
        for c in &ctl {
            load_scale = load_scale.max(match *c {
                Control::Force(f) => f.abs() / self.length,
                Control::Displacement(u) => self.scale * u.abs() / self.length,
            });
        }
        let g0: Vec<f64> = self
            .pairs
            .iter()
            .flat_map(|p| p.nodes.iter().map(|s| s.gap0))
            .collect();
        let cn: Vec<f64> = (0..n)
            .map(|i| 1.0 / self.wn[(i, i)].abs().max(1e-300))
            .collect();
        let ct: Vec<f64> = (0..n)
            .map(|i| 1.0 / self.wt[(i, n + i)].abs().max(1e-300))
            .collect();
        // Column scales: tractions by the shear modulus, translations by the model size.
        let colscale: Vec<f64> = (0..nz)
            .map(|c| if c < 2 * n { self.scale } else { self.length })
            .collect();
        let mut states = self.states.clone();
        let mut history: Vec<Vec<ContactState>> = Vec::new();
        let mut single = false;
        let mut z = vec![0.0; nz];
        let mut residual;
        let mut iterations = 0;
        let evaluate = |z: &[f64]| -> (Vec<f64>, Vec<f64>) {
            let mut g = vec![0.0; n];
            let mut s = vec![0.0; n];
            for i in 0..n {
                let (mut a, mut b) = (g0[i] + gl[i], sl[i]);
                for c in 0..nz {
                    a += self.wn[(i, c)] * z[c];
                    b += self.wt[(i, c)] * z[c];
                }
                g[i] = a;
                s[i] = b;
            }
            (g, s)
        };
        loop {
            iterations += 1;
            // A body held only by contact: while the sets leave one of its free modes unheld,
            // bring the open node that would hold it with the smallest gap into contact. If
            // none can, the mode is held by neither contact nor friction: a clear error.
            if !self.free.is_empty() {
                let mut checked = false;
                while let Some(v) = self.unheld_mode(&states, &fric)? {
                    let c0 = self.free[0].zcol;
                    let (g, _) = evaluate(&z);
                    let weight = |i: usize, w: &Mat<f64>| -> f64 {
                        (0..v.len()).map(|a| w[(i, c0 + a)] * v[a]).sum::<f64>()
                    };
                    if !checked && iterations > 1 {
                        // The last solve left no contact node of the body with a pressure
                        // above round-off of the step's loads: its loads do not press it onto
                        // a contact (or vanish).
                        let (fb, _) = self.name_mode(&v);
                        let touching = (0..n).any(|i| {
                            !matches!(states[i], ContactState::Open | ContactState::Outside)
                                && load_scale > 0.0
                                && z[i] > 1e-9 * load_scale
                                && (0..fb.modes.len())
                                    .any(|a| self.wn[(i, fb.zcol + a)].abs() > 1e-6)
                        });
                        if !touching {
                            let (fb, mode) = self.name_mode(&v);
                            return Err(Error::NoContact {
                                detail: format!(
                                    "load step {k}: {} is held only by contact and friction \
                                     (free rigid-body {mode}), but its loads do not press it \
                                     onto a contact: every contact node opens",
                                    fb.field
                                ),
                            });
                        }
                    }
                    checked = true;
                    let mut best: Option<(f64, usize)> = None;
                    for i in 0..n {
                        if states[i] != ContactState::Open {
                            continue;
                        }
                        let hold = weight(i, &self.wn).abs().max(if fric[i] > 0.0 {
                            weight(i, &self.wt).abs()
                        } else {
                            0.0
                        });
                        if hold > 1e-6 && best.is_none_or(|b| g[i] < b.0) {
                            best = Some((g[i], i));
                        }
                    }
                    match best {
                        Some((_, i)) => states[i] = ContactState::Stick,
                        None => {
                            let (fb, mode) = self.name_mode(&v);
                            return Err(Error::invalid(
                                fb.field.clone(),
                                format!("free rigid-body {mode}"),
                                format!(
                                    "in load step {k} neither contact nor friction holds this \
                                     mode of a body held only by contact (a frictionless contact \
                                     holds no tangential motion; with friction, every contact \
                                     node slips: the tangential load reaches the friction limit): \
                                     add friction, a symmetry or displacement condition, or a \
                                     rigid segment, or reduce the tangential load"
                                ),
                            ));
                        }
                    }
                }
            }
            // Build the linear system of the current sets.
            let mut a = Mat::<f64>::zeros(nz, nz);
            let mut rhs = vec![0.0; nz];
            let mut any_active = false;
            for i in 0..n {
                match states[i] {
                    ContactState::Outside | ContactState::Open => {
                        a[(i, i)] = 1.0;
                        a[(n + i, n + i)] = 1.0;
                    }
                    st => {
                        any_active = true;
                        for c in 0..nz {
                            a[(i, c)] = self.wn[(i, c)];
                        }
                        rhs[i] = -(g0[i] + gl[i]);
                        if fric[i] == 0.0 {
                            a[(n + i, n + i)] = 1.0;
                        } else if st == ContactState::Stick {
                            for c in 0..nz {
                                a[(n + i, c)] = self.wt[(i, c)];
                            }
                            rhs[n + i] = self.slip[i] - sl[i];
                        } else {
                            let sigma = if st == ContactState::SlipPositive {
                                -1.0
                            } else {
                                1.0
                            };
                            // q = sigma f p (slip along +tau: friction along -tau).
                            a[(n + i, n + i)] = 1.0;
                            a[(n + i, i)] = -sigma * fric[i];
                        }
                    }
                }
            }
            for (j, c) in ctl.iter().enumerate() {
                let row = 2 * n + j;
                match *c {
                    Control::Force(f) => {
                        for cc in 0..nz {
                            a[(row, cc)] = self.kf[(j, cc)];
                        }
                        rhs[row] = f - ext(&self.f_ext, j);
                    }
                    Control::Displacement(u) => {
                        a[(row, row)] = 1.0;
                        rhs[row] = u;
                    }
                }
            }
            // Free-body equilibrium in every free mode.
            for q in 0..self.eq_z.nrows() {
                let row = 2 * n + nrig + q;
                for cc in 0..nz {
                    a[(row, cc)] = self.eq_z[(q, cc)];
                }
                rhs[row] = -ext(&self.eq_ext, q);
            }
            // Open and outside nodes have p = q = 0: only the unknowns of contact nodes and the
            // rigid translations enter the solve. Equilibrate: columns by the unknowns'
            // scales, rows by their largest entry.
            let act: Vec<usize> = (0..nz)
                .filter(|&c| {
                    c >= 2 * n
                        || !matches!(states[c % n], ContactState::Open | ContactState::Outside)
                })
                .collect();
            let m = act.len();
            let mut am = Mat::<f64>::zeros(m, m);
            let mut bm = Mat::<f64>::zeros(m, 1);
            for (r, &ra) in act.iter().enumerate() {
                let mut rmax = 0.0_f64;
                for &c in &act {
                    rmax = rmax.max((a[(ra, c)] * colscale[c]).abs());
                }
                let rs = if rmax > 0.0 { 1.0 / rmax } else { 1.0 };
                for (cc, &c) in act.iter().enumerate() {
                    am[(r, cc)] = a[(ra, c)] * colscale[c] * rs;
                }
                bm[(r, 0)] = rhs[ra] * rs;
            }
            let y = am.partial_piv_lu().solve(&bm);
            let chk = &am * &y - &bm;
            let mut bad = false;
            let (mut rn, mut yn) = (0.0_f64, 0.0_f64);
            for r in 0..m {
                if !y[(r, 0)].is_finite() {
                    bad = true;
                }
                rn = nan_max(rn, chk[(r, 0)].abs());
                yn = nan_max(yn, y[(r, 0)].abs());
            }
            if bad || rn.is_nan() || rn > 1e-8 * (yn + 1.0) {
                if !any_active {
                    return Err(Error::NoContact {
                        detail: format!(
                            "load step {k}: no slave node is in contact and a force-controlled \
                             body is left floating"
                        ),
                    });
                }
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: the contact system is singular (residual {rn:.3e}): a \
                         rigid-body mode is restrained by neither contact, friction nor a \
                         displacement control (e.g. a force-controlled tangential load on a \
                         frictionless pair)"
                    ),
                });
            }
            z.iter_mut().for_each(|v| *v = 0.0);
            for (r, &c) in act.iter().enumerate() {
                z[c] = y[(r, 0)] * colscale[c];
            }
            if let Some(fb) = self
                .free
                .iter()
                .find(|fb| (0..fb.modes.len()).any(|k| z[fb.zcol + k].abs() > self.length))
            {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: {} (held only by contact) moves more than the model \
                         size: a free rigid-body mode is held by neither contact nor friction",
                        fb.field
                    ),
                });
            }
            if let Some(j) = (0..nrig).find(|&j| z[2 * n + j].abs() > self.length) {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}: rigid segment '{}' moves {:.3e} m, more than the model \
                         size: a rigid-body mode is restrained by neither contact, friction nor a \
                         displacement control (e.g. a force-controlled tangential load on a \
                         frictionless pair); the step system is singular up to discretization error",
                        self.rigid[j / 2].0,
                        z[2 * n + j]
                    ),
                });
            }
            let (g, s) = evaluate(&z);
            // New sets and the complementarity residual.
            let mut new_states = states.clone();
            let mut rmax = 0.0_f64;
            let pmax = (0..n).map(|i| z[i]).fold(0.0_f64, nan_max);
            for i in 0..n {
                if states[i] == ContactState::Outside {
                    continue;
                }
                let (p, q) = (z[i], z[n + i]);
                let ds = s[i] - self.slip[i];
                let pn = p - cn[i] * g[i];
                let qt = q - ct[i] * ds;
                let bound = fric[i] * pn.max(0.0);
                let r = if pn.is_nan() || qt.is_nan() || bound.is_nan() {
                    f64::NAN
                } else {
                    (p - pn.max(0.0))
                        .abs()
                        .max((q - qt.clamp(-bound, bound)).abs())
                };
                rmax = nan_max(rmax, r);
                new_states[i] = if pn <= 0.0 {
                    ContactState::Open
                } else if fric[i] == 0.0 || qt.abs() <= bound {
                    ContactState::Stick
                } else if qt < 0.0 {
                    ContactState::SlipPositive
                } else {
                    ContactState::SlipNegative
                };
            }
            residual = rmax / nan_max(pmax, f64::MIN_POSITIVE);
            if pmax == 0.0 {
                residual = rmax;
            }
            if !residual.is_finite() {
                return Err(Error::Numerical {
                    context: "2D BEM contact step",
                    detail: format!(
                        "load step {k}, iteration {iterations}: the complementarity residual is \
                         {residual} (a non-finite contact pressure, shear, gap or slip)"
                    ),
                });
            }
            if new_states == states && residual <= options.tolerance {
                break;
            }
            let cycled = history.contains(&new_states);
            if iterations >= options.max_iterations || (cycled && single) {
                return Err(Error::NotConverged {
                    solver: "2D BEM frictional contact (active set)",
                    iterations,
                    residual,
                    tolerance: options.tolerance,
                });
            }
            if cycled {
                // Cycling guard: from now on change one node per iteration, the first that
                // violates its conditions (Murty's least-index rule, finite for P-matrix
                // LCPs); a second cycle is reported as NotConverged.
                single = true;
                history.clear();
            }
            history.push(states.clone());
            if single {
                if let Some(i) = (0..n).find(|&i| new_states[i] != states[i]) {
                    states[i] = new_states[i];
                }
            } else {
                states = new_states;
            }
        }
        self.check_contact_window(&states)?;
        let (g, s) = evaluate(&z);
        let pairs = self.pair_results(&z, &states, &g, &s);
        let rigid = self.rigid_results(&z, &lamv);
        let (solution, pin_traction) = self.boundary_state(&lamv, &z);
        let free_bodies = self.free_results(&solution, &lamv, &pin_traction);
        // Path memory for the next step.
        for i in 0..n {
            if states[i] != ContactState::Outside {
                self.slip[i] = s[i];
            }
        }
        self.states = states;
        Ok(ContactStepResult {
            iterations,
            residual,
            pairs,
            rigid,
            free_bodies,
            solution,
        })
    }

    /// Contact beyond the master segment: an active node next to a slave node outside the
    /// master is an error ([`Error::ContactReachesWindow`]).
    fn check_contact_window(&self, states: &[ContactState]) -> Result<()> {
        for p in &self.pairs {
            for b in 0..p.nodes.len() {
                let i = p.offset + b;
                let active = !matches!(states[i], ContactState::Open | ContactState::Outside);
                if active {
                    let nb = [b.wrapping_sub(1), b + 1];
                    for m in nb {
                        if m < p.nodes.len() && states[p.offset + m] == ContactState::Outside {
                            return Err(Error::ContactReachesWindow {
                                detail: format!(
                                    "contact pair '{}' / '{}': the contact reaches an end of \
                                     the master segment; extend the master segment, or, where \
                                     the master ends at a corner of its body (a punch edge), \
                                     end the slave segment at the same place",
                                    p.pair.slave, p.pair.master
                                ),
                            });
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The per-pair results of the solved step: node values, the slave force and the force
    /// the master receives (through the transfer), whether the contact touches a slave end.
    fn pair_results(
        &self,
        z: &[f64],
        states: &[ContactState],
        g: &[f64],
        s: &[f64],
    ) -> Vec<PairResult> {
        let n = self.n;
        let mut pairs = Vec::new();
        for p in &self.pairs {
            let mut nodes = Vec::new();
            let mut sf = [0.0; 2];
            let mut mf = [0.0; 2];
            let mut touches = false;
            let last = p.nodes.len() - 1;
            let nm = p.master_weights.len();
            let mut tm = vec![[0.0; 2]; nm];
            for (b, sn) in p.nodes.iter().enumerate() {
                let i = p.offset + b;
                let t = [
                    z[i] * sn.normal[0] + z[n + i] * sn.tangent[0],
                    z[i] * sn.normal[1] + z[n + i] * sn.tangent[1],
                ];
                for d in 0..2 {
                    sf[d] += p.slave_weights[b] * t[d];
                }
                for a in 0..nm {
                    for d in 0..2 {
                        tm[a][d] -= p.proj[(a, b)] * t[d];
                    }
                }
                let st = states[i];
                if (b == 0 || b == last)
                    && !matches!(st, ContactState::Open | ContactState::Outside)
                {
                    touches = true;
                }
                let (gap, slip, inc) = if sn.master.is_some() {
                    (Some(g[i]), s[i], s[i] - self.slip[i])
                } else {
                    (None, 0.0, 0.0)
                };
                nodes.push(ContactNode {
                    position: sn.position,
                    param: sn.param,
                    normal: sn.normal,
                    tangent: sn.tangent,
                    pressure: z[i],
                    shear: z[n + i],
                    initial_gap: sn.master.map(|_| sn.gap0),
                    gap,
                    slip,
                    slip_increment: inc,
                    state: st,
                });
            }
            for a in 0..nm {
                for d in 0..2 {
                    mf[d] += p.master_weights[a] * tm[a][d];
                }
            }
            pairs.push(PairResult {
                slave: p.pair.slave.clone(),
                master: p.pair.master.clone(),
                nodes,
                slave_force: sf,
                master_force: mf,
                touches_slave_end: touches,
            });
        }
        pairs
    }

    /// The rigid segments' translations and force resultants for unknowns `z` and load
    /// factors `lamv`.
    fn rigid_results(&self, z: &[f64], lamv: &[f64]) -> Vec<RigidResult> {
        let (n, nz, next) = (self.n, self.pz.ncols(), self.next());
        let ext = |m: &Mat<f64>, i: usize| -> f64 { (0..next).map(|g| lamv[g] * m[(i, g)]).sum() };
        let mut rigid = Vec::new();
        for (j, (name, _)) in self.rigid.iter().enumerate() {
            let mut force = [0.0; 2];
            for d in 0..2 {
                let mut f = ext(&self.f_ext, 2 * j + d);
                for c in 0..nz {
                    f += self.kf[(2 * j + d, c)] * z[c];
                }
                force[d] = f;
            }
            rigid.push(RigidResult {
                segment: name.clone(),
                translation: [z[2 * n + 2 * j], z[2 * n + 2 * j + 1]],
                force,
            });
        }
        rigid
    }

    /// The full boundary state for load factors `lamv` (per load-group column) and contact
    /// unknowns `z`, and the BEM traction at every pin (per free body, per pin). Pins report
    /// their prescribed traction in the state (see the module docs).
    pub(super) fn boundary_state(&self, lamv: &[f64], z: &[f64]) -> (BemSolution, Vec<Vec<f64>>) {
        let next = self.next();
        let np = self.params.len();
        let mut param = vec![0.0; np];
        for k in 0..np {
            let mut v = 0.0;
            for c in 0..z.len() {
                v += self.pz[(k, c)] * z[c];
            }
            param[k] = v;
        }
        let mut x = vec![0.0; self.ncol];
        for body in &self.bodies {
            for (li, &col) in body.cols.iter().enumerate() {
                let mut v = 0.0;
                for g in 0..next {
                    v += lamv[g] * body.x[(li, g)];
                }
                for (k, &gp) in body.params.iter().enumerate() {
                    v += body.x[(li, next + k)] * param[gp];
                }
                x[col] = v;
            }
        }
        let mut over_t: HashMap<(usize, usize, usize), f64> = HashMap::new();
        let mut over_u: HashMap<(usize, usize, usize), f64> = HashMap::new();
        for (k, p) in self.params.iter().enumerate() {
            match *p {
                Param::Traction { region, node, d } => {
                    over_t.insert((region, node, d), param[k]);
                }
                Param::Rigid { j, d } => {
                    let info = &self.problem.mesh.segments[self.rigid[j].1];
                    for &o in &info.owner_nodes {
                        over_u.insert((info.owner, o, d), param[k]);
                    }
                }
                Param::Free { .. } => {}
            }
        }
        let mut pin_traction = Vec::with_capacity(self.free.len());
        for fb in &self.free {
            let mut tp = Vec::with_capacity(fb.pins.len());
            for pin in &fb.pins {
                let u: f64 = (0..fb.modes.len())
                    .map(|k| pin.row[k] * param[fb.param0 + k])
                    .sum();
                over_u.insert((pin.region, pin.node, pin.d), u);
                over_t.insert((pin.region, pin.node, pin.d), lamv[pin.group] * pin.t);
                if let Dof::T { col, .. } = self.dofs[pin.region][pin.node][pin.d] {
                    tp.push(x[col] * self.scale);
                } else {
                    tp.push(0.0);
                }
            }
            pin_traction.push(tp);
        }
        let mut displacement = Vec::new();
        let mut traction = Vec::new();
        for (r, d) in self.dofs.iter().enumerate() {
            let mut u = Vec::with_capacity(d.len());
            let mut t = Vec::with_capacity(d.len());
            for (node, dn) in d.iter().enumerate() {
                let mut un = [0.0; 2];
                let mut tn = [0.0; 2];
                let lam = lamv[self.seg_group[self_segment(&self.problem, r, node)]];
                for dir in 0..2 {
                    match dn[dir] {
                        Dof::U { col, t } => {
                            un[dir] = x[col];
                            tn[dir] = over_t.get(&(r, node, dir)).copied().unwrap_or(lam * t);
                        }
                        Dof::T { col, u } => {
                            un[dir] = over_u.get(&(r, node, dir)).copied().unwrap_or(lam * u);
                            tn[dir] = over_t
                                .get(&(r, node, dir))
                                .copied()
                                .unwrap_or(x[col] * self.scale);
                        }
                        Dof::Interface { u_col, t_col, sign } => {
                            un[dir] = x[u_col];
                            tn[dir] = sign * x[t_col] * self.scale;
                        }
                    }
                }
                if let Some(f) = node_frame(&self.free, r, node) {
                    // Components along the support's frame directions back to global axes.
                    let glob = |v: [f64; 2]| {
                        [
                            v[0] * f[0][0] + v[1] * f[1][0],
                            v[0] * f[0][1] + v[1] * f[1][1],
                        ]
                    };
                    un = glob(un);
                    tn = glob(tn);
                }
                u.push(un);
                t.push(tn);
            }
            displacement.push(u);
            traction.push(t);
        }
        (
            BemSolution {
                mesh: self.problem.mesh.clone(),
                displacement,
                traction,
                residual: self.lu_residual,
                body_force_factor: lamv[0],
            },
            pin_traction,
        )
    }
}
