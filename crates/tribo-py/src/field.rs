//! The stress field under a contact and the damage measures on it, on arrays: the library's
//! field paths (direct sum, FFT + interpolation, FFT on the element centres, each with the
//! edge band or refined tractions, as `[field]` chooses them in a case), the named point
//! arrays of the CLI's `stress.vti` ([`tribo_case::derived::stress_arrays`], the same
//! function), psi_q (21), V_q (22), Psi_q (24) and the energy criterion (34), (35).
//!
//! Arrays of points have the shape (nz, ny, nx): x fastest, the layout of
//! [`FieldGrid::index`].

use numpy::{
    PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::Instant;
use tribo::analysis::damage::{dangerous_region, relative_damage, DamageMesh, Execution, Limit};
use tribo::analysis::edge_refinement::{refine_tractions, EdgeBand};
use tribo::analysis::energy_criterion::{EnergyCoefficients, EnergyCriterion, Temperature};
use tribo::analysis::stress_field::{
    stress_field_direct, stress_field_direct_banded, stress_field_interpolated,
    stress_field_interpolated_banded, stress_field_on_centres_banded,
    stress_field_on_centres_observed, FieldGrid, StressField, SurfaceTractions,
};
use tribo::kernels::subsurface::StressTensor;
use tribo::{ElasticMaterial, SurfaceGrid};
use tribo_case::halfspace::{damage_vocabulary, EDGE_REFINEMENT_BAND};
use tribo_case::pipeline::{FieldBody, FieldEvaluation, Stress, EDGE_BAND_FACTOR};

use crate::{input_error, library_error, SolverError};

/// The named point arrays of a stress field (those of `stress.vti`), each of shape
/// (nz, ny, nx), into `d`, with the coordinates `x`, `y`, `z` (m).
pub(crate) fn stress_dict<'py>(
    py: Python<'py>,
    st: &Stress,
    d: &Bound<'py, PyDict>,
) -> PyResult<()> {
    let g = &st.field.grid;
    let shape = [g.z.len(), g.y.len(), g.x.len()];
    for (name, values) in tribo_case::derived::stress_arrays(st) {
        d.set_item(name, PyArray1::from_vec(py, values).reshape(shape)?)?;
    }
    d.set_item("x", PyArray1::from_vec(py, g.x.clone()))?;
    d.set_item("y", PyArray1::from_vec(py, g.y.clone()))?;
    d.set_item("z", PyArray1::from_vec(py, g.z.clone()))?;
    d.set_item("method", st.method.text())?;
    d.set_item("edge_refinement", edge_text(st.edge_refinement))?;
    d.set_item("body", st.body.name())?;
    d.set_item("youngs_modulus", st.material.youngs_modulus())?;
    d.set_item("poisson_ratio", st.material.poisson_ratio())?;
    d.set_item("bulk", st.bulk.map(|(kind, sigma)| (kind.name(), sigma)))?;
    d.set_item("time_s", st.time_s)?;
    Ok(())
}

/// The text of `field.edge_refinement`: "band", "none" (1) or "xN".
fn edge_text(factor: usize) -> String {
    match factor {
        EDGE_REFINEMENT_BAND => "band".into(),
        1 => "none".into(),
        n => format!("x{n}"),
    }
}

/// A C-contiguous (ny, nx) float64 array's values, or an [`crate::InputError`] naming it.
fn grid_values<'a>(
    py: Python<'_>,
    name: &str,
    a: &'a PyReadonlyArray2<'_, f64>,
    shape: [usize; 2],
) -> PyResult<&'a [f64]> {
    if a.shape() != shape {
        return Err(input_error(
            py,
            format!("{name}: shape {:?}, the pressure's is {shape:?}", a.shape()),
            name,
            &format!("{:?}", a.shape()),
            "the shape (ny, nx) of the pressure",
        ));
    }
    a.as_slice().map_err(|_| {
        input_error(
            py,
            format!("{name}: the array must be C-contiguous"),
            name,
            "non-contiguous array",
            "C-contiguous float64 of shape (ny, nx)",
        )
    })
}

/// Coordinates of field points: non-empty, finite (and for `z` >= 0), m.
fn check_points(py: Python<'_>, name: &str, v: &[f64], depth: bool) -> PyResult<()> {
    let bad = v
        .iter()
        .find(|c| !c.is_finite() || (depth && **c < 0.0))
        .copied();
    if v.is_empty() || bad.is_some() {
        let rule = if depth {
            "depths finite and >= 0 (m), at least one"
        } else {
            "finite coordinates (m), at least one"
        };
        let value = bad.map_or("empty".to_string(), |b| b.to_string());
        return Err(input_error(
            py,
            format!("{name} = {value}: {rule}"),
            name,
            &value,
            rule,
        ));
    }
    Ok(())
}

/// The stress field in the body of Young's modulus E and Poisson's ratio nu under the
/// element tractions `pressure`, `traction_x`, `traction_y` (Pa, shape (ny, nx), C-contiguous
/// float64, on the window `size = (Lx, Ly)`, m, centred on the origin), at the points
/// x (nx,) x y (ny,) x z (nz,) (m, z >= 0 the depth), or with `x`, `y` None at the element
/// centres at the depths `z`. `method`: "direct" (the direct sum, exact at any point) or
/// "fft" (FFT on the extended grid + cubic interpolation); `edge_refinement`: 0 the edge
/// band, 1 the bilinear element tractions, N in [2, 16] the edge-aware tractions N times
/// finer (docs/theory/HALFSPACE.md 2.5). A dict of the named arrays (shape (nz, ny, nx)), the
/// coordinates and the method's description.
#[pyfunction]
#[pyo3(signature = (pressure, size, material, z, x=None, y=None, traction_x=None, traction_y=None, method="direct", edge_refinement=EDGE_REFINEMENT_BAND))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn stress_field<'py>(
    py: Python<'py>,
    pressure: PyReadonlyArray2<'py, f64>,
    size: (f64, f64),
    material: (f64, f64),
    z: Vec<f64>,
    x: Option<Vec<f64>>,
    y: Option<Vec<f64>>,
    traction_x: Option<PyReadonlyArray2<'py, f64>>,
    traction_y: Option<PyReadonlyArray2<'py, f64>>,
    method: &str,
    edge_refinement: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let lib = |e: tribo::Error| library_error(py, &e);
    let shape = [pressure.shape()[0], pressure.shape()[1]];
    let grid = SurfaceGrid::centred(shape[1], shape[0], 0.5 * size.0, 0.5 * size.1).map_err(lib)?;
    let body = ElasticMaterial::named("body", material.0, material.1).map_err(lib)?;
    let p = grid_values(py, "pressure", &pressure, shape)?;
    let qx = match &traction_x {
        Some(a) => Some(grid_values(py, "traction_x", a, shape)?),
        None => None,
    };
    let qy = match &traction_y {
        Some(a) => Some(grid_values(py, "traction_y", a, shape)?),
        None => None,
    };
    let fft = match method {
        "direct" => false,
        "fft" => true,
        other => {
            return Err(input_error(
                py,
                format!("method = {other:?}: one of \"direct\", \"fft\""),
                "method",
                other,
                "one of \"direct\", \"fft\"",
            ))
        }
    };
    if edge_refinement > 16 {
        return Err(input_error(
            py,
            format!("edge_refinement = {edge_refinement}: \"band\", or an integer in [1, 16]"),
            "edge_refinement",
            &edge_refinement.to_string(),
            "\"band\", or an integer in [1, 16]",
        ));
    }
    check_points(py, "z", &z, true)?;
    let points = match (x, y) {
        (Some(x), Some(y)) => {
            check_points(py, "x", &x, false)?;
            check_points(py, "y", &y, false)?;
            Some(FieldGrid { x, y, z: z.clone() })
        }
        (None, None) => None,
        _ => {
            return Err(input_error(
                py,
                "give both x and y (m), or neither (the element centres)".into(),
                "x",
                "",
                "both x and y, or neither",
            ))
        }
    };
    let tractions = SurfaceTractions {
        grid: &grid,
        pressure: p,
        shear_x: qx,
        shear_y: qy,
    };
    let nu = body.poisson_ratio();
    let factor = edge_refinement;
    let evaluation = match (&points, fft) {
        (Some(_), false) => FieldEvaluation::DirectSum,
        (Some(_), true) => FieldEvaluation::FftInterpolated,
        (None, _) if factor > 1 => FieldEvaluation::FftInterpolated,
        (None, _) => FieldEvaluation::FftCentres,
    };
    // The dispatch of tribo_case::pipeline::stress (the case's `[field]`), on given points.
    let computed = py.detach(|| -> tribo::Result<(StressField, f64)> {
        let start = Instant::now();
        let refined = if factor > 1 {
            Some(refine_tractions(&tractions, factor)?)
        } else {
            None
        };
        let t = refined.as_ref().map_or(tractions, |r| r.tractions());
        let band = if factor == EDGE_REFINEMENT_BAND {
            Some(EdgeBand::new(&tractions, EDGE_BAND_FACTOR)?)
        } else {
            None
        };
        let field = match (&points, &band) {
            (Some(g), Some(b)) if fft => stress_field_interpolated_banded(b, nu, g, |_| {})?,
            (Some(g), None) if fft => stress_field_interpolated(&t, nu, g, |_| {})?,
            (Some(g), Some(b)) => stress_field_direct_banded(b, nu, g)?,
            (Some(g), None) => stress_field_direct(&t, nu, g)?,
            (None, _) if refined.is_some() => {
                let g = FieldGrid {
                    x: (0..grid.nx()).map(|i| grid.x(i)).collect(),
                    y: (0..grid.ny()).map(|j| grid.y(j)).collect(),
                    z: z.clone(),
                };
                stress_field_interpolated(&t, nu, &g, |_| {})?
            }
            (None, Some(b)) => stress_field_on_centres_banded(b, nu, &z, |_| {})?,
            (None, None) => stress_field_on_centres_observed(&t, nu, &z, |_| {})?,
        };
        Ok((field, start.elapsed().as_secs_f64()))
    });
    let (field, time_s) = computed.map_err(lib)?;
    let st = Stress {
        field,
        body: FieldBody::Body1,
        material: body,
        bulk: None,
        method: evaluation,
        edge_refinement: factor,
        time_s,
    };
    let d = PyDict::new(py);
    stress_dict(py, &st, &d)?;
    d.del_item("body")?;
    Ok(d)
}

/// The stress tensors of the six component arrays (Pa, one shape, any layout numpy gives).
fn tensors(
    py: Python<'_>,
    components: [PyReadonlyArrayDyn<'_, f64>; 6],
) -> PyResult<Vec<StressTensor>> {
    let n = components[0].len();
    let names = [
        "sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_yz", "sigma_xz",
    ];
    for (c, name) in components.iter().zip(names) {
        if c.len() != n {
            return Err(input_error(
                py,
                format!("{name}: {} values, sigma_xx has {n}", c.len()),
                name,
                &c.len().to_string(),
                "the same number of values as sigma_xx",
            ));
        }
    }
    let views: Vec<_> = components.iter().map(|c| c.as_array()).collect();
    let iters: Vec<Vec<f64>> = views.iter().map(|v| v.iter().copied().collect()).collect();
    Ok((0..n)
        .map(|k| {
            StressTensor::new(
                iters[0][k],
                iters[1][k],
                iters[2][k],
                iters[3][k],
                iters[4][k],
                iters[5][k],
            )
        })
        .collect())
}

/// The mesh of a tensor-product field grid (the case's, [`DamageMesh::from_field_grid`]).
fn field_mesh(
    py: Python<'_>,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    n: usize,
) -> PyResult<DamageMesh> {
    let grid = FieldGrid { x, y, z };
    if grid.len() != n {
        return Err(input_error(
            py,
            format!(
                "the stresses have {n} values, the grid x, y, z {} points",
                grid.len()
            ),
            "sigma_xx",
            &n.to_string(),
            "one value per point of x x y x z (shape (nz, ny, nx))",
        ));
    }
    DamageMesh::from_field_grid(&grid).map_err(|e| library_error(py, &e))
}

/// The JSON text of a serializable library result.
fn json<T: serde::Serialize>(v: &T) -> PyResult<String> {
    serde_json::to_string(v).map_err(|e| SolverError::new_err(e.to_string()))
}

/// The damage of one criterion on a field given by its six stress components (Pa, shape
/// (nz, ny, nx)) at the points x (nx,), y (ny,), z (nz,) (m), in the body (E, nu): psi_q =
/// phi_q / limit (21) at every point (shape (nz, ny, nx)) and the dangerous region as JSON
/// (V_q (22), Psi_q, Psi_q / V_q (24), psi_max and where). `name`: a criterion of
/// `damage.criteria` (docs/user/case-halfspace.md); `limit` in its unit.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn damage<'py>(
    py: Python<'py>,
    components: [PyReadonlyArrayDyn<'py, f64>; 6],
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    material: (f64, f64),
    name: &str,
    limit: f64,
) -> PyResult<(Bound<'py, PyAny>, String, String)> {
    let lib = |e: tribo::Error| library_error(py, &e);
    let shape = [z.len(), y.len(), x.len()];
    let vocabulary = damage_vocabulary();
    let Some(quantity) = vocabulary.iter().find(|q| q.name() == name).copied() else {
        let known: Vec<_> = vocabulary.iter().map(|q| q.name()).collect();
        return Err(input_error(
            py,
            format!(
                "criterion {name:?}: unknown quantity; known: {}",
                known.join(", ")
            ),
            "criterion",
            name,
            &format!("one of {}", known.join(", ")),
        ));
    };
    let body = ElasticMaterial::named("body", material.0, material.1).map_err(lib)?;
    let limit = Limit::new(quantity, limit).map_err(lib)?;
    let stress = tensors(py, components)?;
    let mesh = field_mesh(py, x, y, z, stress.len())?;
    let (psi, region) = py
        .detach(|| -> tribo::Result<_> {
            let psi = relative_damage(&limit, &stress, &body)?;
            let region = dangerous_region(&mesh, &psi, Execution::Parallel)?;
            Ok((psi, region))
        })
        .map_err(lib)?;
    let arr = PyArray1::from_vec(py, psi).reshape(shape)?.into_any();
    Ok((arr, json(&region)?, quantity.unit().to_string()))
}

/// The energy criterion (25), (33)-(35) on a field given as for [`damage`]: psi_u^eff =
/// u_Sigma^eff / u0 (34) at every point (shape (nz, ny, nx)), and as JSON V_u, Psi_u^(eff),
/// their ratio (35) and psi_max with where. `coefficients` = (A_n, A_tau, A_T (1/m^3),
/// A_tau\n, A_M\T); `u0` J/m^3; `temperature` K, one value or one per point.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn energy_damage<'py>(
    py: Python<'py>,
    components: [PyReadonlyArrayDyn<'py, f64>; 6],
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    material: (f64, f64),
    u0: f64,
    coefficients: (f64, f64, f64, f64, f64),
    temperature: Vec<f64>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let lib = |e: tribo::Error| library_error(py, &e);
    let shape = [z.len(), y.len(), x.len()];
    let body = ElasticMaterial::named("body", material.0, material.1).map_err(lib)?;
    let c = EnergyCoefficients {
        a_n: coefficients.0,
        a_tau: coefficients.1,
        a_t: coefficients.2,
        a_tau_n: coefficients.3,
        a_m_t: coefficients.4,
    };
    let criterion = EnergyCriterion::new(c, u0).map_err(lib)?;
    let temperature = match temperature.as_slice() {
        [t] => Temperature::Uniform(*t),
        _ => Temperature::Field(temperature),
    };
    let stress = tensors(py, components)?;
    let mesh = field_mesh(py, x, y, z, stress.len())?;
    let (psi, damage) = py
        .detach(|| -> tribo::Result<_> {
            let psi = criterion.psi_field(&stress, &body, &temperature)?;
            let damage =
                criterion.assess(&mesh, &stress, &body, &temperature, Execution::Parallel)?;
            Ok((psi, damage))
        })
        .map_err(lib)?;
    let arr = PyArray1::from_vec(py, psi).reshape(shape)?.into_any();
    Ok((arr, json(&damage)?))
}
