//! The compiled module `tribo._tribo` of the Python package `tribo` (python/tribo/): PyO3
//! bindings over the physics library `tribo`, the case library `tribo-case` and the study
//! engine `tribo-study` (src/study.rs). The typed, documented Python API is
//! python/tribo/__init__.py (and python/tribo/study.py); this module is its private core.
//!
//! Rules kept here:
//! - no copy of the pipeline: cases run through [`tribo_case::run`], their files are written by
//!   [`tribo_io`], their summaries are the ones `tribo run --json` prints;
//! - arrays cross without copies where the layout allows: inputs are read in place when they
//!   are C-contiguous float64 (the Python layer converts anything else), outputs are vectors
//!   handed over to numpy;
//! - long computations run with the interpreter released ([`Python::detach`]), so other Python
//!   threads go on meanwhile;
//! - errors become exceptions: [`InputError`] (a `ValueError` carrying the field, the value and
//!   the rule) for bad input, [`ConvergenceError`] (carrying the residual) for a solver stopped
//!   before its tolerance, [`SolverError`] for the rest.

use numpy::{
    PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::PathBuf;
use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::kernels::periodic::PeriodicKernel;
use tribo::operators::ConvolutionOperator;
use tribo::solvers::coupled::{solve_coupled, CoupledParams, CoupledProblem, TangentialModel};
use tribo::solvers::normal::{
    normal_compliance_operator, normal_compliance_operator_periodic, solve_normal_from,
    NormalContactParams, NormalContactProblem, NormalContactSolution, NormalLoading, NormalMethod,
};
use tribo::solvers::tangential::{
    solve_tangential, tangential_compliance_operator_periodic, TangentialLoading, TangentialParams,
    TangentialProblem, TangentialSolution,
};
use tribo::solvers::tangential_free::{solve_tangential_free, TangentialBlockOperator};
use tribo::SurfaceGrid;
use tribo_case::{CaseError, Silent};

mod fatigue;
mod field;
mod study;
mod surface;

create_exception!(
    _tribo,
    InputError,
    PyValueError,
    "Bad input: a field breaking a rule. Attributes: `field` (dotted name), `value`, `rule`."
);
create_exception!(
    _tribo,
    ConvergenceError,
    PyRuntimeError,
    "A solver stopped before reaching its tolerance. Attributes: `solver`, `iterations`, \
     `residual` (the solver's documented measure), `tolerance`."
);
create_exception!(
    _tribo,
    SolverError,
    PyRuntimeError,
    "A failure of the computation other than non-convergence (a numerical breakdown, an \
     output that could not be written)."
);

/// An [`InputError`] with its attributes set.
pub(crate) fn input_error(
    py: Python<'_>,
    message: String,
    field: &str,
    value: &str,
    rule: &str,
) -> PyErr {
    let err = InputError::new_err(message);
    let value_obj = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail but for memory.
    let _ = value_obj.setattr("field", field);
    let _ = value_obj.setattr("value", value);
    let _ = value_obj.setattr("rule", rule);
    err
}

/// The exception of a library error.
pub(crate) fn library_error(py: Python<'_>, e: &tribo::Error) -> PyErr {
    match e {
        tribo::Error::InvalidParameter { field, value, rule } => {
            input_error(py, e.to_string(), field, value, rule)
        }
        tribo::Error::NotConverged {
            solver,
            iterations,
            residual,
            tolerance,
        } => {
            let err = ConvergenceError::new_err(e.to_string());
            let v = err.value(py);
            let _ = v.setattr("solver", *solver);
            let _ = v.setattr("iterations", *iterations);
            let _ = v.setattr("residual", *residual);
            let _ = v.setattr("tolerance", *tolerance);
            err
        }
        _ if CaseError::Library(clone_kind(e)).is_bad_input() => {
            input_error(py, e.to_string(), "", "", &e.to_string())
        }
        _ => SolverError::new_err(e.to_string()),
    }
}

/// The variants [`CaseError::is_bad_input`] looks at, rebuilt (the library error is not
/// `Clone`); the others map to a numerical error, which is not bad input.
fn clone_kind(e: &tribo::Error) -> tribo::Error {
    match e {
        tribo::Error::ContactReachesWindow { .. } | tribo::Error::NoContact { .. } => {
            tribo::Error::invalid("", "", "")
        }
        _ => tribo::Error::NotConverged {
            solver: "",
            iterations: 0,
            residual: 0.0,
            tolerance: 0.0,
        },
    }
}

/// The exception of a case error (the field-named rule, the parser's message, a file).
pub(crate) fn case_error(py: Python<'_>, e: &CaseError) -> PyErr {
    match e {
        CaseError::Library(inner) => library_error(py, inner),
        CaseError::Field { field, value, rule } => {
            input_error(py, e.to_string(), field, value, rule)
        }
        CaseError::Unreadable { field, path, .. } | CaseError::DataFile { field, path, .. } => {
            input_error(
                py,
                e.to_string(),
                field,
                &path.display().to_string(),
                &e.to_string(),
            )
        }
        _ => input_error(py, e.to_string(), "", "", &e.to_string()),
    }
}

/// The exception of a writer's error.
fn io_error(e: &tribo_io::IoError) -> PyErr {
    SolverError::new_err(e.to_string())
}

// ----------------------------------------------------------------------------------------
// Hertz
// ----------------------------------------------------------------------------------------

/// The exact Hertz solution of an elliptical (or circular) contact (Johnson 1985, ch. 4;
/// docs/theory/HALFSPACE.md 3.1). Lengths in m, pressures and moduli in Pa, force in N,
/// angles in rad.
#[pyclass(module = "tribo._tribo", name = "HertzContact", frozen)]
struct PyHertz {
    inner: HertzContact,
}

#[pymethods]
impl PyHertz {
    /// Long semi-axis a of the contact ellipse, m.
    #[getter]
    fn semi_major(&self) -> f64 {
        self.inner.semi_major
    }
    /// Short semi-axis b, m (= a for a circular contact).
    #[getter]
    fn semi_minor(&self) -> f64 {
        self.inner.semi_minor
    }
    /// Contact radius sqrt(a b), m (the radius for a circular contact).
    #[getter]
    fn radius(&self) -> f64 {
        (self.inner.semi_major * self.inner.semi_minor).sqrt()
    }
    /// Maximum pressure p0 = 3 F / (2 pi a b), Pa.
    #[getter]
    fn max_pressure(&self) -> f64 {
        self.inner.max_pressure
    }
    /// Mean pressure F / (pi a b), Pa.
    #[getter]
    fn mean_pressure(&self) -> f64 {
        self.inner.normal_load / self.inner.contact_area()
    }
    /// Approach of distant points delta, m.
    #[getter]
    fn approach(&self) -> f64 {
        self.inner.approach
    }
    /// Normal load F, N.
    #[getter]
    fn normal_load(&self) -> f64 {
        self.inner.normal_load
    }
    /// Contact area pi a b, m^2.
    #[getter]
    fn contact_area(&self) -> f64 {
        self.inner.contact_area()
    }
    /// Angle from the x axis to the long semi-axis, rad.
    #[getter]
    fn angle(&self) -> f64 {
        self.inner.angle
    }
    /// Composite modulus E*, Pa.
    #[getter]
    fn composite_modulus(&self) -> f64 {
        self.inner.composite_modulus
    }
    /// The pressure p0 sqrt(1 - x'^2/a^2 - y'^2/b^2) at points (x, y) (m; arrays of one
    /// shape, float64), Pa; 0 outside the ellipse.
    fn pressure<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArrayDyn<'py, f64>,
        y: PyReadonlyArrayDyn<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if x.shape() != y.shape() {
            return Err(input_error(
                py,
                format!(
                    "x and y have different shapes: {:?} and {:?}",
                    x.shape(),
                    y.shape()
                ),
                "y",
                &format!("{:?}", y.shape()),
                "x and y must have the same shape",
            ));
        }
        let shape = x.shape().to_vec();
        let xs = x.as_array();
        let ys = y.as_array();
        let p: Vec<f64> = xs
            .iter()
            .zip(ys.iter())
            .map(|(&x, &y)| self.inner.pressure(x, y))
            .collect();
        Ok(PyArray1::from_vec(py, p).reshape(shape)?.into_any())
    }
    fn __repr__(&self) -> String {
        format!(
            "HertzContact(semi_major={:e} m, semi_minor={:e} m, max_pressure={:e} Pa, \
             approach={:e} m, normal_load={:e} N)",
            self.inner.semi_major,
            self.inner.semi_minor,
            self.inner.max_pressure,
            self.inner.approach,
            self.inner.normal_load
        )
    }
}

/// Hertz contact of two bodies given by their principal radii (m; positive convex, negative
/// concave, inf flat), `angle_between` their principal planes (rad), the composite modulus
/// (Pa) and exactly one of the load (N) or the approach (m).
#[pyfunction]
#[pyo3(signature = (radii1, radii2, angle_between, composite_modulus, load=None, approach=None))]
fn hertz(
    py: Python<'_>,
    radii1: [f64; 2],
    radii2: [f64; 2],
    angle_between: f64,
    composite_modulus: f64,
    load: Option<f64>,
    approach: Option<f64>,
) -> PyResult<PyHertz> {
    let lib = |e: tribo::Error| library_error(py, &e);
    let curvature = GapCurvature::from_radii(radii1, radii2, angle_between).map_err(lib)?;
    let inner = match (load, approach) {
        (Some(f), None) => HertzContact::from_load(&curvature, composite_modulus, f),
        (None, Some(d)) => HertzContact::from_approach(&curvature, composite_modulus, d),
        _ => {
            return Err(input_error(
                py,
                "give exactly one of load (N) and approach (m)".into(),
                "load",
                &format!("{load:?}"),
                "exactly one of load and approach",
            ))
        }
    }
    .map_err(lib)?;
    Ok(PyHertz { inner })
}

/// The composite modulus E* of two bodies, Pa: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
/// (Johnson 1985 eq. (4.22)).
#[pyfunction]
fn composite_modulus(py: Python<'_>, e1: f64, nu1: f64, e2: f64, nu2: f64) -> PyResult<f64> {
    let m1 = tribo::ElasticMaterial::named("body1", e1, nu1).map_err(|e| library_error(py, &e))?;
    let m2 = tribo::ElasticMaterial::named("body2", e2, nu2).map_err(|e| library_error(py, &e))?;
    Ok(tribo::composite_modulus(&m1, &m2))
}

// ----------------------------------------------------------------------------------------
// Normal contact on a grid
// ----------------------------------------------------------------------------------------

/// A field of the grid as a numpy array of shape (ny, nx), without a copy.
fn grid_array<'py>(
    py: Python<'py>,
    v: Vec<f64>,
    grid: &SurfaceGrid,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, v)
        .reshape([grid.ny(), grid.nx()])?
        .into_any())
}

/// The solution of a normal contact problem as a dict of numpy arrays and floats.
fn normal_dict<'py>(
    py: Python<'py>,
    s: NormalContactSolution,
    grid: &SurfaceGrid,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("approach", s.approach)?;
    d.set_item("normal_load", s.normal_load)?;
    d.set_item("contact_area", s.contact_area)?;
    d.set_item("contact_elements", s.contact_elements)?;
    d.set_item("iterations", s.iterations)?;
    d.set_item("residual", s.residual)?;
    d.set_item("pressure", grid_array(py, s.pressure, grid)?)?;
    d.set_item("gap", grid_array(py, s.gap, grid)?)?;
    let xs: Vec<f64> = (0..grid.nx()).map(|i| grid.x(i)).collect();
    let ys: Vec<f64> = (0..grid.ny()).map(|j| grid.y(j)).collect();
    d.set_item("x", PyArray1::from_vec(py, xs))?;
    d.set_item("y", PyArray1::from_vec(py, ys))?;
    Ok(d)
}

/// The loading of a normal solve from its two optional arguments.
fn normal_loading(
    py: Python<'_>,
    load: Option<f64>,
    approach: Option<f64>,
) -> PyResult<NormalLoading> {
    match (load, approach) {
        (Some(f), None) => Ok(NormalLoading::Force(f)),
        (None, Some(d)) => Ok(NormalLoading::Approach(d)),
        _ => Err(input_error(
            py,
            "give exactly one of load (N) and approach (m)".into(),
            "load",
            &format!("{load:?}"),
            "exactly one of load and approach",
        )),
    }
}

/// The solver's parameters from the arguments of a call.
fn normal_params(
    py: Python<'_>,
    tolerance: f64,
    max_iterations: usize,
    method: &str,
) -> PyResult<NormalContactParams> {
    let method = match method {
        "cg" | "conjugate_gradient" => NormalMethod::ConjugateGradient,
        "active_set" => NormalMethod::ActiveSet,
        other => {
            return Err(input_error(
                py,
                format!("method = {other:?}: one of \"cg\", \"active_set\""),
                "method",
                other,
                "one of \"cg\", \"active_set\"",
            ))
        }
    };
    let params = NormalContactParams {
        tolerance,
        max_iterations,
        method,
        ..NormalContactParams::default()
    };
    params.validate().map_err(|e| library_error(py, &e))?;
    Ok(params)
}

/// The periodic kernel of `periodic=True` solves: `None` for a non-periodic solve, else the
/// kernel named by `kernel` ("element" (or "element_integrated"): the periodic sum of Love's
/// element influence, the default; "spectral": the continuous multiplier at the grid
/// frequencies, Tamaas's; docs/theory/HALFSPACE.md 7.1).
fn periodic_kernel(
    py: Python<'_>,
    periodic: bool,
    kernel: &str,
) -> PyResult<Option<PeriodicKernel>> {
    let k = match kernel {
        "element" | "element_integrated" => PeriodicKernel::ElementIntegrated,
        "spectral" => PeriodicKernel::Spectral,
        other => {
            return Err(input_error(
                py,
                format!("kernel = {other:?}: one of \"element\", \"spectral\""),
                "kernel",
                other,
                "one of \"element\", \"spectral\"",
            ))
        }
    };
    Ok(periodic.then_some(k))
}

/// One normal solve on `grid` with the gap read in place and the interpreter released; the
/// result dict carries `solve_time_s`, the solve's own wall time.
#[allow(clippy::too_many_arguments)]
fn normal_solve<'py>(
    py: Python<'py>,
    grid: &SurfaceGrid,
    gap: &PyReadonlyArray2<'py, f64>,
    composite_modulus: f64,
    loading: NormalLoading,
    params: &NormalContactParams,
    operator: Option<&ConvolutionOperator>,
    initial_pressure: Option<&PyReadonlyArray2<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = gap.shape();
    if shape != [grid.ny(), grid.nx()] {
        return Err(input_error(
            py,
            format!(
                "gap: shape {shape:?}, the solver's grid is ({}, {})",
                grid.ny(),
                grid.nx()
            ),
            "gap",
            &format!("{shape:?}"),
            "the shape (ny, nx) of the solver's grid",
        ));
    }
    let initial_gap = gap.as_slice().map_err(|_| {
        input_error(
            py,
            "gap: the array must be C-contiguous (np.ascontiguousarray)".into(),
            "gap",
            "non-contiguous array",
            "C-contiguous float64 of shape (ny, nx)",
        )
    })?;
    let guess = match initial_pressure {
        Some(p) => Some(p.as_slice().map_err(|_| {
            input_error(
                py,
                "initial_pressure: the array must be C-contiguous".into(),
                "initial_pressure",
                "non-contiguous array",
                "C-contiguous float64 of shape (ny, nx)",
            )
        })?),
        None => None,
    };
    let problem = NormalContactProblem {
        grid,
        initial_gap,
        composite_modulus,
        loading,
    };
    // The solve reads the gap in place with the interpreter released: the caller must not
    // write to the array from another thread meanwhile (documented in the Python layer).
    let (solved, seconds) = py.detach(|| {
        let start = std::time::Instant::now();
        let solved = solve_normal_from(&problem, params, operator, guess, None);
        (solved, start.elapsed().as_secs_f64())
    });
    match solved {
        Ok(s) => {
            // The combined elastic displacement u_z1 + u_z2 = g - h + delta (the paper's (16)
            // solved for u), m.
            let displacement: Vec<f64> = s
                .gap
                .iter()
                .zip(initial_gap)
                .map(|(g, h)| g - h + s.approach)
                .collect();
            let d = normal_dict(py, s, grid)?;
            d.set_item("displacement", grid_array(py, displacement, grid)?)?;
            d.set_item("solve_time_s", seconds)?;
            Ok(d)
        }
        Err(e) => Err(library_error(py, &e.kind)),
    }
}

/// Normal contact of two elastic half-spaces on a grid (the paper's (16); Polonsky & Keer
/// 1999 or the dense active set): `gap` the initial separation (m) at element centres,
/// shape (ny, nx), C-contiguous float64 (read in place, not copied); the window
/// `size = (Lx, Ly)` (m) centred on the origin; the composite modulus (Pa); exactly one of
/// `load` (N) and `approach` (m). `periodic`: the window is one period of a periodic surface
/// ([`normal_compliance_operator_periodic`] with the kernel named by `kernel`,
/// [`periodic_kernel`]; force control only, `load` the mean pressure times the period area).
/// Returns a dict (see python/tribo/__init__.py).
#[pyfunction]
#[pyo3(signature = (gap, size, composite_modulus, load=None, approach=None, tolerance=1e-10, max_iterations=10_000, method="cg", initial_pressure=None, periodic=false, kernel="element"))]
#[allow(clippy::too_many_arguments)]
fn normal_contact<'py>(
    py: Python<'py>,
    gap: PyReadonlyArray2<'py, f64>,
    size: (f64, f64),
    composite_modulus: f64,
    load: Option<f64>,
    approach: Option<f64>,
    tolerance: f64,
    max_iterations: usize,
    method: &str,
    initial_pressure: Option<PyReadonlyArray2<'py, f64>>,
    periodic: bool,
    kernel: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = gap.shape().to_vec();
    let grid = SurfaceGrid::centred(shape[1], shape[0], 0.5 * size.0, 0.5 * size.1)
        .map_err(|e| library_error(py, &e))?;
    let loading = normal_loading(py, load, approach)?;
    let params = normal_params(py, tolerance, max_iterations, method)?;
    refuse_on_periodic(py, periodic, method, approach)?;
    let operator = periodic_operator(py, &grid, composite_modulus, periodic, kernel)?;
    normal_solve(
        py,
        &grid,
        &gap,
        composite_modulus,
        loading,
        &params,
        operator.as_ref(),
        initial_pressure.as_ref(),
    )
}

/// The periodic normal compliance operator of a `periodic` solve (None otherwise), built with
/// the interpreter released; the composite modulus checked first (the operator divides by
/// it).
fn periodic_operator(
    py: Python<'_>,
    grid: &SurfaceGrid,
    composite_modulus: f64,
    periodic: bool,
    kernel: &str,
) -> PyResult<Option<ConvolutionOperator>> {
    let Some(kernel) = periodic_kernel(py, periodic, kernel)? else {
        return Ok(None);
    };
    check_composite_modulus(py, composite_modulus)?;
    Ok(Some(py.detach(|| {
        normal_compliance_operator_periodic(grid, composite_modulus, kernel)
    })))
}

/// What a periodic normal solve cannot take, refused with the Python argument named: the
/// approach (the mean displacement of a periodic half-space is unbounded) and the dense
/// active set (its matrix is the non-periodic one).
fn refuse_on_periodic(
    py: Python<'_>,
    periodic: bool,
    method: &str,
    approach: Option<f64>,
) -> PyResult<()> {
    if !periodic {
        return Ok(());
    }
    if let Some(d) = approach {
        return Err(input_error(
            py,
            format!(
                "approach = {d}: approach control is not defined on a periodic grid (the mean \
                 displacement of a periodic half-space is unbounded): give the load (N) or the \
                 mean pressure (Pa)"
            ),
            "approach",
            &d.to_string(),
            "force control only on a periodic grid",
        ));
    }
    if method == "active_set" {
        return Err(input_error(
            py,
            "method = \"active_set\": the dense active set has no periodic form: use \"cg\"".into(),
            "method",
            method,
            "\"cg\" on a periodic grid",
        ));
    }
    Ok(())
}

/// The composite modulus must be finite and > 0 (Pa).
fn check_composite_modulus(py: Python<'_>, composite_modulus: f64) -> PyResult<()> {
    if composite_modulus.is_finite() && composite_modulus > 0.0 {
        return Ok(());
    }
    Err(input_error(
        py,
        format!("composite_modulus = {composite_modulus}: must be finite and > 0 (Pa)"),
        "composite_modulus",
        &composite_modulus.to_string(),
        "finite and > 0 (Pa)",
    ))
}

/// A normal contact solver for many solves on one grid and one composite modulus: the FFT
/// compliance operator is built once (the costly part of a small solve) and reused.
#[pyclass(module = "tribo._tribo", name = "NormalSolver", frozen)]
struct PyNormalSolver {
    grid: SurfaceGrid,
    composite_modulus: f64,
    params: NormalContactParams,
    operator: ConvolutionOperator,
}

#[pymethods]
impl PyNormalSolver {
    /// A solver on the grid of `shape = (ny, nx)` elements over `size = (Lx, Ly)` (m) for
    /// the composite modulus (Pa), with the tolerance, iteration limit and method of every
    /// solve; `periodic` with `kernel` as in [`normal_contact`].
    #[new]
    #[pyo3(signature = (shape, size, composite_modulus, tolerance=1e-10, max_iterations=10_000, method="cg", periodic=false, kernel="element"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        shape: (usize, usize),
        size: (f64, f64),
        composite_modulus: f64,
        tolerance: f64,
        max_iterations: usize,
        method: &str,
        periodic: bool,
        kernel: &str,
    ) -> PyResult<Self> {
        let grid = SurfaceGrid::centred(shape.1, shape.0, 0.5 * size.0, 0.5 * size.1)
            .map_err(|e| library_error(py, &e))?;
        check_composite_modulus(py, composite_modulus)?;
        let params = normal_params(py, tolerance, max_iterations, method)?;
        refuse_on_periodic(py, periodic, method, None)?;
        let operator = match periodic_operator(py, &grid, composite_modulus, periodic, kernel)? {
            Some(op) => op,
            None => py.detach(|| normal_compliance_operator(&grid, composite_modulus)),
        };
        Ok(PyNormalSolver {
            grid,
            composite_modulus,
            params,
            operator,
        })
    }

    /// One solve of the gap (m, shape (ny, nx), C-contiguous float64) under exactly one of
    /// `load` (N) and `approach` (m), from `initial_pressure` (Pa, a warm start) if given; a
    /// dict as `normal_contact` returns.
    #[pyo3(signature = (gap, load=None, approach=None, initial_pressure=None))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        gap: PyReadonlyArray2<'py, f64>,
        load: Option<f64>,
        approach: Option<f64>,
        initial_pressure: Option<PyReadonlyArray2<'py, f64>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let loading = normal_loading(py, load, approach)?;
        refuse_on_periodic(
            py,
            self.operator.is_periodic(),
            self.params.method.name(),
            approach,
        )?;
        normal_solve(
            py,
            &self.grid,
            &gap,
            self.composite_modulus,
            loading,
            &self.params,
            Some(&self.operator),
            initial_pressure.as_ref(),
        )
    }
}

/// The solution of a tangential problem as a dict of numpy arrays and floats.
fn tangential_dict<'py>(
    py: Python<'py>,
    s: TangentialSolution,
    grid: &SurfaceGrid,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("traction_x", grid_array(py, s.traction_x, grid)?)?;
    d.set_item("traction_y", grid_array(py, s.traction_y, grid)?)?;
    d.set_item("slip", grid_array(py, s.slip, grid)?)?;
    let stick = PyArray1::from_vec(py, s.stick).reshape([grid.ny(), grid.nx()])?;
    d.set_item("stick", stick)?;
    d.set_item("shift", s.shift)?;
    d.set_item("tangential_force", s.tangential_force)?;
    d.set_item("stick_area", s.stick_area)?;
    d.set_item("slip_area", s.slip_area)?;
    d.set_item("max_traction", s.max_traction)?;
    d.set_item("iterations", s.iterations)?;
    d.set_item("residual", s.residual)?;
    Ok(d)
}

/// Tangential contact with Coulomb friction (the paper's (8)) on a grid under a given contact
/// `pressure` (Pa, shape (ny, nx), C-contiguous float64, read in place), the tractions
/// parallel to the load (Cattaneo-Mindlin's assumption; the normal-tangential coupling of
/// dissimilar materials left out): partial slip under the tangential force `tangential_load`
/// (N) along `angle` (rad from x), or full sliding (q = f p along `angle`) with `sliding`.
/// Materials: Young's moduli (Pa) and Poisson's ratios of both bodies. `free`: the traction
/// direction free (the full 2D problem, [`solve_tangential_free`]) instead of parallel to the
/// load. `periodic`: the window is one period (the periodic Cerruti compliances,
/// [`tangential_compliance_operator_periodic`] or [`TangentialBlockOperator::new_periodic`],
/// with the kernel named by `kernel`, [`periodic_kernel`]).
#[pyfunction]
#[pyo3(signature = (pressure, size, friction, materials, tangential_load=None, sliding=false, angle=0.0, tolerance=1e-10, max_iterations=10_000, free=false, periodic=false, kernel="element"))]
#[allow(clippy::too_many_arguments)]
fn tangential_contact<'py>(
    py: Python<'py>,
    pressure: PyReadonlyArray2<'py, f64>,
    size: (f64, f64),
    friction: f64,
    materials: (f64, f64, f64, f64),
    tangential_load: Option<f64>,
    sliding: bool,
    angle: f64,
    tolerance: f64,
    max_iterations: usize,
    free: bool,
    periodic: bool,
    kernel: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let kernel = periodic_kernel(py, periodic, kernel)?;
    let lib = |e: &tribo::Error| library_error(py, e);
    let shape = pressure.shape().to_vec();
    let grid = SurfaceGrid::centred(shape[1], shape[0], 0.5 * size.0, 0.5 * size.1)
        .map_err(|e| lib(&e))?;
    let p = pressure.as_slice().map_err(|_| {
        input_error(
            py,
            "pressure: the array must be C-contiguous (np.ascontiguousarray)".into(),
            "pressure",
            "non-contiguous array",
            "C-contiguous float64 of shape (ny, nx)",
        )
    })?;
    let body1 =
        tribo::ElasticMaterial::named("body1", materials.0, materials.1).map_err(|e| lib(&e))?;
    let body2 =
        tribo::ElasticMaterial::named("body2", materials.2, materials.3).map_err(|e| lib(&e))?;
    let loading = tangential_loading(py, tangential_load, sliding, angle)?;
    let problem = TangentialProblem {
        grid: &grid,
        pressure: p,
        friction,
        body1,
        body2,
        loading,
        offset: None,
    };
    let params = TangentialParams {
        tolerance,
        max_iterations,
    };
    let (solved, seconds) = py.detach(|| {
        let start = std::time::Instant::now();
        // The periodic operators are built here (the non-periodic ones by the solvers);
        // their build is part of the solve's time, as the solvers' own is.
        let solved = match (free, kernel) {
            (true, Some(k)) => {
                let op = TangentialBlockOperator::new_periodic(&grid, &body1, &body2, k);
                solve_tangential_free(&problem, &params, Some(&op), None)
            }
            (true, None) => solve_tangential_free(&problem, &params, None, None),
            (false, Some(k)) => {
                let op = tangential_compliance_operator_periodic(&grid, &body1, &body2, angle, k);
                solve_tangential(&problem, &params, Some(&op), None)
            }
            (false, None) => solve_tangential(&problem, &params, None, None),
        };
        (solved, start.elapsed().as_secs_f64())
    });
    match solved {
        Ok(s) => {
            let d = tangential_dict(py, s, &grid)?;
            d.set_item("solve_time_s", seconds)?;
            Ok(d)
        }
        Err(e) => Err(lib(&e.kind)),
    }
}

/// The tangential loading from its arguments: exactly one of a force (N) and sliding.
fn tangential_loading(
    py: Python<'_>,
    tangential_load: Option<f64>,
    sliding: bool,
    angle: f64,
) -> PyResult<TangentialLoading> {
    match (tangential_load, sliding) {
        (Some(q), false) => Ok(TangentialLoading::Force {
            magnitude: q,
            angle,
        }),
        (None, true) => Ok(TangentialLoading::Sliding { angle }),
        _ => Err(input_error(
            py,
            "give exactly one of tangential_load (N) and sliding=True".into(),
            "tangential_load",
            &format!("{tangential_load:?}"),
            "exactly one of tangential_load and sliding",
        )),
    }
}

/// Normal and tangential contact of dissimilar bodies with their coupling (Johnson 1985
/// sec. 5.4; docs/theory/HALFSPACE.md 1.1), solved by alternation ([`solve_coupled`]): the
/// gap (m, shape (ny, nx), C-contiguous float64) on the window `size` (m), the materials
/// (E1, nu1, E2, nu2), friction f, exactly one of `load` (N) and `approach` (m), exactly one
/// of `tangential_load` (N) and `sliding` along `angle` (rad), the traction parallel to the
/// load or (`free`) free in direction. A dict: `normal` and `tangential` (the dicts of
/// `normal_contact` and `tangential_contact`), `passes`, `change` and Dundurs' `beta`.
#[pyfunction]
#[pyo3(signature = (gap, size, materials, friction, load=None, approach=None, tangential_load=None, sliding=false, angle=0.0, free=false, tolerance=1e-8, max_passes=100))]
#[allow(clippy::too_many_arguments)]
fn coupled_contact<'py>(
    py: Python<'py>,
    gap: PyReadonlyArray2<'py, f64>,
    size: (f64, f64),
    materials: (f64, f64, f64, f64),
    friction: f64,
    load: Option<f64>,
    approach: Option<f64>,
    tangential_load: Option<f64>,
    sliding: bool,
    angle: f64,
    free: bool,
    tolerance: f64,
    max_passes: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let lib = |e: &tribo::Error| library_error(py, e);
    let shape = gap.shape().to_vec();
    let grid = SurfaceGrid::centred(shape[1], shape[0], 0.5 * size.0, 0.5 * size.1)
        .map_err(|e| lib(&e))?;
    let initial_gap = gap.as_slice().map_err(|_| {
        input_error(
            py,
            "gap: the array must be C-contiguous (np.ascontiguousarray)".into(),
            "gap",
            "non-contiguous array",
            "C-contiguous float64 of shape (ny, nx)",
        )
    })?;
    let body1 =
        tribo::ElasticMaterial::named("body1", materials.0, materials.1).map_err(|e| lib(&e))?;
    let body2 =
        tribo::ElasticMaterial::named("body2", materials.2, materials.3).map_err(|e| lib(&e))?;
    let problem = CoupledProblem {
        grid: &grid,
        initial_gap,
        body1,
        body2,
        normal_loading: normal_loading(py, load, approach)?,
        tangential_loading: tangential_loading(py, tangential_load, sliding, angle)?,
        friction,
    };
    let model = if free {
        TangentialModel::Free
    } else {
        TangentialModel::LoadParallel
    };
    let params = CoupledParams::new(tolerance, max_passes, model).map_err(|e| lib(&e))?;
    let (solved, seconds) = py.detach(|| {
        let start = std::time::Instant::now();
        let solved = solve_coupled(&problem, &params, None);
        (solved, start.elapsed().as_secs_f64())
    });
    let s = solved.map_err(|e| lib(&e.kind))?;
    let d = PyDict::new(py);
    d.set_item("normal", normal_dict(py, s.normal, &grid)?)?;
    d.set_item("tangential", tangential_dict(py, s.tangential, &grid)?)?;
    d.set_item("passes", s.passes)?;
    d.set_item("change", s.change)?;
    d.set_item("beta", s.beta)?;
    d.set_item("solve_time_s", seconds)?;
    Ok(d)
}

// ----------------------------------------------------------------------------------------
// Cases
// ----------------------------------------------------------------------------------------

/// A TOML value from a Python object (dict, list, tuple, str, bool, int, float); `path`
/// names it in errors.
pub(crate) fn to_toml(py: Python<'_>, obj: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    let bad = |what: &str| {
        input_error(
            py,
            format!("{path}: {what} (a case dict holds dicts, lists, str, bool, int and float)"),
            path,
            what,
            "dicts, lists, str, bool, int and float",
        )
    };
    if obj.is_instance_of::<PyBool>() {
        Ok(toml::Value::Boolean(obj.extract()?))
    } else if obj.is_instance_of::<PyInt>() {
        Ok(toml::Value::Integer(
            obj.extract()
                .map_err(|_| bad("an integer beyond 64 bits"))?,
        ))
    } else if obj.is_instance_of::<PyFloat>() {
        Ok(toml::Value::Float(obj.extract()?))
    } else if obj.is_instance_of::<PyString>() {
        Ok(toml::Value::String(obj.extract()?))
    } else if let Ok(d) = obj.cast::<PyDict>() {
        let mut table = toml::map::Map::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| bad("a key that is not a str"))?;
            if v.is_none() {
                continue;
            }
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            table.insert(key, to_toml(py, &v, &sub)?);
        }
        Ok(toml::Value::Table(table))
    } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            items.push(to_toml(py, &v?, &format!("{path}[{i}]"))?);
        }
        Ok(toml::Value::Array(items))
    } else if let Ok(f) = obj.extract::<f64>() {
        // numpy scalars and other numbers.
        Ok(toml::Value::Float(f))
    } else {
        Err(bad(&format!("a {}", obj.get_type().name()?)))
    }
}

/// A validated case of either kind (a half-space case or a 2D boundary element case).
#[pyclass(module = "tribo._tribo", name = "Case", frozen)]
struct PyCase {
    inner: tribo_case::Case,
    text: String,
    source: String,
    base_dir: Option<PathBuf>,
}

#[pymethods]
impl PyCase {
    /// Parse and validate a case file's text; `source` names it in errors, `base_dir`
    /// resolves its relative paths (height maps, meshes).
    #[staticmethod]
    #[pyo3(signature = (text, source="<string>", base_dir=None))]
    fn from_toml_text(
        py: Python<'_>,
        text: String,
        source: &str,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Self> {
        let base = base_dir.clone().unwrap_or_else(|| PathBuf::from("."));
        let inner =
            tribo_case::Case::from_toml(&text, source, &base).map_err(|e| case_error(py, &e))?;
        Ok(PyCase {
            inner,
            text,
            source: source.to_string(),
            base_dir,
        })
    }

    /// A case from nested dicts with the keys of a case file (values in SI units or strings
    /// with units), validated by the same rules.
    #[staticmethod]
    #[pyo3(signature = (data, source="<dict>", base_dir=None))]
    fn from_dict(
        py: Python<'_>,
        data: &Bound<'_, PyDict>,
        source: &str,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Self> {
        let value = to_toml(py, data.as_any(), "")?;
        let text = toml::to_string(&value).map_err(|e| {
            input_error(
                py,
                format!("the dict is not a TOML table: {e}"),
                "",
                "",
                &e.to_string(),
            )
        })?;
        Self::from_toml_text(py, text, source, base_dir)
    }

    /// An embedded example case by name (`tribo example` lists them).
    #[staticmethod]
    fn example(py: Python<'_>, name: &str) -> PyResult<Self> {
        let ex = tribo_case::examples::find(name).ok_or_else(|| {
            input_error(
                py,
                format!(
                    "no example {name:?}; known: {}",
                    tribo_case::examples::names()
                ),
                "name",
                name,
                "the name of an embedded example",
            )
        })?;
        Self::from_toml_text(py, ex.text.to_string(), &format!("<embedded {name}>"), None)
    }

    /// The case's kind: "halfspace" or "bem2d".
    #[getter]
    fn kind(&self) -> &'static str {
        match self.inner {
            tribo_case::Case::HalfSpace(_) => "halfspace",
            tribo_case::Case::Bem2d(_) => "bem2d",
        }
    }

    /// The case's title.
    #[getter]
    fn title(&self) -> String {
        match &self.inner {
            tribo_case::Case::HalfSpace(c) => c.title.clone(),
            tribo_case::Case::Bem2d(c) => c.title.clone(),
        }
    }

    /// The TOML text the case was read from.
    #[getter]
    fn toml(&self) -> String {
        self.text.clone()
    }

    /// The name of the case in errors (its file, `<string>`, `<dict>`, `<embedded NAME>`).
    #[getter]
    fn source(&self) -> String {
        self.source.clone()
    }

    /// The folder its relative paths resolve against (None: the working directory).
    #[getter]
    fn base_dir(&self) -> Option<PathBuf> {
        self.base_dir.clone()
    }

    fn __repr__(&self) -> String {
        format!("Case(kind={:?}, title={:?})", self.kind(), self.title())
    }
}

/// The results of a run with the case that produced them.
#[pyclass(module = "tribo._tribo", name = "Results", frozen)]
struct PyResults {
    case: tribo_case::Case,
    results: tribo_case::Results,
}

impl PyResults {
    /// The summary (`summary.json`, as `tribo run --json` prints it but for the write time)
    /// as JSON text.
    fn summary_text(&self) -> Result<String, String> {
        let plots = tribo_io::WriteOptions::default().draws_plots();
        match (&self.case, &self.results) {
            (tribo_case::Case::HalfSpace(c), tribo_case::Results::HalfSpace(o)) => {
                let s = tribo_io::halfspace::summary(c, o, plots).map_err(|e| e.to_string())?;
                serde_json::to_string(&s).map_err(|e| e.to_string())
            }
            (tribo_case::Case::Bem2d(c), tribo_case::Results::Bem2d(o)) => {
                let mut s = tribo_case::bem::summary::BemSummary::new(c, o, Vec::new())
                    .map_err(|e| e.to_string())?;
                s.outputs = tribo_io::bem::files(o, &s, plots);
                serde_json::to_string(&s).map_err(|e| e.to_string())
            }
            _ => Err("results of another kind than the case".into()),
        }
    }
}

#[pymethods]
impl PyResults {
    /// The summary as JSON text (the keys and units of docs/user/outputs.md).
    fn summary_json(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| self.summary_text())
            .map_err(SolverError::new_err)
    }

    /// The stress field of a half-space run with `[field]`: a dict of the named point arrays
    /// of `stress.vti` (shape (nz, ny, nx); Pa, J/m^3, strains 1), with the damage criteria's
    /// psi where the case has `[damage]`, the coordinates x, y, z (m) and how the field was
    /// computed; None without a field.
    fn field<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let tribo_case::Results::HalfSpace(o) = &self.results else {
            return Ok(None);
        };
        let Some(st) = &o.stress else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        field::stress_dict(py, st, &d)?;
        let g = &st.field.grid;
        let shape = [g.z.len(), g.y.len(), g.x.len()];
        let psi = PyDict::new(py);
        if let Some(dmg) = &o.damage {
            for c in &dmg.criteria {
                let arr = PyArray1::from_vec(py, c.psi.clone()).reshape(shape)?;
                psi.set_item(&c.assessment.name, arr)?;
            }
        }
        d.set_item("psi", psi)?;
        Ok(Some(d))
    }

    /// Writes the files `tribo run` writes into `directory` (created if needed; an earlier
    /// run's files there are removed); returns the names written (the summary's `outputs`).
    fn write(&self, py: Python<'_>, directory: PathBuf) -> PyResult<Vec<String>> {
        let opts = tribo_io::WriteOptions::default();
        let written = py.detach(|| match (&self.case, &self.results) {
            (tribo_case::Case::HalfSpace(c), tribo_case::Results::HalfSpace(o)) => {
                tribo_io::write_halfspace(&directory, c, o, &opts).map(|w| w.files)
            }
            (tribo_case::Case::Bem2d(c), tribo_case::Results::Bem2d(o)) => {
                tribo_io::write_bem(&directory, c, o, &opts).map(|w| w.files)
            }
            _ => Ok(Vec::new()),
        });
        written.map_err(|e| io_error(&e))
    }

    /// The contact fields of a half-space run as a dict of numpy arrays of shape (ny, nx)
    /// (pressure, Pa; gap, m; and with friction traction_x, traction_y, Pa) and the
    /// coordinates x, y of the element centres (m); None for a 2D case.
    fn fields<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let tribo_case::Results::HalfSpace(o) = &self.results else {
            return Ok(None);
        };
        let grid = &o.prepared.grid;
        let d = normal_dict(py, o.solution.clone(), grid)?;
        let (hx, hy) = grid.half_widths();
        d.set_item("size", (2.0 * hx, 2.0 * hy))?;
        if let Some(t) = &o.tangential {
            d.set_item(
                "traction_x",
                grid_array(py, t.solution.traction_x.clone(), grid)?,
            )?;
            d.set_item(
                "traction_y",
                grid_array(py, t.solution.traction_y.clone(), grid)?,
            )?;
            let stick: Vec<bool> = t.solution.stick.clone();
            let arr = numpy::PyArray1::from_vec(py, stick).reshape([grid.ny(), grid.nx()])?;
            d.set_item("stick", arr)?;
        }
        Ok(Some(d))
    }
}

/// Runs a case through tribo-case's pipeline with the interpreter released.
#[pyfunction]
fn run(py: Python<'_>, case: &PyCase) -> PyResult<PyResults> {
    let inner = case.inner.clone();
    let results = py
        .detach(|| tribo_case::run(&inner, &mut Silent))
        .map_err(|e| case_error(py, &e))?;
    Ok(PyResults {
        case: inner,
        results,
    })
}

/// The names of the embedded example cases.
#[pyfunction]
fn example_names() -> Vec<&'static str> {
    tribo_case::examples::EXAMPLES
        .iter()
        .map(|e| e.name)
        .collect()
}

/// The compiled core of the Python package `tribo`.
#[pymodule]
fn _tribo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("ConvergenceError", py.get_type::<ConvergenceError>())?;
    m.add("SolverError", py.get_type::<SolverError>())?;
    m.add_class::<PyHertz>()?;
    m.add_class::<PyCase>()?;
    m.add_class::<PyResults>()?;
    m.add_class::<PyNormalSolver>()?;
    m.add_class::<study::PyStudy>()?;
    m.add_class::<study::PyStudyDir>()?;
    m.add_function(wrap_pyfunction!(hertz, m)?)?;
    m.add_function(wrap_pyfunction!(composite_modulus, m)?)?;
    m.add_function(wrap_pyfunction!(normal_contact, m)?)?;
    m.add_function(wrap_pyfunction!(tangential_contact, m)?)?;
    m.add_function(wrap_pyfunction!(coupled_contact, m)?)?;
    m.add_function(wrap_pyfunction!(field::stress_field, m)?)?;
    m.add_function(wrap_pyfunction!(field::damage, m)?)?;
    m.add_function(wrap_pyfunction!(field::energy_damage, m)?)?;
    m.add_function(wrap_pyfunction!(fatigue::fatigue_fit, m)?)?;
    m.add_function(wrap_pyfunction!(fatigue::fatigue_diagram, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(example_names, m)?)?;
    m.add_function(wrap_pyfunction!(study::slurm_ranges, m)?)?;
    m.add_function(wrap_pyfunction!(study::slurm_job_id, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_examples, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_generate, m)?)?;
    m.add_function(wrap_pyfunction!(surface::spectrum_moments, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_statistics, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_psd, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_fit_power_law, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_autocorrelation, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_detrend, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_resample, m)?)?;
    m.add_function(wrap_pyfunction!(surface::surface_read, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
