//! Shared test models of the dynamics tests (`#[cfg(test)]` only): the 1D column with
//! nu = 0 (docs/theory/DYNAMICS.md 3.1), the ring standing for the cylindrical cavity
//! (3.2) with its closed-form wall displacement in the Laplace domain, a response wrapper
//! reading the cavity wall's mean radial displacement, and small helpers. One place for
//! what `laplace/tests.rs`, `laplace/time_tests.rs` and `laplace/verify*.rs` build.

use std::f64::consts::PI;

use faer::c64;

use crate::dynamics::cq::LaplaceResponse;
use crate::dynamics::laplace::LaplaceBem;
use crate::error::Result;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

/// A rectangle L x W (plane strain) with `nx` elements along x and `ny` across; segments
/// "bottom", "right", "top", "left" (counter-clockwise from the origin).
pub fn rectangle(m: ElasticMaterial, l: f64, w: f64, nx: usize, ny: usize) -> BemModel {
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "column",
            m,
            vec![
                Segment::line("bottom", [0.0, 0.0], [l, 0.0], nx),
                Segment::line("right", [l, 0.0], [l, w], ny),
                Segment::line("top", [l, w], [0.0, w], nx),
                Segment::line("left", [0.0, w], [0.0, 0.0], ny),
            ],
        )],
    )
}

/// The column's material: E = 1, nu = 0 (so that the 1D solution is an exact plane-strain
/// solution, docs/theory/DYNAMICS.md 3.1); with rho = 1, c1 = 1.
pub fn column_material() -> ElasticMaterial {
    ElasticMaterial::new(1.0, 0.0).expect("E = 1, nu = 0 is a valid material")
}

/// The column's boundary conditions: the traction t_x = 1 on the face x = 0 ("left",
/// outward normal -x: the end pressure p0 = 1) and rollers (u_x = 0, t_y = 0) at x = L.
pub fn column_bcs() -> BoundaryConditions {
    BoundaryConditions::new()
        .set(
            "left",
            SegmentBc::traction(Profile::Uniform(1.0), Profile::Uniform(0.0)),
        )
        .set("right", SegmentBc::roller_x())
}

/// The column L = 1 x W = 0.25 (E = 1, nu = 0) with `nx` x `ny` quadratic elements and
/// [`column_bcs`].
pub fn column(nx: usize, ny: usize) -> (BemModel, BoundaryConditions) {
    (
        rectangle(column_material(), 1.0, 0.25, nx, ny),
        column_bcs(),
    )
}

/// The cavity's material: mu = 1, nu = 0.25 (with rho = 1: c2 = 1, c1 = sqrt 3), the
/// values of the reference table docs/theory/DYNAMICS.md 3.2.
pub fn cavity_material() -> ElasticMaterial {
    let (mu, nu) = (1.0, 0.25);
    ElasticMaterial::new(2.0 * mu * (1.0 + nu), nu).expect("mu = 1, nu = 0.25 is valid")
}

/// An annulus a < r < R (plane strain, [`cavity_material`]): "outer_a", "outer_b" (upper
/// and lower half of r = R, `n_outer` elements each) and the hole "hole_a", "hole_b"
/// (`n_hole` elements per half circle).
pub fn ring(a: f64, big: f64, n_outer: usize, n_hole: usize) -> BemModel {
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            cavity_material(),
            vec![
                Segment::arc("outer_a", [0.0, 0.0], big, 0.0, PI, n_outer),
                Segment::arc("outer_b", [0.0, 0.0], big, PI, 2.0 * PI, n_outer),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], a, PI, 0.0, n_hole),
            Segment::arc("hole_b", [0.0, 0.0], a, 2.0 * PI, PI, n_hole),
        ])],
    )
}

/// The unit internal pressure on the ring's hole (outer boundary free).
pub fn cavity_bcs() -> BoundaryConditions {
    BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)))
}

/// The wall displacement of the cylindrical cavity (radius `a`) in the infinite plane
/// under the transformed pressure P(s) = 1 ([`cavity_material`], rho = 1),
/// docs/theory/DYNAMICS.md 3.2: `u_r(a, s) = K1(k a) / (k D)`,
/// `D = (lam + 2 mu) K0(k a) + 2 mu K1(k a)/(k a)`, k = s/c1.
pub fn cavity_wall_exact(a: f64, s: c64) -> c64 {
    use complex_bessel::besselk;
    let (mu, nu) = (1.0_f64, 0.25_f64);
    let lam = 2.0 * mu * nu / (1.0 - 2.0 * nu);
    let c1 = (lam + 2.0 * mu).sqrt();
    let k = s / c1;
    let ka = k * a;
    let k0 = besselk(0.0, ka).expect("K0 at Re s > 0");
    let k1 = besselk(1.0, ka).expect("K1 at Re s > 0");
    let d = k0 * (lam + 2.0 * mu) + k1 / ka * (2.0 * mu);
    k1 / (k * d)
}

/// The cavity wall's mean radial displacement (outputs: 1) of a ring under internal
/// pressure, from the full Laplace-domain state: a response wrapper as a user's own
/// post-processing would write it.
pub struct CavityWall {
    /// The ring's Laplace-domain BEM.
    pub bem: LaplaceBem,
    /// The hole radius a (m).
    pub radius: f64,
}

impl CavityWall {
    /// The ring [`ring`] (density 1) under [`cavity_bcs`].
    pub fn new(a: f64, big: f64, n_outer: usize, n_hole: usize) -> Self {
        let bem = LaplaceBem::new(&ring(a, big, n_outer, n_hole), &[1.0], &cavity_bcs(), &[])
            .expect("the ring is a valid model");
        CavityWall { bem, radius: a }
    }
}

impl LaplaceResponse for CavityWall {
    fn inputs(&self) -> usize {
        self.bem.inputs()
    }

    fn outputs(&self) -> usize {
        1
    }

    fn respond(&self, s: c64, inputs: &[c64]) -> Result<Vec<c64>> {
        let state = self.bem.respond_state(s, inputs)?;
        let region = &self.bem.static_problem().mesh.regions[0];
        let (mut sum, mut count) = (c64::ZERO, 0.0);
        for (node, u) in region.nodes.iter().zip(&state.displacement[0]) {
            let x = node.position;
            let r = x[0].hypot(x[1]);
            if (r - self.radius).abs() < 1e-9 {
                sum += (u[0] * x[0] + u[1] * x[1]) / r;
                count += 1.0;
            }
        }
        Ok(vec![sum / count])
    }
}

/// The closed-form cavity wall displacement [`cavity_wall_exact`] as a CQ response
/// (1 input: the pressure p(t); 1 output: u_r(a, t)), the infinite-plane reference that
/// [`CavityWall`] approximates before the outer boundary's reflection returns.
pub struct CavityExact(pub f64);

impl LaplaceResponse for CavityExact {
    fn inputs(&self) -> usize {
        1
    }

    fn outputs(&self) -> usize {
        1
    }

    fn respond(&self, s: c64, inputs: &[c64]) -> Result<Vec<c64>> {
        Ok(vec![cavity_wall_exact(self.0, s) * inputs[0]])
    }
}

/// `v` times the complex factor `f`.
pub fn complex(v: &[f64], f: c64) -> Vec<c64> {
    v.iter().map(|&x| f * x).collect()
}

/// A list of errors printed as `1.23e-4 5.67e-5 ...`.
pub struct Errors(pub Vec<f64>);

impl std::fmt::Display for Errors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for e in &self.0 {
            write!(f, "{e:.2e} ")?;
        }
        Ok(())
    }
}
