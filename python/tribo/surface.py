"""Rough surfaces: generation, statistics, detrending, resampling and measured topographies.

The Rust library's ``tribo::surface`` (crates/tribo/src/surface) and the topography readers
of ``tribo_case::topography`` on numpy arrays; the conventions (the PSD's normalisation,
wavenumbers in rad/m, the sampling errors of filtered noise) are those of
docs/theory/SURFACES.md.

A surface is a :class:`Topography`: heights (m) of shape (ny, nx), point ``[j, i]`` at
``(x, y) = (i dx, j dy)``, with the spacing ``(dx, dy)`` (m). A generated one is periodic with
the periods ``size = (nx dx, ny dy)``; the spectral statistics take any topography as one
period of a periodic surface (detrend a measured one first).

Quick start::

    from tribo import surface
    t = surface.self_affine((256, 256), size=(1e-3, 1e-3), hurst=0.8,
                            powerlaw_start=2 * np.pi / 0.25e-3, cutoff=2 * np.pi / 16e-6,
                            rms_slope=0.1, seed=1)
    surface.rms_slopes(t), surface.psd(t).fit().hurst
    r = tribo.normal_contact(t.gap(), size=t.size, composite_modulus=1e11,
                             mean_pressure=1e7, periodic=True)

For Tamaas users, :class:`Isopowerlaw` with :class:`SurfaceGeneratorFilter` (or
:class:`SurfaceGeneratorRandomPhase`) take Tamaas's parameters (``q0``, ``q1``, ``q2`` in
units of the fundamental wavenumber, ``hurst``, ``random_seed``) and return a numpy array, as
``tamaas.Isopowerlaw2D`` and ``tamaas.SurfaceGeneratorFilter2D`` do (docs/user/python.md has
the mapping table).

Errors: :class:`tribo.InputError` naming the argument (``hurst``, ``spacing``, ...) or, for a
file, ``path`` with the file and the problem in the message.
"""

from __future__ import annotations

import math as _math
import os as _os
from dataclasses import dataclass as _dataclass

import numpy as _np

from . import _tribo
from ._tribo import InputError

# Bound for real (typing.get_type_hints resolves the string annotations); `__dir__` keeps
# them out of dir().
import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

del annotations  # the __future__ feature's name: not part of the API

__all__ = [
    "Isopowerlaw",
    "PowerLawFit",
    "RadialPSD",
    "SurfaceGeneratorFilter",
    "SurfaceGeneratorRandomPhase",
    "Topography",
    "autocorrelation",
    "detrend",
    "moments",
    "psd",
    "read",
    "resample",
    "rms_curvature",
    "rms_heights",
    "rms_slopes",
    "self_affine",
    "spectrum_moments",
]


def _input_error(field: str, rule: str, value: Any = "") -> InputError:
    """An :class:`InputError` with its ``field``, ``value`` and ``rule`` set."""
    err = InputError(f"{field}: {rule}")
    err.field, err.value, err.rule = field, str(value), rule
    return err


def _pair(name: str, value: Any) -> Tuple[float, float]:
    """Two floats from a pair (or one number for both)."""
    try:
        if _np.ndim(value) == 0:
            v = float(value)
            return (v, v)
        a, b = value
        return (float(a), float(b))
    except (TypeError, ValueError):
        raise _input_error(name, "a number or a pair of numbers is needed", value) from None


def _number(name: str, value: Any) -> float:
    """A real number (a Python or numpy scalar), or an InputError naming ``name``."""
    if isinstance(value, (bool, _np.bool_)) or _np.ndim(value) != 0:
        raise _input_error(name, "a real number is needed", value)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise _input_error(name, "a real number is needed", value) from None


def _integer(name: str, value: Any, rule: str) -> int:
    """An integer (or an integral float: 64.0, never 64.5), or an InputError naming ``name``."""
    if isinstance(value, (bool, _np.bool_)) or _np.ndim(value) != 0:
        raise _input_error(name, rule, value)
    try:
        x = float(value)
        n = int(value)
    except (TypeError, ValueError, OverflowError):
        raise _input_error(name, rule, value) from None
    if not _math.isfinite(x) or x != n:
        raise _input_error(name, rule, value)
    return n


def _shape(value: Any) -> Tuple[int, int]:
    """The grid shape (ny, nx) from a pair (or one integer for a square grid)."""
    rule = "(ny, nx): two integers >= 2"
    if _np.ndim(value) == 0:
        n = _integer("shape", value, rule)
        ny, nx = n, n
    else:
        try:
            pair = list(value)
        except TypeError:
            raise _input_error("shape", rule, value) from None
        if len(pair) != 2:
            raise _input_error("shape", rule, value)
        ny, nx = (_integer("shape", v, rule) for v in pair)
    if nx < 2 or ny < 2:
        raise _input_error("shape", "(ny, nx): two integers >= 2", (ny, nx))
    return (ny, nx)


def _heights(a: Any) -> np.ndarray:
    """Heights as a C-contiguous float64 array of two dimensions."""
    arr = _np.asarray(a)
    if arr.dtype.kind not in "fiu":
        raise TypeError(f"heights: an array of real numbers is needed, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise _input_error("heights", f"an array of shape (ny, nx) is needed, got {arr.shape}")
    return _np.ascontiguousarray(arr, dtype=_np.float64)


@_dataclass(frozen=True)
class Topography:
    """Heights on a regular grid: ``heights[j, i]`` (m) at ``(x, y) = (i dx, j dy)``.

    A generated topography is one period of a periodic surface, ``size = (nx dx, ny dy)``.
    """

    heights: np.ndarray
    """Heights, m, shape (ny, nx) (NaN at invalid points only for ``read(keep_invalid=True)``)."""
    spacing: Tuple[float, float]
    """Point spacing (dx, dy), m."""
    path: Optional[str] = None
    """The file it was read from (None when generated or built)."""
    invalid: int = 0
    """Invalid (unmeasured) points of the file (NaN in ``heights``)."""

    def __post_init__(self) -> None:
        object.__setattr__(self, "heights", _heights(self.heights))
        object.__setattr__(self, "spacing", _pair("spacing", self.spacing))

    @property
    def shape(self) -> Tuple[int, int]:
        """(ny, nx)."""
        return (int(self.heights.shape[0]), int(self.heights.shape[1]))

    @property
    def size(self) -> Tuple[float, float]:
        """The periods (Lx, Ly) = (nx dx, ny dy), m: the window of a periodic contact."""
        ny, nx = self.shape
        return (nx * self.spacing[0], ny * self.spacing[1])

    @property
    def x(self) -> np.ndarray:
        """Point coordinates along x, ``i dx``, m (shape (nx,))."""
        return _np.arange(self.shape[1]) * self.spacing[0]

    @property
    def y(self) -> np.ndarray:
        """Point coordinates along y, ``j dy``, m (shape (ny,))."""
        return _np.arange(self.shape[0]) * self.spacing[1]

    def gap(self) -> np.ndarray:
        """The initial separation of this surface (peaks up) from a rigid flat touching its
        highest point, ``max(h) - h`` (m, >= 0): the ``gap`` of :func:`tribo.normal_contact`
        (its element (iy, ix) is this point (j, i); the window is ``size``)."""
        return float(self.heights.max()) - self.heights

    def __repr__(self) -> str:
        ny, nx = self.shape
        src = f", path={self.path!r}" if self.path else ""
        return f"Topography({ny} x {nx} points, spacing={self.spacing} m{src})"


def _topo(surface: Any, spacing: Any) -> Tuple[np.ndarray, Tuple[float, float]]:
    """Heights and spacing of a :class:`Topography`, or of an array with ``spacing``."""
    if isinstance(surface, Topography):
        if spacing is not None:
            raise _input_error("spacing", "give it only with an array (a Topography has one)")
        return surface.heights, surface.spacing
    if spacing is None:
        raise _input_error("spacing", "an array of heights needs its spacing (dx, dy) in m")
    return _heights(surface), _pair("spacing", spacing)


def self_affine(
    shape: Any,
    *,
    size: Any,
    hurst: float,
    powerlaw_start: float,
    cutoff: float,
    rolloff: Optional[float] = None,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    anisotropy: Any = (1.0, 1.0),
    method: str = "filter",
    seed: int = 0,
) -> Topography:
    """A Gaussian self-affine surface, periodic by construction (docs/theory/SURFACES.md 2).

    The isotropic power law with roll-off (Persson 2006; Tamaas's ``Isopowerlaw``):
    ``C(q) = C_r`` for ``rolloff <= q < powerlaw_start``, ``C_r (q / powerlaw_start)^(-2(1 +
    hurst))`` up to ``cutoff``, 0 elsewhere; wavenumbers in rad/m (``2 pi / wavelength``),
    ``0 <= rolloff <= powerlaw_start < cutoff`` (``rolloff`` None: ``powerlaw_start``, no
    plateau), ``0 < hurst <= 1``. ``anisotropy = (s_x, s_y)`` scales the wavevector
    (``s_y > s_x``: features longer along y).

    ``shape = (ny, nx)`` points over the periods ``size = (Lx, Ly)`` (m). The level ``C_r`` is
    set by exactly one of ``rms_height`` (m) and ``rms_slope`` (the expectation over the grid's
    modes: exact for ``method="random_phase"``, the mean over seeds for ``"filter"``,
    filtered white noise, the default). ``seed``: a non-negative integer; the same arguments
    give the same surface bit for bit on every machine and thread count.
    """
    if rolloff is None:
        rolloff = powerlaw_start
    seed = _integer("seed", seed, "a non-negative integer")
    if seed < 0 or seed >= 2**64:
        raise _input_error("seed", "a non-negative integer below 2^64", seed)
    if not isinstance(method, str):
        raise _input_error("method", '"filter" or "random_phase"', method)
    heights = _tribo.surface_generate(
        _shape(shape),
        _pair("size", size),
        _number("rolloff", rolloff),
        _number("powerlaw_start", powerlaw_start),
        _number("cutoff", cutoff),
        _number("hurst", hurst),
        _pair("anisotropy", anisotropy),
        None if rms_height is None else _number("rms_height", rms_height),
        None if rms_slope is None else _number("rms_slope", rms_slope),
        method,
        seed,
    )
    ny, nx = heights.shape
    size = _pair("size", size)
    return Topography(heights, (size[0] / nx, size[1] / ny))


def spectrum_moments(
    *,
    hurst: float,
    powerlaw_start: float,
    cutoff: float,
    rolloff: Optional[float] = None,
    anisotropy: Any = (1.0, 1.0),
    shape: Any = None,
    size: Any = None,
) -> Dict[str, Dict[str, Optional[float]]]:
    """The spectral moments of the power law of :func:`self_affine` with the plateau
    ``C_r = 1`` (multiply by the plateau; rms values by its square root).

    ``"continuous"``: the closed-form integrals ``m_pq = int q_x^p q_y^q C(q) d^2q``
    (docs/theory/SURFACES.md 1); with ``shape = (ny, nx)`` and ``size`` (m) also
    ``"discrete"``, the sums over the grid's modes (what a generated surface carries on
    average), and ``"discrete_std"``, the standard deviations of each over filtered-noise
    realisations. Each a dict: ``m00``, ``m20``, ``m02``, ``m11``, ``m40``, ``m04``, ``m22``,
    ``rms_height``, ``rms_slope``, ``rms_curvature``, ``bandwidth`` (Nayak's alpha).
    """
    if rolloff is None:
        rolloff = powerlaw_start
    if (shape is None) != (size is None):
        raise _input_error("size", "give both shape and size, or neither")
    return _tribo.spectrum_moments(
        float(rolloff),
        float(powerlaw_start),
        float(cutoff),
        float(hurst),
        _pair("anisotropy", anisotropy),
        None if shape is None else _shape(shape),
        None if size is None else _pair("size", size),
    )


def moments(surface: Any, spacing: Any = None) -> Dict[str, Optional[float]]:
    """The spectral moments of a topography (a :class:`Topography`, or heights (ny, nx) in m
    with ``spacing = (dx, dy)`` in m), ``m_pq = sum_q q_x^p q_y^q |h_q|^2`` (Nayak 1971; the
    mean excluded): ``m00`` (m^2), ``m20``, ``m02``, ``m11`` (1), ``m40``, ``m04``, ``m22``
    (1/m^2), with ``rms_height`` (m), ``rms_slope`` (spectral), ``rms_slope_fd`` (forward
    differences), ``rms_curvature`` (of the mean curvature, 1/m) and Nayak's ``bandwidth``
    ``m00 m40 / m20^2`` (None without x-variation)."""
    h, s = _topo(surface, spacing)
    return _tribo.surface_statistics(h, s)


def rms_heights(surface: Any, spacing: Any = None) -> float:
    """The rms height about the mean, m (Tamaas: ``Statistics2D.computeRMSHeights``)."""
    h, s = _topo(surface, spacing if spacing is not None or isinstance(surface, Topography)
                 else (1.0, 1.0))
    return float(_tribo.surface_statistics(h, s)["rms_height"])


def rms_slopes(surface: Any, spacing: Any = None, *, method: str = "spectral") -> float:
    """The rms slope ``sqrt(<|grad h|^2>)``: ``method="spectral"`` (of the trigonometric
    interpolant, ``sqrt(m20 + m02)``; Tamaas's ``computeSpectralRMSSlope``) or ``"fd"``
    (periodic forward differences; Tamaas's ``computeFDRMSSlope``), dimensionless."""
    if method not in ("spectral", "fd"):
        raise _input_error("method", 'one of "spectral", "fd"', method)
    m = moments(surface, spacing)
    return float(m["rms_slope"] if method == "spectral" else m["rms_slope_fd"])


def rms_curvature(surface: Any, spacing: Any = None) -> float:
    """The rms of the mean curvature ``(h_xx + h_yy) / 2`` (spectral), 1/m."""
    return float(moments(surface, spacing)["rms_curvature"])


@_dataclass(frozen=True)
class PowerLawFit:
    """A least-squares power law ``C = prefactor q^exponent`` through PSD bins."""

    exponent: float
    """The exponent (``-2 (1 + H)`` for a self-affine surface)."""
    hurst: float
    """The Hurst exponent ``H = -exponent/2 - 1``."""
    prefactor: float
    """The prefactor, m^4 (rad/m)^(-exponent)."""
    bins: int
    """Bins used."""


@_dataclass(frozen=True)
class RadialPSD:
    """The radially averaged power spectrum: ``C = |h_q|^2 / dq^2`` averaged over annuli of
    width ``2 pi / min(Lx, Ly)`` up to the smaller Nyquist wavenumber (docs/theory/SURFACES.md
    3)."""

    q: np.ndarray
    """Mean wavenumber of each bin, rad/m."""
    psd: np.ndarray
    """Mean PSD of each bin, m^4."""
    modes: np.ndarray
    """Modes per bin."""

    def fit(self, q_min: float = 0.0, q_max: float = _math.inf) -> PowerLawFit:
        """The power law fitted to the bins with ``q_min <= q <= q_max`` (rad/m), weighted by
        their modes; raises :class:`InputError` (``q_range``) with fewer than 2 bins."""
        d = _tribo.surface_fit_power_law(
            [float(v) for v in self.q],
            [float(v) for v in self.psd],
            [int(v) for v in self.modes],
            float(q_min),
            float(q_max),
        )
        return PowerLawFit(**d)


def psd(surface: Any, spacing: Any = None) -> RadialPSD:
    """The radially averaged PSD of a topography (Tamaas: ``computePowerSpectrum`` gives the
    2D spectrum; this is its radial average in tribo's normalisation, ``<h^2> = int C d^2q``)."""
    h, s = _topo(surface, spacing)
    q, c, n = _tribo.surface_psd(h, s)
    return RadialPSD(q, c, n)


def autocorrelation(surface: Any, spacing: Any = None) -> np.ndarray:
    """The periodic autocorrelation ``R(r) = mean (h(x) - <h>)(h(x + r) - <h>)``, m^2, shape
    (ny, nx): the lag ``(i dx, j dy)`` at ``[j, i]`` (beyond half the period the negative lags,
    wrapped: ``np.fft.fftshift`` centres it); ``R[0, 0]`` is the variance."""
    h, s = _topo(surface, spacing)
    return _tribo.surface_autocorrelation(h, s)


def detrend(surface: Any, degree: int = 1, spacing: Any = None) -> Topography:
    """The topography minus its least-squares polynomial of total degree ``degree`` (0 the
    mean, 1 the plane, 2 a quadric: the form of a ball or a cylinder; at most 10)."""
    h, s = _topo(surface, spacing)
    if int(degree) < 0:
        raise _input_error("degree", "an integer from 0 to 10", degree)
    residual, _trend, _coefficients = _tribo.surface_detrend(h, s, int(degree))
    path = surface.path if isinstance(surface, Topography) else None
    return Topography(residual, s, path)


def resample(
    surface: Any,
    shape: Any,
    new_spacing: Any,
    *,
    periodic: bool = True,
    spacing: Any = None,
) -> Topography:
    """The topography resampled onto ``shape = (ny, nx)`` points of ``new_spacing = (dx, dy)``
    (m) from the same origin by Keys' bicubic convolution (C1; Keys 1981), wrapping around
    (``periodic``: a generated surface) or within the measured extent (``periodic=False``:
    a measurement; a grid beyond it raises :class:`InputError`)."""
    h, s = _topo(surface, spacing)
    out = _tribo.surface_resample(h, s, _shape(shape), _pair("new_spacing", new_spacing),
                                  bool(periodic))
    return Topography(out, _pair("new_spacing", new_spacing))


def read(
    path: Union[str, "os.PathLike[str]"],
    *,
    spacing: Any = None,
    height_unit: float = 1.0,
    keep_invalid: bool = False,
) -> Topography:
    """A measured topography from a file, the format by the extension: ISO 25178-72 ``.x3p``,
    ``.npy``, or an ASCII/CSV grid (``.csv``, ``.txt``, ``.asc``, ``.dat``; tribo's
    ``# dx:`` / ``# dy:`` header or Gwyddion's export header) (docs/theory/SURFACES.md 5).

    ``spacing = (dx, dy)`` (m) for files without one (npy, a headerless grid; checked against
    the file's where it has one); ``height_unit``: metres per stored unit for files without
    units (npy, headerless grids; 1e-6 for micrometres). Invalid (unmeasured) points are
    refused (:class:`InputError` naming the file, their count and the first one) unless
    ``keep_invalid``, which keeps them as NaN (the statistics then refuse the topography).
    """
    heights, sp, invalid = _tribo.surface_read(
        _os.fspath(path),
        None if spacing is None else _pair("spacing", spacing),
        float(height_unit),
        bool(keep_invalid),
    )
    return Topography(heights, sp, _os.fspath(path), int(invalid))


# ---------------------------------------------------------------------------------------------
# Tamaas-like generator objects
# ---------------------------------------------------------------------------------------------


class Isopowerlaw:
    """The isotropic power law of Tamaas's ``Isopowerlaw2D``: ``q0`` (roll-off), ``q1``
    (start of the power law), ``q2`` (cutoff) in units of the fundamental wavenumber
    ``2 pi / Lx`` (Tamaas's integer wavenumbers), and ``hurst``. The same spectrum as
    :func:`self_affine`'s ``rolloff``, ``powerlaw_start``, ``cutoff`` = ``2 pi q / Lx``."""

    __slots__ = ("q0", "q1", "q2", "hurst")

    def __init__(self, q0: float = 1.0, q1: float = 1.0, q2: float = 2.0,
                 hurst: float = 0.8) -> None:
        self.q0: float = q0
        """Roll-off, in units of 2 pi / Lx."""
        self.q1: float = q1
        """Start of the power law, in units of 2 pi / Lx."""
        self.q2: float = q2
        """Short cutoff, in units of 2 pi / Lx."""
        self.hurst: float = hurst
        """Hurst exponent, in (0, 1]."""

    def wavenumbers(self, lx: float) -> Tuple[float, float, float]:
        """(rolloff, powerlaw_start, cutoff) in rad/m for the period ``lx`` (m)."""
        k = 2.0 * _math.pi / float(lx)
        return (k * float(self.q0), k * float(self.q1), k * float(self.q2))

    def __repr__(self) -> str:
        return f"Isopowerlaw(q0={self.q0}, q1={self.q1}, q2={self.q2}, hurst={self.hurst})"


_TAMAAS_FIELDS = {"rolloff": "spectrum.q0", "powerlaw_start": "spectrum.q1",
                  "cutoff": "spectrum.q2", "hurst": "spectrum.hurst", "seed": "random_seed"}


class SurfaceGeneratorFilter:
    """Tamaas's ``SurfaceGeneratorFilter2D``: ``SurfaceGeneratorFilter((ny, nx))``, set
    ``spectrum`` (an :class:`Isopowerlaw`) and ``random_seed``, call :meth:`buildSurface`
    (filtered white noise, as :func:`self_affine` with ``method="filter"``).

    The level, as Tamaas's: every Fourier coefficient has ``E|h_q|^2 = Phi(q)``, with ``Phi = 1``
    on the plateau (the spectrum's shape at the integer wavenumbers), whatever ``size`` (the
    periods, m; Tamaas's unit square by default). Set ``rms_height`` or ``rms_slope`` instead
    to normalise (or divide the surface by its rms slope, as Tamaas users do). The random
    numbers differ from Tamaas's: the same seed gives another (equally distributed) surface.
    """

    _method = "filter"

    def __init__(self, shape: Any, size: Any = (1.0, 1.0)) -> None:
        self.shape: Tuple[int, int] = _shape(shape)
        """The grid (ny, nx)."""
        self.size: Tuple[float, float] = _pair("size", size)
        """The periods (Lx, Ly), m."""
        self.spectrum: Optional[Isopowerlaw] = None
        """The spectrum (an :class:`Isopowerlaw`)."""
        self.random_seed: int = 0
        """The seed (a non-negative integer)."""
        self.rms_height: Optional[float] = None
        """Target rms height (m), or None (Tamaas's level)."""
        self.rms_slope: Optional[float] = None
        """Target rms slope, or None (Tamaas's level)."""

    @property
    def spacing(self) -> Tuple[float, float]:
        """(dx, dy) = (Lx / nx, Ly / ny), m."""
        return (self.size[0] / self.shape[1], self.size[1] / self.shape[0])

    def buildSurface(self) -> np.ndarray:  # noqa: N802 (Tamaas's name)
        """The heights, shape (ny, nx) (:meth:`build` for a :class:`Topography`)."""
        return self.build().heights

    def build(self) -> Topography:
        """The surface as a :class:`Topography` of spacing :attr:`spacing`."""
        sp = self.spectrum
        if not isinstance(sp, Isopowerlaw):
            raise _input_error("spectrum", "set spectrum to an Isopowerlaw first", sp)
        ql, qr, qs = sp.wavenumbers(self.size[0])
        args = dict(size=self.size, hurst=float(sp.hurst), rolloff=ql, powerlaw_start=qr,
                    cutoff=qs, method=self._method, seed=int(self.random_seed))
        try:
            if self.rms_height is None and self.rms_slope is None:
                m = spectrum_moments(hurst=args["hurst"], powerlaw_start=qr, cutoff=qs,
                                     rolloff=ql, shape=self.shape, size=self.size)
                dq2 = (2.0 * _math.pi) ** 2 / (self.size[0] * self.size[1])
                level = _math.sqrt(m["discrete"]["m00"] / dq2)
                return self_affine(self.shape, rms_height=level, **args)
            return self_affine(self.shape, rms_height=self.rms_height, rms_slope=self.rms_slope,
                               **args)
        except InputError as e:
            field = getattr(e, "field", "")
            if field in _TAMAAS_FIELDS:
                raise _input_error(_TAMAAS_FIELDS[field], getattr(e, "rule", str(e)),
                                   getattr(e, "value", "")) from None
            raise

    def __repr__(self) -> str:
        return f"{type(self).__name__}(shape={self.shape}, spectrum={self.spectrum!r})"


class SurfaceGeneratorRandomPhase(SurfaceGeneratorFilter):
    """Tamaas's ``SurfaceGeneratorRandomPhase2D``: exact amplitudes ``|h_q| = sqrt(Phi(q))``
    and random phases (:func:`self_affine` with ``method="random_phase"``): every spectral
    statistic equals the spectrum's for any seed."""

    _method = "random_phase"


def __dir__() -> List[str]:
    # Tab completion and dir() list the API alone; the typing names above are real module
    # attributes so that typing.get_type_hints() resolves the (string) annotations.
    return sorted(__all__)
