//! The mesh the damage layer integrates over: simplices (triangles in 2D, tetrahedra in 3D)
//! over nodes that carry the field values, and the exact integration of a piecewise-linear
//! relative damage psi over the dangerous region {psi >= 1} (the paper's (22), (24)).

use rayon::prelude::*;
use serde::Serialize;

use super::sum::ExactSum;
use crate::analysis::stress_field::FieldGrid;
use crate::error::{Error, Result};

/// Cells per work unit of the parallel integration.
const CHUNK: usize = 4096;

/// Serial or parallel (rayon) evaluation. Both give the same bits: the cell contributions are
/// accumulated in exactly rounded sums (see the module docs of [`super`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum Execution {
    /// One thread.
    Serial,
    /// All rayon threads.
    #[default]
    Parallel,
}

/// A simplicial mesh: triangles (2D, plane strain, measures are areas per unit thickness,
/// m^2/m = m^2) or tetrahedra (3D, volumes, m^3), over nodes at which the field is given.
///
/// The relative damage is interpolated linearly on each simplex; the dangerous volume and
/// damageability are then integrated exactly ([`dangerous_region`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DamageMesh {
    dimension: usize,
    nodes: Vec<[f64; 3]>,
    /// Vertex indices; in 2D the fourth entry is unused (0).
    cells: Vec<[usize; 4]>,
    /// Area (2D, m^2) or volume (3D, m^3) of each cell.
    measures: Vec<f64>,
}

fn check_axis(name: &str, v: &[f64]) -> Result<()> {
    if v.len() < 2 {
        return Err(Error::invalid(
            name,
            format!("{} points", v.len()),
            "needs at least 2 points",
        ));
    }
    if v.iter().any(|c| !c.is_finite()) || v.windows(2).any(|w| w[1] <= w[0]) {
        return Err(Error::invalid(
            name,
            "coordinates",
            "must be finite and strictly increasing (m)",
        ));
    }
    Ok(())
}

fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs()
}

fn tetrahedron_volume(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    det.abs() / 6.0
}

impl DamageMesh {
    /// The tetrahedral mesh of a [`FieldGrid`]: nodes are the grid points in the grid's
    /// layout ([`FieldGrid::index`], so the field's values are the nodal values as they
    /// are), each hexahedral cell between neighbouring points split into the 6 Kuhn
    /// (Freudenthal) tetrahedra around its main diagonal (corner (0,0,0) to (1,1,1)); the
    /// same split in every cell makes the mesh conforming. Coordinates must be strictly
    /// increasing along each axis, at least 2 points each.
    pub fn from_field_grid(grid: &FieldGrid) -> Result<Self> {
        check_axis("field.x", &grid.x)?;
        check_axis("field.y", &grid.y)?;
        check_axis("field.z", &grid.z)?;
        let (nx, ny, nz) = (grid.x.len(), grid.y.len(), grid.z.len());
        let mut nodes = Vec::with_capacity(grid.len());
        for &z in &grid.z {
            for &y in &grid.y {
                for &x in &grid.x {
                    nodes.push([x, y, z]);
                }
            }
        }
        const PERMUTATIONS: [[usize; 3]; 6] = [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ];
        let mut cells = Vec::with_capacity(6 * (nx - 1) * (ny - 1) * (nz - 1));
        for iz in 0..nz - 1 {
            for iy in 0..ny - 1 {
                for ix in 0..nx - 1 {
                    let corner = |b: [usize; 3]| grid.index(ix + b[0], iy + b[1], iz + b[2]);
                    for p in PERMUTATIONS {
                        let mut b = [0usize; 3];
                        let v0 = corner(b);
                        b[p[0]] = 1;
                        let v1 = corner(b);
                        b[p[1]] = 1;
                        let v2 = corner(b);
                        b[p[2]] = 1;
                        let v3 = corner(b);
                        cells.push([v0, v1, v2, v3]);
                    }
                }
            }
        }
        Self::build(3, nodes, cells)
    }

    /// The triangular mesh of a 2D structured grid of points (x fastest: node
    /// `iy * x.len() + ix`), each quadrilateral split into two triangles along its diagonal
    /// from (ix, iy) to (ix + 1, iy + 1). For plane fields (2D BEM, plane strain) the
    /// measures are areas per unit thickness, m^2.
    pub fn structured_2d(x: &[f64], y: &[f64]) -> Result<Self> {
        check_axis("mesh.x", x)?;
        check_axis("mesh.y", y)?;
        let nx = x.len();
        let nodes: Vec<[f64; 2]> = y
            .iter()
            .flat_map(|&yy| x.iter().map(move |&xx| [xx, yy]))
            .collect();
        let mut cells = Vec::with_capacity(2 * (nx - 1) * (y.len() - 1));
        for iy in 0..y.len() - 1 {
            for ix in 0..nx - 1 {
                let n = |i: usize, j: usize| (iy + j) * nx + ix + i;
                cells.push([n(0, 0), n(1, 0), n(1, 1)]);
                cells.push([n(0, 0), n(1, 1), n(0, 1)]);
            }
        }
        Self::triangles(nodes, cells)
    }

    /// A mesh of triangles (x, y nodes in m) for plane fields, e.g. the cells of a 2D BEM
    /// interior evaluation. Errors: an index out of range, a non-finite coordinate, or a
    /// triangle of zero area.
    pub fn triangles(nodes: Vec<[f64; 2]>, triangles: Vec<[usize; 3]>) -> Result<Self> {
        let nodes = nodes.into_iter().map(|[x, y]| [x, y, 0.0]).collect();
        let cells = triangles
            .into_iter()
            .map(|[a, b, c]| [a, b, c, 0])
            .collect();
        Self::build(2, nodes, cells)
    }

    /// A mesh of tetrahedra (x, y, z nodes in m). Errors as for [`DamageMesh::triangles`].
    pub fn tetrahedra(nodes: Vec<[f64; 3]>, tetrahedra: Vec<[usize; 4]>) -> Result<Self> {
        Self::build(3, nodes, tetrahedra)
    }

    fn build(dimension: usize, nodes: Vec<[f64; 3]>, cells: Vec<[usize; 4]>) -> Result<Self> {
        if nodes.iter().flatten().any(|c| !c.is_finite()) {
            return Err(Error::invalid(
                "mesh.nodes",
                "non-finite coordinate",
                "coordinates must be finite (m)",
            ));
        }
        if cells.is_empty() {
            return Err(Error::invalid("mesh.cells", 0, "needs at least one cell"));
        }
        let mut measures = Vec::with_capacity(cells.len());
        for (k, cell) in cells.iter().enumerate() {
            let vertices = &cell[..=dimension];
            if let Some(v) = vertices.iter().find(|&&v| v >= nodes.len()) {
                return Err(Error::invalid(
                    format!("mesh.cells[{k}]"),
                    v,
                    format!("vertex index must be < the node count {}", nodes.len()),
                ));
            }
            let p = |i: usize| nodes[cell[i]];
            let measure = if dimension == 2 {
                triangle_area(p(0), p(1), p(2))
            } else {
                tetrahedron_volume(p(0), p(1), p(2), p(3))
            };
            if !(measure > 0.0 && measure.is_finite()) {
                return Err(Error::invalid(
                    format!("mesh.cells[{k}]"),
                    format!("{vertices:?}"),
                    "the cell is degenerate (zero area or volume)",
                ));
            }
            measures.push(measure);
        }
        Ok(Self {
            dimension,
            nodes,
            cells,
            measures,
        })
    }

    /// 2 (triangles, areas per unit thickness) or 3 (tetrahedra, volumes).
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// Number of nodes (one field value per node).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of simplices.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Node coordinates (x, y, z), m (z = 0 in 2D).
    pub fn nodes(&self) -> &[[f64; 3]] {
        &self.nodes
    }

    /// The vertices of cell `k` (3 in 2D, 4 in 3D).
    pub fn cell(&self, k: usize) -> &[usize] {
        &self.cells[k][..=self.dimension]
    }

    /// Total measure of the mesh: m^3 (3D) or m^2 per unit thickness (2D).
    pub fn total_measure(&self) -> f64 {
        let mut s = ExactSum::default();
        self.measures.iter().for_each(|&m| s.add(m));
        s.value()
    }

    /// The same mesh with its cells in the order `order` (a permutation of the cell
    /// indices), e.g. to check that results do not depend on the cell order.
    pub fn reordered(&self, order: &[usize]) -> Result<Self> {
        let mut seen = vec![false; self.cells.len()];
        if order.len() != self.cells.len()
            || order
                .iter()
                .any(|&k| k >= seen.len() || std::mem::replace(&mut seen[k], true))
        {
            return Err(Error::invalid(
                "order",
                format!("{} indices", order.len()),
                "must be a permutation of the cell indices",
            ));
        }
        Ok(Self {
            dimension: self.dimension,
            nodes: self.nodes.clone(),
            cells: order.iter().map(|&k| self.cells[k]).collect(),
            measures: order.iter().map(|&k| self.measures[k]).collect(),
        })
    }
}

/// The dangerous region of one relative-damage field psi: the paper's (22) and (24).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DangerousRegion {
    /// Dangerous volume V_q = integral over {psi_q >= 1} of dV (22): m^3 (3D) or m^2 per
    /// unit thickness (2D).
    pub volume: f64,
    /// Damageability Psi_q = integral over {psi_q >= 1} of psi_q dV (24, numerator; (35)
    /// for the effective energy): m^3 (3D) or m^2 (2D), psi being dimensionless.
    pub damageability: f64,
    /// Volume-averaged damageability Psi_q^(V_av) = Psi_q / V_q (24), dimensionless;
    /// `None` where there is no dangerous volume.
    pub average: Option<f64>,
    /// Largest psi_q over the nodes (the maximum of the piecewise-linear field).
    pub psi_max: f64,
    /// The node where psi_q is largest (lowest index among equal values).
    pub psi_max_node: usize,
    /// Its coordinates (x, y, z), m.
    pub psi_max_at: [f64; 3],
}

/// Measure fraction of {psi >= 1} in one simplex and the integral of psi over it divided by
/// the simplex measure, with psi linear (vertex values `psi`, 3 or 4 of them). Exact closed
/// form; see the derivation in the docs of [`super`].
pub(crate) fn clip_simplex(psi: &[f64]) -> (f64, f64) {
    let d = psi.len() - 1; // dimension
    let g: Vec<f64> = psi.iter().map(|v| v - 1.0).collect();
    let positive: Vec<usize> = (0..=d).filter(|&i| g[i] >= 0.0).collect();
    let negative: Vec<usize> = (0..=d).filter(|&i| g[i] < 0.0).collect();
    let mean = psi.iter().sum::<f64>() / (d + 1) as f64;
    let dd = d as f64;
    // Fraction of the corner simplex at vertex `c` cut off by psi = 1: product over the
    // other vertices j of t_j = g_c / (g_c - g_j) (the cut point along edge c-j).
    let corner = |c: usize, others: &[usize]| -> f64 {
        others.iter().map(|&j| g[c] / (g[c] - g[j])).product()
    };
    match (positive.len(), negative.len()) {
        (_, 0) => (1.0, mean),
        (0, _) => (0.0, 0.0),
        (1, _) => {
            let p = positive[0];
            let f = corner(p, &negative);
            // psi = psi_p at the vertex, 1 at the d cut points.
            (f, f * (psi[p] + dd) / (dd + 1.0))
        }
        (_, 1) => {
            let m = negative[0];
            let f = corner(m, &positive);
            (1.0 - f, mean - f * (psi[m] + dd) / (dd + 1.0))
        }
        _ => {
            // Tetrahedron with two vertices a, b where psi >= 1 and two c, e where psi < 1:
            // the region is a wedge with triangles (a, P_ac, P_ae) and (b, P_bc, P_be),
            // split into three tetrahedra; their volume fractions are the determinants of
            // their barycentric coordinates.
            let (a, b, c, e) = (positive[0], positive[1], negative[0], negative[1]);
            let vertex = |i: usize| {
                let mut x = [0.0; 4];
                x[i] = 1.0;
                x
            };
            let cut = |i: usize, j: usize| {
                let t = g[i] / (g[i] - g[j]);
                let mut x = [0.0; 4];
                x[i] = 1.0 - t;
                x[j] = t;
                x
            };
            let (a0, a1, a2) = (vertex(a), cut(a, c), cut(a, e));
            let (b0, b1, b2) = (vertex(b), cut(b, c), cut(b, e));
            let mut fraction = 0.0;
            let mut integral = 0.0;
            for (tet, vertex_psi) in [
                ([a0, a1, a2, b2], psi[a] + 3.0),
                ([a0, a1, b1, b2], psi[a] + 3.0),
                ([a0, b0, b1, b2], psi[a] + psi[b] + 2.0),
            ] {
                let f = det4(tet).abs();
                fraction += f;
                integral += f * vertex_psi / 4.0;
            }
            (fraction, integral)
        }
    }
}

fn det4(m: [[f64; 4]; 4]) -> f64 {
    let minor = |r: [usize; 3], c: [usize; 3]| {
        m[r[0]][c[0]] * (m[r[1]][c[1]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[1]])
            - m[r[0]][c[1]] * (m[r[1]][c[0]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[0]])
            + m[r[0]][c[2]] * (m[r[1]][c[0]] * m[r[2]][c[1]] - m[r[1]][c[1]] * m[r[2]][c[0]])
    };
    let rows = [1, 2, 3];
    m[0][0] * minor(rows, [1, 2, 3]) - m[0][1] * minor(rows, [0, 2, 3])
        + m[0][2] * minor(rows, [0, 1, 3])
        - m[0][3] * minor(rows, [0, 1, 2])
}

fn check_nodal(mesh: &DamageMesh, psi: &[f64]) -> Result<()> {
    if psi.len() != mesh.node_count() {
        return Err(Error::invalid(
            "psi",
            format!("{} values", psi.len()),
            format!("needs one value per mesh node ({})", mesh.node_count()),
        ));
    }
    if let Some(k) = psi.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            format!("psi[{k}]"),
            psi[k],
            "relative damage must be finite",
        ));
    }
    Ok(())
}

/// Exact sums of (measure, integral of psi) over {psi >= 1}.
fn integrate(mesh: &DamageMesh, psi: &[f64], execution: Execution) -> (ExactSum, ExactSum) {
    let d = mesh.dimension;
    let chunk_sums = |range: std::ops::Range<usize>| {
        let (mut volume, mut integral) = (ExactSum::default(), ExactSum::default());
        let mut values = [0.0; 4];
        for k in range {
            let cell = &mesh.cells[k];
            for i in 0..=d {
                values[i] = psi[cell[i]];
            }
            let (f, int) = clip_simplex(&values[..=d]);
            if f > 0.0 {
                volume.add(f * mesh.measures[k]);
                integral.add(int * mesh.measures[k]);
            }
        }
        (volume, integral)
    };
    let n = mesh.cells.len();
    let ranges: Vec<_> = (0..n.div_ceil(CHUNK))
        .map(|c| c * CHUNK..((c + 1) * CHUNK).min(n))
        .collect();
    let parts: Vec<(ExactSum, ExactSum)> = match execution {
        Execution::Serial => ranges.into_iter().map(chunk_sums).collect(),
        Execution::Parallel => ranges.into_par_iter().map(chunk_sums).collect(),
    };
    let (mut volume, mut integral) = (ExactSum::default(), ExactSum::default());
    for (v, i) in &parts {
        volume.merge(v);
        integral.merge(i);
    }
    (volume, integral)
}

/// The dangerous region of the nodal relative damage `psi` (one value per node,
/// dimensionless), psi linear on each simplex: V = measure of {psi >= 1} (22),
/// Psi = integral of psi over it and Psi / V (24), each cell cut by the psi = 1 surface
/// counted exactly by its part (second-order accurate for a smooth psi, exact for a psi
/// linear on each cell). The result does not depend on the cell order nor on `execution`
/// (exactly rounded sums).
pub fn dangerous_region(
    mesh: &DamageMesh,
    psi: &[f64],
    execution: Execution,
) -> Result<DangerousRegion> {
    check_nodal(mesh, psi)?;
    let (volume, integral) = integrate(mesh, psi, execution);
    let (volume, damageability) = (volume.value(), integral.value());
    let mut best = 0;
    for (i, &v) in psi.iter().enumerate() {
        if v > psi[best] {
            best = i;
        }
    }
    Ok(DangerousRegion {
        volume,
        damageability,
        average: (volume > 0.0).then(|| damageability / volume),
        psi_max: psi[best],
        psi_max_node: best,
        psi_max_at: mesh.nodes[best],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (64-bit LCG, Knuth's MMIX constants) in [0, 1).
    pub(crate) struct Lcg(pub u64);
    impl Lcg {
        pub(crate) fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn clipped_parts_add_up_to_the_simplex() {
        // {psi >= 1} and {psi < 1} = {2 - psi > 1} partition the simplex: the fractions add
        // to 1 and the integrals of psi to the mean (round-off only, 1e-13). Random values
        // straddling 1 exercise every case (1, 2, 3 vertices above), the wedge included.
        let mut rng = Lcg(7);
        for d in [2usize, 3] {
            for _ in 0..2000 {
                let psi: Vec<f64> = (0..=d).map(|_| 0.2 + 1.6 * rng.next()).collect();
                let flipped: Vec<f64> = psi.iter().map(|v| 2.0 - v).collect();
                let (f1, i1) = clip_simplex(&psi);
                let (f2, i2) = clip_simplex(&flipped);
                assert!((f1 + f2 - 1.0).abs() < 1e-13, "{psi:?}");
                assert!((0.0..=1.0).contains(&f1));
                // Integral of psi over the complement: 2 f2 - (integral of 2 - psi there).
                let mean = psi.iter().sum::<f64>() / (d + 1) as f64;
                assert!((i1 + 2.0 * f2 - i2 - mean).abs() < 1e-13, "{psi:?}");
            }
        }
    }

    #[test]
    fn clipped_wedge_matches_monte_carlo() {
        // Independent check of the wedge case against sampling the reference tetrahedron
        // (uniform barycentric points): 4e5 samples, standard error ~ 0.5/sqrt(4e5) < 1e-3,
        // tolerance 4e-3 (4 sigma).
        let psi = [1.7, 1.2, 0.4, 0.9];
        let (f, i) = clip_simplex(&psi);
        let mut rng = Lcg(11);
        let (mut count, mut sum) = (0.0, 0.0);
        let n = 400_000;
        for _ in 0..n {
            // Uniform point in the simplex: sorted uniforms' spacings.
            let mut u = [rng.next(), rng.next(), rng.next()];
            u.sort_by(f64::total_cmp);
            let l = [u[0], u[1] - u[0], u[2] - u[1], 1.0 - u[2]];
            let v: f64 = l.iter().zip(&psi).map(|(a, b)| a * b).sum();
            if v >= 1.0 {
                count += 1.0;
                sum += v;
            }
        }
        assert!((count / n as f64 - f).abs() < 4e-3, "{f}");
        assert!((sum / n as f64 - i).abs() < 4e-3, "{i}");
    }

    #[test]
    fn kuhn_mesh_fills_the_box() {
        let grid = FieldGrid {
            x: vec![0.0, 0.1, 0.35, 1.0],
            y: vec![-1.0, 0.5, 2.0],
            z: vec![0.0, 0.2, 0.7],
        };
        let mesh = DamageMesh::from_field_grid(&grid).unwrap();
        assert_eq!(mesh.cell_count(), 6 * 3 * 2 * 2);
        assert!((mesh.total_measure() - 3.0 * 0.7).abs() < 1e-14);
        let m2 = DamageMesh::structured_2d(&[0.0, 1.0, 3.0], &[0.0, 2.0]).unwrap();
        assert_eq!(m2.cell_count(), 4);
        assert!((m2.total_measure() - 6.0).abs() < 1e-15);
    }

    #[test]
    fn bad_meshes_and_fields_are_named() {
        let bad = FieldGrid {
            x: vec![0.0, 0.0],
            y: vec![0.0, 1.0],
            z: vec![0.0, 1.0],
        };
        let err = DamageMesh::from_field_grid(&bad).unwrap_err().to_string();
        assert!(err.starts_with("field.x"), "{err}");
        let err = DamageMesh::triangles(vec![[0.0, 0.0], [1.0, 0.0]], vec![[0, 1, 2]])
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("mesh.cells[0]"), "{err}");
        let err = DamageMesh::triangles(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![[0, 1, 2]])
            .unwrap_err()
            .to_string();
        assert!(err.contains("degenerate"), "{err}");
        let mesh = DamageMesh::structured_2d(&[0.0, 1.0], &[0.0, 1.0]).unwrap();
        assert!(dangerous_region(&mesh, &[1.0; 3], Execution::Serial).is_err());
        let err = dangerous_region(&mesh, &[1.0, f64::NAN, 1.0, 1.0], Execution::Serial)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("psi[1]"), "{err}");
        assert!(mesh.reordered(&[0, 0]).is_err());
    }
}
