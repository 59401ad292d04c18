//! Rough surfaces from Python (the submodule `tribo.surface`, python/tribo/surface.py): the
//! generator, the statistics, detrending and resampling of [`tribo::surface`] and the
//! topography readers of [`tribo_case::topography`], on numpy arrays of shape (ny, nx) (row j
//! at y = j dy, column i at x = i dx: the layout of [`tribo::surface::Topography`], x
//! fastest).
//!
//! Errors name the Python argument: the library's field names (`spectrum.hurst`,
//! `topography.dx`, ...) are renamed to the arguments of the Python functions (`hurst`,
//! `spacing`, ...) by [`renamed`]; a file's errors name the file (`path`).

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use tribo::surface::{
    detrend, generate, resample, statistics, GenerateParams, Method, Normalization, PowerSpectrum,
    SpectralMoments, Topography,
};

use crate::{input_error, library_error};

/// The Python argument that a library field stands for (the field itself when none does).
fn argument_of(field: &str) -> String {
    let tail = |prefix: &str| field.strip_prefix(prefix).map(str::to_string);
    if let Some(rest) = tail("topography.heights") {
        return format!("heights{rest}");
    }
    match field {
        "topography.dx" | "topography.dy" | "resample.dx" | "resample.dy" => "spacing".into(),
        "topography" => "heights".into(),
        "generate.n" | "resample.n" => "shape".into(),
        "generate.periods[0]" | "generate.periods[1]" => "size".into(),
        "detrend.degree" => "degree".into(),
        _ => tail("spectrum.")
            .or_else(|| tail("normalization."))
            .unwrap_or_else(|| field.to_string()),
    }
}

/// The exception of a library error, its field renamed to the Python argument
/// ([`argument_of`]).
pub(crate) fn renamed(py: Python<'_>, e: tribo::Error) -> PyErr {
    match e {
        tribo::Error::InvalidParameter { field, value, rule } => {
            let arg = argument_of(&field);
            input_error(py, format!("{arg} = {value}: {rule}"), &arg, &value, &rule)
        }
        other => library_error(py, &other),
    }
}

/// The heights of a (ny, nx) array (m) as a [`Topography`] of spacing `spacing` (m).
fn topography(
    py: Python<'_>,
    heights: &PyReadonlyArray2<'_, f64>,
    spacing: (f64, f64),
) -> PyResult<Topography> {
    let shape = heights.shape();
    let (ny, nx) = (shape[0], shape[1]);
    let h = heights.as_array().iter().copied().collect::<Vec<f64>>();
    Topography::new(nx, ny, spacing.0, spacing.1, h).map_err(|e| renamed(py, e))
}

/// A topography's heights as a numpy array of shape (ny, nx).
fn heights_array<'py>(py: Python<'py>, t: Topography) -> PyResult<Bound<'py, PyAny>> {
    let (nx, ny) = (t.nx(), t.ny());
    Ok(PyArray1::from_vec(py, t.into_heights())
        .reshape([ny, nx])?
        .into_any())
}

/// A values vector as a numpy array of shape (ny, nx).
fn grid_values<'py>(
    py: Python<'py>,
    v: Vec<f64>,
    nx: usize,
    ny: usize,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, v).reshape([ny, nx])?.into_any())
}

/// The spectrum of the arguments (wavenumbers in rad/m), validated.
fn spectrum(
    py: Python<'_>,
    rolloff: f64,
    powerlaw_start: f64,
    cutoff: f64,
    hurst: f64,
    anisotropy: (f64, f64),
) -> PyResult<PowerSpectrum> {
    PowerSpectrum {
        rolloff,
        powerlaw_start,
        cutoff,
        hurst,
        anisotropy: [anisotropy.0, anisotropy.1],
    }
    .validated()
    .map_err(|e| renamed(py, e))
}

/// Moments as a dict: `m00` .. `m22` and the statistics made of them (`rms_height`,
/// `rms_slope`, `rms_curvature`, `bandwidth`).
fn moments_dict<'py>(py: Python<'py>, m: &SpectralMoments) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in [
        ("m00", m.m00),
        ("m20", m.m20),
        ("m02", m.m02),
        ("m11", m.m11),
        ("m40", m.m40),
        ("m04", m.m04),
        ("m22", m.m22),
        ("rms_height", m.rms_height()),
        ("rms_slope", m.rms_slope()),
        ("rms_curvature", m.rms_curvature()),
    ] {
        d.set_item(k, v)?;
    }
    // Nayak's bandwidth needs m20 > 0 (a surface with x-variation).
    let alpha = m.bandwidth();
    d.set_item(
        "bandwidth",
        if alpha.is_finite() { Some(alpha) } else { None },
    )?;
    Ok(d)
}

/// A Gaussian self-affine surface ([`tribo::surface::generate`]): `shape = (ny, nx)` points
/// over the periods `size = (Lx, Ly)` (m); the spectrum's roll-off, start of the power law and
/// cutoff wavenumbers (rad/m), Hurst exponent and anisotropy factors; exactly one of
/// `rms_height` (m) and `rms_slope`; `method` "filter" (filtered white noise) or
/// "random_phase"; the seed. The heights, shape (ny, nx), m.
#[pyfunction]
#[pyo3(signature = (shape, size, rolloff, powerlaw_start, cutoff, hurst, anisotropy, rms_height, rms_slope, method, seed))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn surface_generate<'py>(
    py: Python<'py>,
    shape: (usize, usize),
    size: (f64, f64),
    rolloff: f64,
    powerlaw_start: f64,
    cutoff: f64,
    hurst: f64,
    anisotropy: (f64, f64),
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
    method: &str,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let normalization = match (rms_height, rms_slope) {
        (Some(h), None) => Normalization::RmsHeight(h),
        (None, Some(s)) => Normalization::RmsSlope(s),
        _ => {
            return Err(input_error(
                py,
                "give exactly one of rms_height (m) and rms_slope".into(),
                "rms_height",
                &format!("{rms_height:?}"),
                "exactly one of rms_height and rms_slope",
            ))
        }
    };
    let method = match method {
        "filter" => Method::FilteredNoise,
        "random_phase" => Method::RandomPhase,
        other => {
            return Err(input_error(
                py,
                format!("method = {other:?}: one of \"filter\", \"random_phase\""),
                "method",
                other,
                "one of \"filter\", \"random_phase\"",
            ))
        }
    };
    let spectrum = spectrum(py, rolloff, powerlaw_start, cutoff, hurst, anisotropy)?;
    check_memory(py, shape)?;
    let params = GenerateParams {
        nx: shape.1,
        ny: shape.0,
        periods: size,
        spectrum,
        normalization,
        method,
        seed,
    };
    let t = py
        .detach(|| generate(&params))
        .map_err(|e| renamed(py, e))?;
    heights_array(py, t)
}

/// Refuses a grid whose generation cannot get its memory (24 bytes per point: the transform
/// and the heights), before the generator's O(n) pass over the modes: a mistyped shape is an
/// immediate [`crate::InputError`] naming `shape`, not minutes of work before the library's
/// own out-of-memory error.
fn check_memory(py: Python<'_>, shape: (usize, usize)) -> PyResult<()> {
    let bytes = shape
        .0
        .checked_mul(shape.1)
        .and_then(|n| n.checked_mul(24))
        .filter(|&b| {
            let mut probe: Vec<u8> = Vec::new();
            probe.try_reserve_exact(b).is_ok()
        });
    match bytes {
        Some(_) => Ok(()),
        None => Err(input_error(
            py,
            format!(
                "shape = {shape:?}: the surface needs 24 bytes per point, more memory than can \
                 be allocated"
            ),
            "shape",
            &format!("{shape:?}"),
            "a grid whose memory (24 bytes per point) can be allocated",
        )),
    }
}

/// The spectral moments of the continuous spectrum (closed forms) with the plateau `C_r = 1`
/// (`continuous`), and, when a grid `shape = (ny, nx)` over `size` (m) is given, the sums over
/// its modes (`discrete`) with the standard deviations of filtered noise (`discrete_std`), each
/// a dict as [`surface_moments`] returns.
#[pyfunction]
#[pyo3(signature = (rolloff, powerlaw_start, cutoff, hurst, anisotropy, shape=None, size=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn spectrum_moments<'py>(
    py: Python<'py>,
    rolloff: f64,
    powerlaw_start: f64,
    cutoff: f64,
    hurst: f64,
    anisotropy: (f64, f64),
    shape: Option<(usize, usize)>,
    size: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = spectrum(py, rolloff, powerlaw_start, cutoff, hurst, anisotropy)?;
    let d = PyDict::new(py);
    d.set_item("continuous", moments_dict(py, &s.moments_continuous())?)?;
    if let (Some((ny, nx)), Some((lx, ly))) = (shape, size) {
        if !(lx.is_finite() && lx > 0.0 && ly.is_finite() && ly > 0.0) {
            return Err(input_error(
                py,
                format!("size = ({lx}, {ly}): the periods must be finite and > 0 (m)"),
                "size",
                &format!("({lx}, {ly})"),
                "finite and > 0 (m)",
            ));
        }
        let (mean, std) = py.detach(|| s.moments_discrete(nx, ny, (lx, ly)));
        d.set_item("discrete", moments_dict(py, &mean)?)?;
        d.set_item("discrete_std", moments_dict(py, &std)?)?;
    }
    Ok(d)
}

/// The spectral moments of a topography (heights (ny, nx), m; `spacing = (dx, dy)`, m) and
/// the statistics made of them ([`moments_dict`]), with the rms height about the mean
/// (`rms_height` from the heights themselves) and the forward-difference rms slope
/// (`rms_slope_fd`).
#[pyfunction]
pub(crate) fn surface_statistics<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    spacing: (f64, f64),
) -> PyResult<Bound<'py, PyDict>> {
    let t = topography(py, &heights, spacing)?;
    let (m, fd, rms) = py.detach(|| {
        (
            statistics::moments(&t),
            statistics::rms_slope_fd(&t),
            statistics::rms_height(&t),
        )
    });
    let d = moments_dict(py, &m.map_err(|e| renamed(py, e))?)?;
    d.set_item("rms_height", rms)?;
    d.set_item("rms_slope_fd", fd)?;
    Ok(d)
}

/// The radially averaged PSD of a topography: (q (rad/m), C (m^4), modes per bin).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub(crate) fn surface_psd<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    spacing: (f64, f64),
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
)> {
    let t = topography(py, &heights, spacing)?;
    let bins = py
        .detach(|| statistics::radial_psd(&t))
        .map_err(|e| renamed(py, e))?;
    let q = bins.iter().map(|b| b.q).collect();
    let c = bins.iter().map(|b| b.psd).collect();
    let n = bins.iter().map(|b| b.modes as u64).collect();
    Ok((
        PyArray1::from_vec(py, q),
        PyArray1::from_vec(py, c),
        PyArray1::from_vec(py, n),
    ))
}

/// The power law `C = A q^e` fitted to PSD bins (q rad/m, C m^4, modes) between `q_min` and
/// `q_max` (rad/m): a dict `exponent`, `hurst`, `prefactor`, `bins`.
#[pyfunction]
pub(crate) fn surface_fit_power_law<'py>(
    py: Python<'py>,
    q: Vec<f64>,
    psd: Vec<f64>,
    modes: Vec<u64>,
    q_min: f64,
    q_max: f64,
) -> PyResult<Bound<'py, PyDict>> {
    if q.len() != psd.len() || q.len() != modes.len() {
        return Err(input_error(
            py,
            format!(
                "q, psd and modes have {}, {} and {} values: one each per bin",
                q.len(),
                psd.len(),
                modes.len()
            ),
            "psd",
            &format!("{} values", psd.len()),
            "as many values as q",
        ));
    }
    let bins: Vec<statistics::PsdBin> = q
        .iter()
        .zip(&psd)
        .zip(&modes)
        .map(|((&q, &psd), &m)| statistics::PsdBin {
            q,
            psd,
            modes: m as usize,
        })
        .collect();
    let fit = statistics::fit_power_law(&bins, q_min, q_max).map_err(|e| {
        let rule = e.to_string();
        input_error(
            py,
            rule.clone(),
            "q_range",
            &format!("({q_min}, {q_max})"),
            &rule,
        )
    })?;
    let d = PyDict::new(py);
    d.set_item("exponent", fit.exponent)?;
    d.set_item("hurst", fit.hurst)?;
    d.set_item("prefactor", fit.prefactor)?;
    d.set_item("bins", fit.bins)?;
    Ok(d)
}

/// The periodic autocorrelation of a topography (m^2, shape (ny, nx), lag (i dx, j dy) at
/// [j, i], negative lags wrapped).
#[pyfunction]
pub(crate) fn surface_autocorrelation<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    spacing: (f64, f64),
) -> PyResult<Bound<'py, PyAny>> {
    let t = topography(py, &heights, spacing)?;
    let (nx, ny) = (t.nx(), t.ny());
    let r = py
        .detach(|| statistics::autocorrelation(&t))
        .map_err(|e| renamed(py, e))?;
    grid_values(py, r, nx, ny)
}

/// The least-squares polynomial of total degree `degree` removed from a topography:
/// (residual (ny, nx), trend (ny, nx), coefficients of the Legendre products), m.
#[pyfunction]
#[allow(clippy::type_complexity)]
pub(crate) fn surface_detrend<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    spacing: (f64, f64),
    degree: usize,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Vec<f64>)> {
    let t = topography(py, &heights, spacing)?;
    let (nx, ny) = (t.nx(), t.ny());
    let d = py
        .detach(|| detrend::detrend_polynomial(&t, degree))
        .map_err(|e| renamed(py, e))?;
    Ok((
        heights_array(py, d.residual)?,
        grid_values(py, d.trend, nx, ny)?,
        d.coefficients,
    ))
}

/// A topography resampled by Keys' bicubic convolution onto `shape = (ny, nx)` points of
/// `new_spacing` (m) from the same origin, periodic or bounded.
#[pyfunction]
pub(crate) fn surface_resample<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    spacing: (f64, f64),
    shape: (usize, usize),
    new_spacing: (f64, f64),
    periodic: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let t = topography(py, &heights, spacing)?;
    let boundary = if periodic {
        resample::Boundary::Periodic
    } else {
        resample::Boundary::Bounded
    };
    let r = py
        .detach(|| resample::resample(&t, boundary, shape.1, shape.0, new_spacing))
        .map_err(|e| renamed(py, e))?;
    heights_array(py, r)
}

/// Reads a measured topography (X3P, ASCII/CSV grid, `.npy`; the format by the extension):
/// (heights (ny, nx) in m with NaN at invalid points, (dx, dy) in m, invalid count). `spacing`
/// (m) for the formats that do not carry it (checked against the file's where it does);
/// `height_unit`: metres per stored unit for formats without units. Invalid points are
/// refused unless `keep_invalid`.
#[pyfunction]
#[pyo3(signature = (path, spacing=None, height_unit=1.0, keep_invalid=false))]
#[allow(clippy::type_complexity)]
pub(crate) fn surface_read<'py>(
    py: Python<'py>,
    path: PathBuf,
    spacing: Option<(f64, f64)>,
    height_unit: f64,
    keep_invalid: bool,
) -> PyResult<(Bound<'py, PyAny>, (f64, f64), usize)> {
    if !(height_unit.is_finite() && height_unit > 0.0) {
        return Err(input_error(
            py,
            format!("height_unit = {height_unit}: must be finite and > 0 (m per stored unit)"),
            "height_unit",
            &height_unit.to_string(),
            "finite and > 0 (m per stored unit)",
        ));
    }
    let options = tribo_case::topography::ReadOptions {
        spacing,
        height_unit,
        ..Default::default()
    };
    let file_error = |e: tribo_case::topography::TopographyError| {
        input_error(
            py,
            e.to_string(),
            "path",
            &e.path.display().to_string(),
            &e.problem,
        )
    };
    let m = py
        .detach(|| tribo_case::topography::read(&path, &options))
        .map_err(file_error)?;
    let (nx, ny, dx, dy) = (m.nx, m.ny, m.dx, m.dy);
    let invalid = m.invalid_count();
    let heights = if keep_invalid {
        m.heights
    } else {
        m.into_topography().map_err(file_error)?.into_heights()
    };
    Ok((grid_values(py, heights, nx, ny)?, (dx, dy), invalid))
}
