//! The 2D boundary element method at a complex frequency s (the Laplace domain): the
//! operators H(s), G(s) of each region and the solve of the static BEM's boundary-value
//! problem (same boundary conditions, bonded interfaces and DOF layout) for complex data.
//! This is what convolution quadrature evaluates at its frequencies (docs/theory/DYNAMICS.md
//! sec. 1.1; Schanz & Antes 1997; Schanz 2001).
//!
//! **Difference form.** The transformed boundary integral equation of a region reads
//! `H(s) u(s) = G(s) t(s)` with the kernels of [`LaplaceKelvin2d`] (zero initial conditions,
//! no body forces). The strongly singular part of T(s) and the free term are those of the
//! static kernel (T(s) - T_Kelvin is bounded, ~ r ln r at r -> 0), so
//!
//! ```text
//! H(s) = H_static + dH(s),   dH_ij = sum_e int_e [T(s) - T_Kelvin]_ij N_k dG
//! G(s) = G_static + dG(s),   dG_ij = sum_e int_e [U(s) - U_Kelvin]_ij N_k dG
//! ```
//!
//! where H_static keeps its rigid-body diagonal blocks (Brebbia & Dominguez sec. 5.7: the
//! free term plus the singular integral, which the dynamic kernel shares) and dH, dG
//! integrate the bounded differences over every element, the collocation node's own
//! elements included (there with the power-substitution singular rule: dU ~ const + r^2 ln
//! r, dT ~ r ln r). The rigid-body rule cannot be applied to H(s) itself: a rigid
//! translation is not a solution of the dynamic equations (H(s) 1 != 0). The kernels vary
//! on the length |c2/s|, so every element is first cut into `ceil(|s| l / c2)` equal pieces
//! (l its chord), at most [`MAX_PIECES`], each integrated with the static rules.
//!
//! **Speed** (issue 13). The kernels' radial functions depend on r alone at a fixed s: one
//! [`RadialTable`] per region and frequency (Chebyshev interpolants on intervals of c2/|s|,
//! equal to the direct Bessel form to round-off) serves every quadrature point, instead of
//! four complex Bessel evaluations per point. An element at least d away from the source
//! point with Re(s) d/c1 > [`FAR_DECAY`] is not integrated: the dynamic kernels there are
//! below e^-45 of their size, so its difference integrals are minus its static ones (one
//! static element integral, no pieces), and the H(s), G(s) entries of node pairs whose
//! elements are all far are 0 to rounding (where the direct integration left the static
//! rule's own quadrature error, up to 8e-8 of the largest entry on curved elements).
//!
//! **Solve.** The static system build ([`BemProblem`]'s, generic over the scalar) with
//! complex H(s), G(s): known values are the transformed prescribed displacements (m s) and
//! tractions (Pa s) per known DOF. Bodies need no restraint (inertia holds them for
//! Re s > 0). Interior displacements at probe points by the transformed Somigliana identity
//! `u(x, s) = sum_e int U(s) t(s) - int T(s) u(s)`.

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use faer::linalg::solvers::Solve;
use faer::{c64, Mat};

use crate::dynamics::cq::LaplaceResponse;
use crate::dynamics::kernel::{LaplaceKelvin2d, RadialTable, Tensor2};
use crate::error::{Error, Result};
use crate::operators::bem2d::assemble::{
    assemble_rows, matrix_bytes_of, probe_memory, try_zeros_of,
};
use crate::operators::bem2d::integrate::{element_hg, element_integrals};
use crate::operators::bem2d::mesh::{Element, RegionMesh};
use crate::operators::bem2d::{BemModel, RegionOperators};
use crate::solvers::bem2d::{
    junction_fields, known_values, locate_site, BemProblem, BoundaryConditions, Dof, Site,
};
use crate::solvers::nan_max;

/// The largest number of pieces an element is cut into for the Laplace-domain integrals
/// (|s| l / c2 up to 256: far beyond the resolution of the elements' quadratic fields).
pub const MAX_PIECES: usize = 256;

/// The integrals of one element for one source point: `[i][2k + j]` (source direction i,
/// element node k, direction j).
type ElementBlock = [[c64; 6]; 2];

/// Re(s) d / c1 above which an element at distance at least d from the source point
/// is left out of the dynamic integrals: there |U(s)|, |T(s)| are below exp(-45) = 3e-20
/// of their size at the wave front (K0, K1 ~ sqrt(pi/(2 z)) exp(-z), the P wave's z1 =
/// s r/c1 decaying slowest), so the element's full dynamic integrals are 0 to rounding and
/// its difference integrals are minus its static ones: dH_e = -H_static,e, dG_e =
/// -G_static,e (an H(s) or G(s) entry whose elements are all far is then 0 to rounding).
/// The margin covers the kernels' algebraic factors (|z|^(1/2) and s/c in T: a factor
/// below 1e4 for |z| < 1e8), leaving < 1e-15 of the static entries.
pub const FAR_DECAY: f64 = 45.0;

/// Number of pieces of element `e` for the kernel's length scale c2/|s| (module docs).
fn pieces(e: &Element, kernel: &LaplaceKelvin2d, s: c64) -> usize {
    let n = (s.norm() * e.chord_length() / kernel.s_wave_speed()).ceil();
    if n.is_finite() && n >= 1.0 {
        (n as usize).min(MAX_PIECES)
    } else {
        1
    }
}

/// A lower bound of the distance from `p` to the points of element `e` (m): every point
/// x(xi) = g1 + xi (g2 - g0)/2 + xi^2 ((g0 + g2)/2 - g1) of the quadratic element lies
/// within |g2 - g0|/2 + |(g0 + g2)/2 - g1| <= the two chords' length of its middle
/// geometry point g1.
fn distance_bound(e: &Element, p: [f64; 2]) -> f64 {
    let g = &e.geometry;
    let (dx, dy) = (g[1][0] - p[0], g[1][1] - p[1]);
    (dx * dx + dy * dy).sqrt() - e.chord_length()
}

/// Whether element `e` is far from `p` for the kernel at s: Re(s) d / c1 > `far_decay`
/// ([`FAR_DECAY`]).
fn far(e: &Element, p: [f64; 2], kernel: &LaplaceKelvin2d, s: c64, far_decay: f64) -> bool {
    s.re * distance_bound(e, p) > far_decay * kernel.p_wave_speed()
}

/// The element integrals of the kernel differences dT, dU (or of the full kernels where
/// `full`) for source point `p` (model-local) and the element's node at the source, the
/// radial functions from `table` (its kernel and s). A far element ([`FAR_DECAY`]) is not
/// integrated: its differences are minus its static integrals (its full integrals 0).
fn element_differences(
    table: &RadialTable<'_>,
    e: &Element,
    p: [f64; 2],
    singular: Option<usize>,
    full: bool,
) -> Result<(ElementBlock, ElementBlock)> {
    element_differences_with(table, e, p, singular, full, FAR_DECAY)
}

/// [`element_differences`] with the far threshold `far_decay` in place of [`FAR_DECAY`]
/// (infinite: no element is left out).
fn element_differences_with(
    table: &RadialTable<'_>,
    e: &Element,
    p: [f64; 2],
    singular: Option<usize>,
    full: bool,
    far_decay: f64,
) -> Result<(ElementBlock, ElementBlock)> {
    let (kernel, s) = (table.kernel(), table.s());
    if singular.is_none() && far(e, p, kernel, s, far_decay) {
        if full {
            return Ok(([[c64::ZERO; 6]; 2], [[c64::ZERO; 6]; 2]));
        }
        let (h, g) = element_hg(kernel.statics(), e, p, None);
        let neg = |b: [[f64; 6]; 2]| b.map(|row| row.map(|v| c64::new(-v, 0.0)));
        return Ok((neg(h), neg(g)));
    }
    let mut err: Option<Error> = None;
    let zero: Tensor2 = [[c64::ZERO; 2]; 2];
    let out = element_integrals(e, p, singular, pieces(e, kernel, s), &mut |r, n| {
        let v = if full {
            table.kernels(r, n)
        } else {
            table.differences(r, n)
        };
        v.unwrap_or_else(|x| {
            err.get_or_insert(x);
            (zero, zero)
        })
    });
    match err {
        Some(x) => Err(x),
        None => Ok(out),
    }
}

/// The largest distance between two points of `region`'s boundary (m, an upper bound:
/// the diagonal of the geometry points' bounding box plus the longest element's chords),
/// the range of r the radial tables cover.
fn region_extent(region: &RegionMesh) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut chord = 0.0_f64;
    for e in &region.local_elements {
        for g in &e.geometry {
            for d in 0..2 {
                lo[d] = lo[d].min(g[d]);
                hi[d] = hi[d].max(g[d]);
            }
        }
        chord = chord.max(e.chord_length());
    }
    (hi[0] - lo[0]).hypot(hi[1] - lo[1]) + 2.0 * chord
}

/// The Laplace-domain operators `(H(s), G(s))` of one region (2n x 2n, the DOF and row
/// layout of [`RegionOperators`]) from its static operators `statics` and its dynamic
/// kernel (module docs).
///
/// Errors: [`Error::OutOfMemory`]; a kernel evaluation failure (s off the principal branch,
/// a Bessel failure).
pub fn region_operators(
    region: &RegionMesh,
    statics: &RegionOperators,
    kernel: &LaplaceKelvin2d,
    s: c64,
) -> Result<(Mat<c64>, Mat<c64>)> {
    let dof = 2 * region.nodes.len();
    let what = format!(
        "the Laplace-domain H and G matrices of region '{}' ({dof} x {dof}, complex)",
        region.name
    );
    let table = kernel.radial_table(s, region_extent(region))?;
    let (mut h, mut g) = assemble_rows(region, &what, false, &|e, p, singular| {
        element_differences(&table, e, p, singular, false)
    })?;
    for j in 0..dof {
        for i in 0..dof {
            h[(i, j)] += c64::new(statics.h[(i, j)], 0.0);
            g[(i, j)] += c64::new(statics.g[(i, j)], 0.0);
        }
    }
    Ok((h, g))
}

/// LU-solves `a x = b` (any number of right-hand sides) at frequency `s` and checks it:
/// every entry of x finite and the relative residual of one combination of the columns,
/// `|a (x w) - b w| / (|a| |x w| + |b w|)` (infinity norms, w_j = 1 + j / k for k
/// columns), below 1e-8. LU with partial pivoting is backward stable in practice (a
/// residual of a few ulps of |a| |x| for every column), so a combination with distinct positive weights has one
/// too; a singular or failed factorization shows as a non-finite x or a large residual.
/// The check costs one matrix-vector product instead of the full `a x - b` (a fifth of the
/// LU's flops for ~100 right-hand sides) and the moduli as `sqrt(re^2 + im^2)` (the
/// entries are far from overflow; a NaN propagates and fails the check).
///
/// Errors: [`Error::OutOfMemory`]; a singular or inaccurate solve ([`Error::Numerical`]
/// naming s).
fn lu_solve(a: Mat<c64>, b: Mat<c64>, s: c64) -> Result<Mat<c64>> {
    let (n, k) = (a.nrows(), b.ncols());
    // The LU's copy of A: allocated inside faer.
    probe_memory(
        &format!("the LU factorization of the Laplace-domain BEM system ({n} x {n})"),
        matrix_bytes_of::<c64>(n, n),
    )?;
    let x = a.partial_piv_lu().solve(&b);
    let fail = |residual: f64| Error::Numerical {
        context: "Laplace-domain BEM solve",
        detail: format!(
            "the LU solve of the {n} x {n} system at s = {s} failed (relative residual \
             {residual:.3e}); the system is singular or ill-conditioned"
        ),
    };
    let finite = |v: &c64| v.re.is_finite() && v.im.is_finite();
    if !(0..k).all(|j| x.col(j).iter().all(finite)) {
        return Err(fail(f64::NAN));
    }
    let w = Mat::<c64>::from_fn(k, 1, |j, _| c64::new(1.0 + j as f64 / k.max(1) as f64, 0.0));
    let xw = &x * &w;
    let bw = &b * &w;
    let res = &a * &xw - &bw;
    let modulus = |v: c64| (v.re * v.re + v.im * v.im).sqrt();
    let vec_inf =
        |m: &Mat<c64>| (0..m.nrows()).fold(0.0, |acc, i| nan_max(acc, modulus(m[(i, 0)])));
    let mut na = 0.0_f64;
    let mut rows = vec![0.0_f64; n];
    for j in 0..n {
        for (r, v) in rows.iter_mut().zip(a.col(j).iter()) {
            *r += modulus(*v);
        }
    }
    for r in rows {
        na = nan_max(na, r);
    }
    let residual = vec_inf(&res) / (na * vec_inf(&xw) + vec_inf(&bw)).max(f64::MIN_POSITIVE);
    if !(residual.is_finite() && residual < 1e-8) {
        return Err(fail(residual));
    }
    Ok(x)
}

/// One known DOF (an input of [`LaplaceBem::respond`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KnownDof {
    /// Region index.
    pub region: usize,
    /// Node index in the region.
    pub node: usize,
    /// Direction (0 = x, 1 = y).
    pub direction: usize,
    /// Whether the known value is a displacement (else a traction).
    pub displacement: bool,
}

/// The boundary state and probe displacements at one s (transformed: m s and Pa s for
/// data in m and Pa).
#[derive(Debug, Clone)]
pub struct LaplaceState {
    /// Nodal displacements per region and node.
    pub displacement: Vec<Vec<[c64; 2]>>,
    /// Nodal tractions per region and node (on that region).
    pub traction: Vec<Vec<[c64; 2]>>,
    /// Displacement at each probe point.
    pub probes: Vec<[c64; 2]>,
    /// Relative residual of the complex solve.
    pub residual: f64,
}

/// The Laplace-domain BEM of a model with densities per region and a fixed layout of
/// boundary conditions (which DOFs are known), built once: [`LaplaceBem::respond`] maps
/// the transformed known values at s to the transformed unknowns (module docs).
#[derive(Debug, Clone)]
pub struct LaplaceBem {
    problem: BemProblem,
    kernels: Vec<LaplaceKelvin2d>,
    dofs: Vec<Vec<[Dof; 2]>>,
    ncol: usize,
    known: Vec<KnownDof>,
    /// Static values of the known DOFs (input order).
    known_static: Vec<f64>,
    /// Whether system column c is a traction unknown.
    traction_col: Vec<bool>,
    /// (region, site) per probe: a model-local evaluation point, or a segment junction
    /// evaluated from the boundary state ([`probe_sites`]).
    probes: Vec<(usize, Site)>,
    /// (region, site) per stress probe ([`stress`]), as `probes`.
    stress_probes: Vec<(usize, Site)>,
    /// Per region the index into [`LaplaceBem::operators`]' list of the operators it uses
    /// (congruent regions share one, [`congruence`]).
    slot: Vec<usize>,
    /// The regions whose operators are assembled (one per slot).
    assembled: Vec<usize>,
}

impl LaplaceBem {
    /// Meshes and assembles `model` (static operators), with mass density `densities[r]`
    /// (kg/m^3) for region r, the DOF layout of `bcs` (which DOFs are prescribed; their
    /// values are the static data, [`LaplaceBem::static_known_values`]) and interior
    /// `probes` (m) whose displacements follow the boundary unknowns in the outputs.
    ///
    /// Each probe is evaluated where the static field sampler evaluates it (in the first
    /// region holding it; [`LaplaceBem::with_field_points`] names the region): inside by the
    /// Somigliana identity, within the boundary layer at that distance inside, at a segment
    /// junction from the boundary state by the static junction rule (module docs).
    ///
    /// Errors: as [`BemProblem::new`]; a density count that is not the region count or a
    /// density that is not positive; a region with body forces (not supported in the
    /// Laplace domain); the condition errors of [`BemProblem::solve`]; a probe outside every
    /// region ([`Error::InvalidParameter`]).
    pub fn new(
        model: &BemModel,
        densities: &[f64],
        bcs: &BoundaryConditions,
        probes: &[[f64; 2]],
    ) -> Result<Self> {
        let problem = BemProblem::new(model)?;
        let regions = &problem.mesh.regions;
        if densities.len() != regions.len() {
            return Err(Error::invalid(
                "densities",
                densities.len(),
                format!("must give one density per region ({})", regions.len()),
            ));
        }
        let mut kernels = Vec::with_capacity(regions.len());
        for (region, &rho) in regions.iter().zip(densities) {
            if region.body_force.is_some() {
                return Err(Error::invalid(
                    format!("region '{}'", region.name),
                    "body force",
                    "body forces are not supported by the Laplace-domain BEM",
                ));
            }
            kernels.push(
                LaplaceKelvin2d::from_static(&region.kernels, rho).map_err(|_| {
                    Error::invalid(
                        format!("density of region '{}'", region.name),
                        rho,
                        "the mass density must be positive and finite (kg/m^3)",
                    )
                })?,
            );
        }
        let sources = congruence::operator_sources(regions, &kernels);
        let assembled: Vec<usize> = (0..regions.len()).filter(|&r| sources[r] == r).collect();
        let slot = sources
            .iter()
            .map(|q| assembled.iter().position(|a| a == q).unwrap_or(0))
            .collect();
        let (dofs, ncol) = problem.dofs(bcs)?;
        let statics = known_values(&dofs);
        let mut known: Vec<(usize, KnownDof, f64)> = Vec::new();
        let mut traction_col = vec![false; ncol];
        for (r, nodes) in dofs.iter().enumerate() {
            for (node, d) in nodes.iter().enumerate() {
                for (direction, dof) in d.iter().enumerate() {
                    let value = statics[r][node][direction];
                    let mut push = |col, displacement| {
                        known.push((
                            col,
                            KnownDof {
                                region: r,
                                node,
                                direction,
                                displacement,
                            },
                            value,
                        ))
                    };
                    match *dof {
                        Dof::U { col, .. } => push(col, false),
                        Dof::T { col, .. } => {
                            push(col, true);
                            traction_col[col] = true;
                        }
                        Dof::Interface { t_col, .. } => traction_col[t_col] = true,
                    }
                }
            }
        }
        known.sort_by_key(|k| k.0);
        let probes = probe_sites(&problem.mesh, probes, &vec![None; probes.len()])?;
        Ok(Self {
            kernels,
            dofs,
            ncol,
            known_static: known.iter().map(|k| k.2).collect(),
            known: known.into_iter().map(|k| k.1).collect(),
            traction_col,
            probes,
            stress_probes: Vec::new(),
            slot,
            assembled,
            problem,
        })
    }

    /// The static problem (mesh and static operators).
    pub fn static_problem(&self) -> &BemProblem {
        &self.problem
    }

    /// The dynamic kernels per region.
    pub fn kernels(&self) -> &[LaplaceKelvin2d] {
        &self.kernels
    }

    /// Number of inputs: the known DOFs, in the static column order (by segment, owner
    /// node and direction; interfaces have none).
    pub fn inputs(&self) -> usize {
        self.known.len()
    }

    /// Number of outputs: the system unknowns (in column order: the unknown of each
    /// non-interface DOF, the displacement then the traction of each interface DOF), then
    /// two displacement components per probe, then three stress components (sigma_xx,
    /// sigma_yy, sigma_xy) per stress probe ([`LaplaceBem::with_stress_probes`], from
    /// [`LaplaceBem::first_stress_output`] on).
    pub fn outputs(&self) -> usize {
        self.ncol + 2 * self.probes.len() + 3 * self.stress_probes.len()
    }

    /// What each input is.
    pub fn known_dofs(&self) -> &[KnownDof] {
        &self.known
    }

    /// Whether output `k` (< [`LaplaceBem::outputs`]) is a traction (Pa s) rather than a
    /// displacement (m s).
    pub fn output_is_traction(&self, k: usize) -> bool {
        self.traction_col.get(k).copied().unwrap_or(false)
    }

    /// The static values of the known DOFs (m or Pa, input order): the data of the
    /// boundary conditions the model was built with. A load `f(t)` times this pattern has
    /// the inputs `f(s) * static_known_values()`.
    pub fn static_known_values(&self) -> &[f64] {
        &self.known_static
    }

    /// The values of the known DOFs (m or Pa, input order) of other boundary conditions
    /// `bcs` with the same layout as the model's (the same DOFs known, displacement or
    /// traction alike): the load pattern of one condition alone, for loads with one time
    /// function per condition (`sum_b f_b(t) * known_values_of(bcs_b)`).
    ///
    /// Errors: a condition naming no segment of the model (as [`BemProblem::solve`]); a layout that differs from the model's
    /// ([`Error::InvalidParameter`]).
    pub fn known_values_of(&self, bcs: &BoundaryConditions) -> Result<Vec<f64>> {
        let (dofs, ncol) = self.problem.dofs(bcs)?;
        let layout = |d: &Dof| match *d {
            Dof::U { col, .. } => (0, col, 0),
            Dof::T { col, .. } => (1, col, 0),
            Dof::Interface { u_col, t_col, .. } => (2, u_col, t_col),
        };
        let same = dofs.len() == self.dofs.len()
            && dofs.iter().zip(&self.dofs).all(|(a, b)| {
                a.len() == b.len()
                    && a.iter()
                        .flatten()
                        .zip(b.iter().flatten())
                        .all(|(x, y)| layout(x) == layout(y))
            });
        if ncol != self.ncol || !same {
            return Err(Error::invalid(
                "bcs",
                "(other layout)",
                "must prescribe the same DOFs (displacement or traction) as the model's \
                 boundary conditions",
            ));
        }
        let values = known_values(&dofs);
        Ok(self
            .known
            .iter()
            .map(|k| values[k.region][k.node][k.direction])
            .collect())
    }

    /// The transformed unknowns at `s` for the transformed known values `known` (length
    /// [`LaplaceBem::inputs`]): the outputs described at [`LaplaceBem::outputs`].
    ///
    /// Errors: as [`LaplaceBem::respond_state`].
    pub fn respond(&self, s: c64, known: &[c64]) -> Result<Vec<c64>> {
        let (x, state) = self.solve(s, known)?;
        let mut out = Vec::with_capacity(self.outputs());
        let scale = self.problem.traction_scale();
        for c in 0..self.ncol {
            let v = x[(c, 0)];
            out.push(if self.traction_col[c] { v * scale } else { v });
        }
        for p in &state.probes {
            out.extend_from_slice(p);
        }
        if !self.stress_probes.is_empty() {
            for p in self.probe_stresses(s, &state)? {
                out.extend_from_slice(&p);
            }
        }
        Ok(out)
    }

    /// The output index of the unknown of DOF component (`region`, `node`, `direction`): its
    /// displacement where the traction is known (or on an interface), its traction where the
    /// displacement is known; None for an index out of range.
    pub fn unknown_output(&self, region: usize, node: usize, direction: usize) -> Option<usize> {
        match *self.dofs.get(region)?.get(node)?.get(direction)? {
            Dof::U { col, .. } | Dof::T { col, .. } => Some(col),
            Dof::Interface { u_col, .. } => Some(u_col),
        }
    }

    /// The system unknowns (the first `outputs() - 2 probes` values of
    /// [`LaplaceBem::respond`], same units and order; no probes) for several vectors of known
    /// values at once: one assembly and one LU factorization at `s` for all of them (what a
    /// transfer matrix of many inputs needs).
    ///
    /// Errors: as [`LaplaceBem::respond_state`] for each vector.
    pub fn respond_columns(&self, s: c64, known: &[Vec<c64>]) -> Result<Vec<Vec<c64>>> {
        let x = self.solve_columns(s, known)?;
        let scale = self.problem.traction_scale();
        Ok((0..known.len())
            .map(|j| {
                (0..self.ncol)
                    .map(|c| {
                        let v = x[(c, j)];
                        if self.traction_col[c] {
                            v * scale
                        } else {
                            v
                        }
                    })
                    .collect()
            })
            .collect())
    }

    /// The region operators `(H(s), G(s))` ([`region_operators`]) of the regions in
    /// `self.assembled`: region r uses entry `self.slot[r]` (congruent regions share one,
    /// [`congruence`]).
    fn operators(&self, s: c64) -> Result<Vec<(Mat<c64>, Mat<c64>)>> {
        self.assembled
            .iter()
            .map(|&r| {
                region_operators(
                    &self.problem.mesh.regions[r],
                    &self.problem.operators[r],
                    &self.kernels[r],
                    s,
                )
            })
            .collect()
    }

    /// The operators of every region (in region order) from the list of
    /// [`LaplaceBem::operators`].
    fn region_refs<'a>(
        &self,
        ops: &'a [(Mat<c64>, Mat<c64>)],
    ) -> Vec<(&'a Mat<c64>, &'a Mat<c64>)> {
        self.slot.iter().map(|&k| (&ops[k].0, &ops[k].1)).collect()
    }

    /// The raw solutions (`ncol x known.len()`, the traction unknowns divided by the
    /// traction scale, as [`BemProblem::solve_assembled`]'s) for several vectors of known
    /// values: one assembly and one LU factorization at `s` for all of them.
    fn solve_columns(&self, s: c64, known: &[Vec<c64>]) -> Result<Mat<c64>> {
        for k in known {
            self.check_input(s, k)?;
        }
        let mesh = &self.problem.mesh;
        let ops = self.operators(s)?;
        let refs = self.region_refs(&ops);
        // Right-hand sides: the known column of G (known traction) or -H (known
        // displacement) times the value, as the system build of the static solver.
        let mut offsets = Vec::with_capacity(refs.len());
        let mut offset = 0;
        for (h, _) in &refs {
            offsets.push(offset);
            offset += h.nrows();
        }
        let mut b = try_zeros_of::<c64>(
            &format!(
                "the Laplace-domain right-hand sides ({} x {})",
                self.ncol,
                known.len()
            ),
            self.ncol,
            known.len(),
        )?;
        for (j, values) in known.iter().enumerate() {
            for (k, v) in self.known.iter().zip(values) {
                if *v == c64::ZERO {
                    continue;
                }
                let (h, g) = refs[k.region];
                let c = 2 * k.node + k.direction;
                let off = offsets[k.region];
                for row in 0..h.nrows() {
                    if k.displacement {
                        b[(off + row, j)] -= h[(row, c)] * v;
                    } else {
                        b[(off + row, j)] += g[(row, c)] * v;
                    }
                }
            }
        }
        let blocks = self.independent_blocks(&offsets);
        if blocks.len() < 2 {
            let zero: Vec<Vec<[c64; 2]>> = mesh
                .regions
                .iter()
                .map(|r| vec![[c64::ZERO; 2]; r.nodes.len()])
                .collect();
            let (a, _) = self
                .problem
                .assemble_system(&self.dofs, self.ncol, &refs, &zero, &[])?;
            return lu_solve(a, b, s);
        }
        // Bodies that share no interface: A is block diagonal (region rows x the columns of
        // the region's DOFs), so each body's block is factored alone (the same solution,
        // a fraction of the dense LU's cost: two equal bodies take a quarter). A block of
        // one region is built from its operators directly (the dense A is never formed);
        // blocks with the same operators and column layout (congruent bodies with the same
        // conditions) are factored once for all their right-hand sides.
        let single: Vec<Option<Vec<(bool, usize)>>> = blocks
            .iter()
            .map(|(regions, _, cols)| match regions.as_slice() {
                [r] => self.single_layout(*r, cols),
                _ => None,
            })
            .collect();
        let full = if single.iter().any(Option::is_none) {
            let zero: Vec<Vec<[c64; 2]>> = mesh
                .regions
                .iter()
                .map(|r| vec![[c64::ZERO; 2]; r.nodes.len()])
                .collect();
            Some(
                self.problem
                    .assemble_system(&self.dofs, self.ncol, &refs, &zero, &[])?
                    .0,
            )
        } else {
            None
        };
        let nk = known.len();
        let mut x = try_zeros_of::<c64>(
            &format!("the Laplace-domain solutions ({} x {nk})", self.ncol),
            self.ncol,
            nk,
        )?;
        let mut done = vec![false; blocks.len()];
        for k in 0..blocks.len() {
            if done[k] {
                continue;
            }
            // The blocks that share block k's matrix (k itself first).
            let group: Vec<usize> = match (&single[k], &blocks[k].0[..]) {
                (Some(layout), [r]) => (k..blocks.len())
                    .filter(|&m| {
                        !done[m]
                            && matches!(blocks[m].0[..], [q] if self.slot[q] == self.slot[*r])
                            && single[m].as_ref() == Some(layout)
                    })
                    .collect(),
                _ => vec![k],
            };
            let (_, rows, cols) = &blocks[k];
            let ab = match (&single[k], &full) {
                (Some(layout), _) => {
                    let what = format!(
                        "the Laplace-domain block matrix ({} x {}, complex)",
                        rows.len(),
                        cols.len()
                    );
                    let mut ab = try_zeros_of::<c64>(&what, rows.len(), cols.len())?;
                    let (h, g) = refs[blocks[k].0[0]];
                    let scale = self.problem.traction_scale();
                    // The same operations as `BemProblem::assemble_system` on a zero matrix.
                    for (c, &(traction, j)) in layout.iter().enumerate() {
                        for row in 0..rows.len() {
                            if traction {
                                ab[(row, j)] -= g[(row, c)] * scale;
                            } else {
                                ab[(row, j)] += h[(row, c)];
                            }
                        }
                    }
                    ab
                }
                (None, Some(a)) => {
                    Mat::<c64>::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
                }
                (None, None) => {
                    return Err(Error::Numerical {
                        context: "Laplace-domain BEM solve",
                        detail: "no system matrix for a block".into(),
                    })
                }
            };
            let bb = Mat::<c64>::from_fn(rows.len(), group.len() * nk, |i, j| {
                b[(blocks[group[j / nk]].1[i], j % nk)]
            });
            let xb = lu_solve(ab, bb, s)?;
            for (g, &m) in group.iter().enumerate() {
                for (i, &c) in blocks[m].2.iter().enumerate() {
                    for j in 0..nk {
                        x[(c, j)] = xb[(i, g * nk + j)];
                    }
                }
                done[m] = true;
            }
        }
        Ok(x)
    }

    /// The column layout of the block of region `r` alone with the (sorted) system columns
    /// `cols`: per region DOF 2 node + direction, whether it is a traction unknown and its
    /// column in the block; None where the region has an interface DOF or a column is not
    /// in `cols`.
    fn single_layout(&self, r: usize, cols: &[usize]) -> Option<Vec<(bool, usize)>> {
        let mut layout = Vec::with_capacity(2 * self.dofs[r].len());
        for dof in self.dofs[r].iter().flatten() {
            let (traction, col) = match *dof {
                Dof::U { col, .. } => (false, col),
                Dof::T { col, .. } => (true, col),
                Dof::Interface { .. } => return None,
            };
            layout.push((traction, cols.binary_search(&col).ok()?));
        }
        Some(layout)
    }

    /// The independent diagonal blocks of the system matrix (regions, rows, columns), one
    /// per set of regions joined by bonded interfaces, with the first row of each region at
    /// `offsets[r]`; empty where a block would not be square (then the whole system is
    /// solved at once).
    #[allow(clippy::type_complexity)]
    fn independent_blocks(&self, offsets: &[usize]) -> Vec<(Vec<usize>, Vec<usize>, Vec<usize>)> {
        let nr = self.dofs.len();
        // Union-find over the regions: an interface column joins the regions that use it.
        let mut parent: Vec<usize> = (0..nr).collect();
        fn root(parent: &mut [usize], mut r: usize) -> usize {
            while parent[r] != r {
                parent[r] = parent[parent[r]];
                r = parent[r];
            }
            r
        }
        let mut owner: Vec<Option<usize>> = vec![None; self.ncol];
        for (r, nodes) in self.dofs.iter().enumerate() {
            for dof in nodes.iter().flatten() {
                let cols = match *dof {
                    Dof::U { col, .. } | Dof::T { col, .. } => [col, col],
                    Dof::Interface { u_col, t_col, .. } => [u_col, t_col],
                };
                for c in cols {
                    match owner[c] {
                        None => owner[c] = Some(r),
                        Some(o) => {
                            let (a, b) = (root(&mut parent, o), root(&mut parent, r));
                            parent[a] = b;
                        }
                    }
                }
            }
        }
        let mut blocks: Vec<(usize, Vec<usize>, Vec<usize>, Vec<usize>)> = Vec::new();
        for r in 0..nr {
            let id = root(&mut parent, r);
            let k = match blocks.iter().position(|b| b.0 == id) {
                Some(k) => k,
                None => {
                    blocks.push((id, Vec::new(), Vec::new(), Vec::new()));
                    blocks.len() - 1
                }
            };
            blocks[k].1.push(r);
            blocks[k]
                .2
                .extend(offsets[r]..offsets[r] + 2 * self.dofs[r].len());
        }
        for (c, o) in owner.iter().enumerate() {
            let Some(o) = o else { return Vec::new() };
            let id = root(&mut parent, *o);
            if let Some(b) = blocks.iter_mut().find(|b| b.0 == id) {
                b.3.push(c);
            }
        }
        if blocks.iter().any(|b| b.2.len() != b.3.len()) {
            return Vec::new();
        }
        blocks.into_iter().map(|b| (b.1, b.2, b.3)).collect()
    }

    /// The transfer matrix `R(s)` (`outputs x inputs`, row-major: the outputs of
    /// [`LaplaceBem::respond`] for each unit input): one assembly and one LU factorization
    /// for all inputs and the probe tables built once (issue 13 "Speed"; the trait's
    /// default assembles and factors once per input).
    ///
    /// Errors: as [`LaplaceBem::respond_state`].
    pub fn transfer_matrix(&self, s: c64) -> Result<Vec<c64>> {
        let (ni, no) = (self.inputs(), self.outputs());
        let units: Vec<Vec<c64>> = (0..ni)
            .map(|j| {
                let mut v = vec![c64::ZERO; ni];
                v[j] = c64::ONE;
                v
            })
            .collect();
        let x = self.solve_columns(s, &units)?;
        let scale = self.problem.traction_scale();
        let mut out = vec![c64::ZERO; no * ni];
        for c in 0..self.ncol {
            let f = if self.traction_col[c] { scale } else { 1.0 };
            for j in 0..ni {
                out[c * ni + j] = x[(c, j)] * f;
            }
        }
        if self.probes.is_empty() && self.stress_probes.is_empty() {
            return Ok(out);
        }
        let tables = self.probe_tables(s)?;
        let stress_tables = self.stress_tables(s)?;
        let mut values: Vec<Vec<[c64; 2]>> = self
            .problem
            .mesh
            .regions
            .iter()
            .map(|r| vec![[c64::ZERO; 2]; r.nodes.len()])
            .collect();
        for (j, k) in self.known.iter().enumerate() {
            values[k.region][k.node][k.direction] = c64::ONE;
            let xj = Mat::<c64>::from_fn(self.ncol, 1, |i, _| x[(i, j)]);
            let (displacement, traction) = self.problem.unpack(&self.dofs, &xj, &values);
            values[k.region][k.node][k.direction] = c64::ZERO;
            let probes = self.probe_displacements(&tables, &displacement, &traction)?;
            let stresses = self.probe_stresses_with(&stress_tables, &displacement, &traction)?;
            let column = probes.iter().flatten().chain(stresses.iter().flatten());
            for (row, v) in (self.ncol..).zip(column) {
                out[row * ni + j] = *v;
            }
        }
        Ok(out)
    }

    /// Checks `s` and one vector of known values (see [`LaplaceBem::respond_state`]).
    fn check_input(&self, s: c64, known: &[c64]) -> Result<()> {
        if !(s.re.is_finite() && s.im.is_finite() && s.re > 0.0) {
            return Err(Error::invalid(
                "s",
                format!("{s}"),
                "the Laplace parameter must be finite with Re s > 0",
            ));
        }
        if known.len() != self.known.len() {
            return Err(Error::invalid(
                "known",
                known.len(),
                format!("must give one value per known DOF ({})", self.known.len()),
            ));
        }
        if known
            .iter()
            .any(|v| !(v.re.is_finite() && v.im.is_finite()))
        {
            return Err(Error::invalid("known", "a value", "must be finite"));
        }
        Ok(())
    }

    /// The boundary state and probe displacements at `s` for the known values `known`.
    ///
    /// Errors: `known` of the wrong length or not finite, s not finite or Re s <= 0
    /// ([`Error::InvalidParameter`]); [`Error::OutOfMemory`]; a singular solve
    /// ([`Error::Numerical`]).
    pub fn respond_state(&self, s: c64, known: &[c64]) -> Result<LaplaceState> {
        Ok(self.solve(s, known)?.1)
    }

    fn solve(&self, s: c64, known: &[c64]) -> Result<(Mat<c64>, LaplaceState)> {
        self.check_input(s, known)?;
        let mesh = &self.problem.mesh;
        let mut values: Vec<Vec<[c64; 2]>> = mesh
            .regions
            .iter()
            .map(|r| vec![[c64::ZERO; 2]; r.nodes.len()])
            .collect();
        for (k, v) in self.known.iter().zip(known) {
            values[k.region][k.node][k.direction] = *v;
        }
        let ops = self.operators(s)?;
        let refs = self.region_refs(&ops);
        let (x, residual) =
            self.problem
                .solve_system(&self.dofs, self.ncol, &refs, &values, &[])?;
        let (displacement, traction) = self.problem.unpack(&self.dofs, &x, &values);
        let tables = self.probe_tables(s)?;
        let probes = self.probe_displacements(&tables, &displacement, &traction)?;
        Ok((
            x,
            LaplaceState {
                displacement,
                traction,
                probes,
                residual,
            },
        ))
    }

    /// One radial table at `s` per region that holds a displacement probe (None for the
    /// others).
    fn probe_tables(&self, s: c64) -> Result<Vec<Option<RadialTable<'_>>>> {
        self.problem
            .mesh
            .regions
            .iter()
            .zip(&self.kernels)
            .enumerate()
            .map(|(r, (region, kernel))| {
                self.probes
                    .iter()
                    .any(|q| q.0 == r && matches!(q.1, Site::Interior(_)))
                    .then(|| kernel.radial_table(s, region_extent(region)))
                    .transpose()
            })
            .collect()
    }

    /// The transformed displacements at the probes (the Somigliana identity, module docs)
    /// of the boundary state `displacement`, `traction` (per region and node), with the
    /// tables of [`LaplaceBem::probe_tables`].
    fn probe_displacements(
        &self,
        tables: &[Option<RadialTable<'_>>],
        displacement: &[Vec<[c64; 2]>],
        traction: &[Vec<[c64; 2]>],
    ) -> Result<Vec<[c64; 2]>> {
        let mut probes = Vec::with_capacity(self.probes.len());
        for (r, site) in &self.probes {
            let r = *r;
            let region = &self.problem.mesh.regions[r];
            let p = match site {
                Site::Interior(p) => *p,
                Site::Junction(feet) => {
                    let (u, _) = junction_state(region, feet, &displacement[r], &traction[r]);
                    probes.push(u);
                    continue;
                }
            };
            let Some(table) = &tables[r] else {
                return Err(Error::Numerical {
                    context: "LaplaceBem probes",
                    detail: format!("no radial table for region {r}"),
                });
            };
            let mut u = [c64::ZERO; 2];
            for e in &region.local_elements {
                let (h, g) = element_differences(table, e, p, None, true)?;
                for (k, &m) in e.nodes.iter().enumerate() {
                    for i in 0..2 {
                        for j in 0..2 {
                            u[i] += g[i][2 * k + j] * traction[r][m][j]
                                - h[i][2 * k + j] * displacement[r][m][j];
                        }
                    }
                }
            }
            probes.push(u);
        }
        Ok(probes)
    }
}

/// The sites of `points` (m; point i in region `regions[i]`, None: the first region holding
/// it) for the probes of a model with mesh `mesh` ([`locate_site`]): interior points in
/// model-local coordinates (the Somigliana integrals' frame, `RegionMesh::local_elements`),
/// segment junctions as found.
///
/// Errors: as [`locate_site`]; counts that differ ([`Error::InvalidParameter`]).
pub(crate) fn probe_sites(
    mesh: &crate::operators::bem2d::BemMesh,
    points: &[[f64; 2]],
    regions: &[Option<usize>],
) -> Result<Vec<(usize, Site)>> {
    if regions.len() != points.len() {
        return Err(Error::invalid(
            "regions",
            regions.len(),
            format!("must give one region per point ({})", points.len()),
        ));
    }
    let o = mesh.origin;
    points
        .iter()
        .zip(regions)
        .map(|(&p, &region)| {
            let (r, site) = locate_site(mesh, region, p)?;
            Ok(match site {
                Site::Interior(q) => (r, Site::Interior([q[0] - o[0], q[1] - o[1]])),
                junction => (r, junction),
            })
        })
        .collect()
}

/// The static junction rule ([`junction_fields`]) on a transformed boundary state (per
/// node of `region`): the rule is linear in the boundary data, so it applies to the real
/// and the imaginary part separately; the transformed displacement (m s) and stress
/// [xx, yy, xy] (Pa s).
pub(crate) fn junction_state(
    region: &RegionMesh,
    feet: &[(usize, f64)],
    displacement: &[[c64; 2]],
    traction: &[[c64; 2]],
) -> ([c64; 2], [c64; 3]) {
    let part = |f: fn(&c64) -> f64| {
        let u: Vec<[f64; 2]> = displacement.iter().map(|v| v.each_ref().map(f)).collect();
        let t: Vec<[f64; 2]> = traction.iter().map(|v| v.each_ref().map(f)).collect();
        junction_fields(region, feet, &u, &t)
    };
    let (ur, sr) = part(|v| v.re);
    let (ui, si) = part(|v| v.im);
    (
        [0, 1].map(|d| c64::new(ur[d], ui[d])),
        [0, 1, 2].map(|c| c64::new(sr[c], si[c])),
    )
}

/// The Laplace-domain BEM as the response that convolution quadrature convolves
/// ([`crate::dynamics::cq::convolve`], docs/theory/DYNAMICS.md sec. 1.1 and 5): inputs the
/// known DOF values, outputs the unknowns then the probe displacements, exactly as
/// [`LaplaceBem::respond`].
impl LaplaceResponse for LaplaceBem {
    fn inputs(&self) -> usize {
        LaplaceBem::inputs(self)
    }

    fn outputs(&self) -> usize {
        LaplaceBem::outputs(self)
    }

    fn respond(&self, s: c64, inputs: &[c64]) -> Result<Vec<c64>> {
        LaplaceBem::respond(self, s, inputs)
    }

    fn transfer_matrix(&self, s: c64) -> Result<Vec<c64>> {
        LaplaceBem::transfer_matrix(self, s)
    }
}

mod congruence;
pub mod stress;
pub mod verify_limits;

#[cfg(test)]
mod tests;

#[cfg(test)]
mod time_tests;

#[cfg(test)]
mod verify_cavity;

#[cfg(test)]
mod verify_stability;

#[cfg(test)]
mod verify_static;

#[cfg(test)]
mod verify_lamb;

#[cfg(test)]
mod fast_tests;

#[cfg(test)]
mod congruence_tests;
