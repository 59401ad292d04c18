"""tribo for Python: contact mechanics and tribo-fatigue, numpy in and out.

A thin, typed layer over the compiled module ``tribo._tribo`` (the Rust crates ``tribo`` and
``tribo-case``): the same solvers and the same case pipeline as the ``tribo`` command line.

Units are SI throughout: lengths in m, pressures, stresses and moduli in Pa, forces in N,
angles in rad.

Quick start::

    import numpy as np, tribo
    h = tribo.hertz(load=100.0, radius=0.01, composite_modulus=115e9)
    h.max_pressure                          # Pa

    x = np.linspace(-0.5e-3, 0.5e-3, 128, endpoint=False) + 0.5e-3 / 128
    X, Y = np.meshgrid(x, x)                # shape (ny, nx), C order
    r = tribo.normal_contact((X**2 + Y**2) / (2 * 0.01), size=(1e-3, 1e-3),
                             composite_modulus=115e9, load=100.0)
    r.pressure.max(), r.residual

    t = tribo.surface.self_affine((128, 128), size=(1e-3, 1e-3), hurst=0.8,
                                  powerlaw_start=2e4, cutoff=2e5, rms_slope=0.1, seed=1)
    rough = tribo.normal_contact(t.gap(), size=t.size, composite_modulus=115e9,
                                 mean_pressure=50e6, periodic=True)
    rough.contact_fraction                  # real over nominal contact area

    field = tribo.stress_field(r, E=210e9, nu=0.3, x=x, y=[0.0], z=x[x >= 0])
    field["von_mises"]                      # an xarray.Dataset (dims z, y, x; units in attrs)
    tribo.damage(field, {"sigma_int": 0.5e9})["sigma_int"].volume   # V (22), m^3

    res = tribo.run(tribo.Case.example("sphere-on-flat"))
    res.summary["contact"]["max_pressure"]  # the numbers of `tribo run --json`
    res.write("out")                        # the CLI's files

    tribo.fatigue.fit(df)                   # pyLife's Woehler keys k_1, ND, SD, TN, TS

Errors: :class:`InputError` (a ``ValueError``; ``.field``, ``.value``, ``.rule``) for bad
input, :class:`ConvergenceError` (``.residual``, ``.iterations``, ``.tolerance``) for a solver
stopped before its tolerance, :class:`SolverError` for other failures.

Long computations release the GIL: several threads may solve at once.
"""

from __future__ import annotations

# The imports are bound to private names (and the typing names exist for type checkers only,
# the annotations being strings): `dir(tribo)` and tab completion show the API alone.
import json as _json
import math as _math
import os as _os
from collections.abc import Mapping as _Mapping
from dataclasses import dataclass as _dataclass
from pathlib import Path as _Path

import numpy as _np

from . import _tribo
from ._tribo import ConvergenceError, HertzContact, InputError, SolverError
from ._field import Damage, damage, energy_criterion, stress_field, _to_field
from . import fatigue
from . import surface

# The names of the annotations (strings, PEP 563) are bound for real, so that
# typing.get_type_hints() resolves them; `__dir__` below keeps them out of dir(tribo).
import os
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

del annotations  # the __future__ feature's name: not part of the API

__version__: str = _tribo.__version__

__all__ = [
    "Case",
    "ConvergenceError",
    "CoupledContact",
    "Damage",
    "HertzContact",
    "InputError",
    "NormalContact",
    "NormalSolver",
    "Results",
    "SolverError",
    "TangentialContact",
    "composite_modulus",
    "coupled_contact",
    "damage",
    "energy_criterion",
    "examples",
    "fatigue",
    "hertz",
    "normal_contact",
    "run",
    "stress_field",
    "study",
    "surface",
    "tangential_contact",
]

_INF = _math.inf


def composite_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """The composite modulus E* of two bodies, Pa.

    ``1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2`` (Johnson 1985, eq. (4.22)), with Young's
    moduli ``E1``, ``E2`` in Pa and Poisson's ratios ``nu1``, ``nu2`` in (-1, 0.5).

    Raises :class:`InputError` naming ``body1.E``/``body1.nu``/... for a value out of range.
    """
    return _tribo.composite_modulus(float(E1), float(nu1), float(E2), float(nu2))


def hertz(
    *,
    load: Optional[float] = None,
    approach: Optional[float] = None,
    radius: Optional[float] = None,
    radii1: Optional[Sequence[float]] = None,
    radii2: Sequence[float] = (_INF, _INF),
    angle_between: float = 0.0,
    composite_modulus: float,
) -> HertzContact:
    """The exact Hertz solution of a point contact (Johnson 1985, ch. 4).

    Give the geometry as ``radius`` (m: a sphere on a flat, or the effective radius
    ``1/R = 1/R1 + 1/R2`` of two spheres) or as the principal radii of both bodies,
    ``radii1``, ``radii2`` (m; positive convex, negative concave, ``inf`` flat; body 2's first
    principal plane at ``angle_between`` rad from body 1's). Give exactly one of ``load``
    (normal force, N) and ``approach`` (approach of distant points, m). ``composite_modulus``
    is E* in Pa (:func:`composite_modulus`).

    Elliptical contacts are solved exactly with complete elliptic integrals (not the
    Hamrock-Brewe curve fits).

    Returns a :class:`HertzContact`: ``semi_major``, ``semi_minor``, ``radius`` (m),
    ``max_pressure``, ``mean_pressure`` (Pa), ``approach`` (m), ``normal_load`` (N),
    ``contact_area`` (m^2), ``angle`` (rad), ``composite_modulus`` (Pa) and
    ``pressure(x, y)`` (Pa at points in m).
    """
    if (radius is None) == (radii1 is None):
        raise _input_error("radius", "give exactly one of radius and radii1 (m)")
    if radius is not None:
        r1 = [float(radius), float(radius)]
        r2 = [_INF, _INF]
    else:
        r1 = [float(v) for v in radii1]  # type: ignore[union-attr]
        r2 = [float(v) for v in radii2]
    return _tribo.hertz(
        r1,
        r2,
        float(angle_between),
        float(composite_modulus),
        None if load is None else float(load),
        None if approach is None else float(approach),
    )


def _input_error(field: str, rule: str, value: Any = "") -> InputError:
    """An :class:`InputError` with its ``field``, ``value`` and ``rule`` set."""
    err = InputError(f"{field}: {rule}")
    err.field, err.value, err.rule = field, str(value), rule
    return err


def _grid_array(name: str, a: Any) -> np.ndarray:
    """``a`` as a C-contiguous float64 array of two dimensions, without a copy when it is one.

    Real arrays of another dtype (float32, integers) or layout (Fortran order, strided views)
    are converted (a copy; float32 and integers up to 2**53 convert exactly); complex,
    boolean, object and string arrays are refused with a TypeError naming the argument.
    """
    arr = _np.asarray(a)
    if arr.dtype.kind not in "fiu":
        raise TypeError(
            f"{name}: an array of real numbers is needed (float64 preferred), got dtype {arr.dtype}"
        )
    if arr.ndim != 2:
        raise _input_error(name, f"an array of shape (ny, nx) is needed, got shape {arr.shape}")
    return _np.ascontiguousarray(arr, dtype=_np.float64)


@_dataclass(frozen=True)
class NormalContact:
    """The solution of a normal contact problem on a grid, with its convergence record.

    Arrays have the shape (ny, nx) of the input gap, element (iy, ix) at ``(y[iy], x[ix])``.
    """

    pressure: np.ndarray
    """Contact pressure at element centres, Pa (>= 0)."""
    gap: np.ndarray
    """Deformed gap at element centres, m (0 in contact)."""
    x: np.ndarray
    """Element centres along x, m (shape (nx,))."""
    y: np.ndarray
    """Element centres along y, m (shape (ny,))."""
    approach: float
    """Approach of distant points, m."""
    normal_load: float
    """Normal force, N."""
    contact_area: float
    """Area of the elements in contact, m^2."""
    contact_elements: int
    """Number of elements in contact."""
    iterations: int
    """Iterations done (CG iterations or active-set sweeps)."""
    residual: float
    """Final complementarity residual, relative to the maximum pressure (dimensionless)."""
    solve_time_s: float
    """Wall time of the solve inside the library, s (the rest of the call is Python's)."""
    size: Optional[Tuple[float, float]] = None
    """The window (Lx, Ly), m (what :func:`stress_field` needs with the pressure)."""
    displacement: Optional[np.ndarray] = None
    """Combined elastic displacement of the surfaces u_z1 + u_z2 = gap - h + approach at
    element centres, m (None for the normal solution inside :class:`CoupledContact` and
    :meth:`Results.fields`). Periodic: measured from its mean plane (zero mean)."""
    periodic: bool = False
    """Whether the window was one period of a periodic surface."""

    @property
    def max_pressure(self) -> float:
        """The maximum contact pressure, Pa."""
        return float(self.pressure.max())

    @property
    def mean_pressure(self) -> float:
        """The normal force over the window's area, F / (Lx Ly), Pa (periodic: the nominal
        pressure)."""
        if self.size is None:
            raise _input_error("size", "the window is not known")
        return self.normal_load / (self.size[0] * self.size[1])

    @property
    def contact_fraction(self) -> float:
        """The fraction of the window in contact, A / (Lx Ly) (periodic: the real over the
        nominal contact area)."""
        return float(self.contact_elements) / float(self.pressure.size)

    @property
    def contact(self) -> np.ndarray:
        """The contact mask (pressure > 0), bool, shape (ny, nx)."""
        return self.pressure > 0.0


def _iterations(value: Any) -> int:
    """``max_iterations`` as a positive integer, or an InputError naming it."""
    rule = "an integer >= 1"
    if isinstance(value, (bool, np.bool_)) or np.ndim(value) != 0:
        raise _input_error("max_iterations", rule, value)
    try:
        n = int(value)
        exact = float(value) == n
    except (TypeError, ValueError, OverflowError):
        raise _input_error("max_iterations", rule, value) from None
    if not exact or n < 1 or n >= 2**63:
        raise _input_error("max_iterations", rule, value)
    return n


def _periodic_load(
    load: Optional[float],
    mean_pressure: Optional[float],
    size: Tuple[float, float],
    periodic: bool,
) -> Optional[float]:
    """The force (N) of a solve given its ``load`` or ``mean_pressure`` (periodic only: the
    force per period is the mean pressure times the period area Lx Ly)."""
    if mean_pressure is None:
        return None if load is None else float(load)
    if not periodic:
        raise _input_error("mean_pressure",
                           "only for periodic=True (give the load, N, on a finite window)",
                           mean_pressure)
    if load is not None:
        raise _input_error("mean_pressure", "give exactly one of load (N) and mean_pressure (Pa)",
                           mean_pressure)
    return float(mean_pressure) * size[0] * size[1]


def normal_contact(
    gap: Any,
    *,
    size: Tuple[float, float],
    composite_modulus: float,
    load: Optional[float] = None,
    approach: Optional[float] = None,
    mean_pressure: Optional[float] = None,
    tolerance: float = 1e-10,
    max_iterations: int = 10_000,
    method: str = "cg",
    initial_pressure: Any = None,
    periodic: bool = False,
    kernel: str = "element",
) -> NormalContact:
    """Normal contact of two elastic half-spaces with unknown contact area on a grid.

    The linear complementarity problem of the paper's (16): ``p >= 0``,
    ``g = K p + h - delta >= 0``, ``p g = 0``, with Love's influence functions for
    piecewise-constant pressure (non-periodic: the window is a part of an infinite surface),
    solved by Polonsky & Keer's constrained conjugate gradients on an FFT operator
    (``method="cg"``, any grid) or by the dense active set (``method="active_set"``, small
    grids).

    ``gap``: the initial separation h (m) of the undeformed surfaces at the element centres,
    shape (ny, nx), element (iy, ix) at x = -Lx/2 + (ix + 1/2) Lx/nx and likewise in y. For
    rough surfaces give ``h = -(height1 + height2)`` shifted so that ``h.min() == 0``. A
    C-contiguous float64 array is read in place (no copy; do not write to it from another
    thread during the solve); float32, integer or Fortran-ordered arrays are converted (a
    copy); complex, boolean or object arrays raise TypeError.

    ``size = (Lx, Ly)``: the window, m, centred on the origin. ``composite_modulus``: E*,
    Pa. Exactly one of ``load`` (N, force control) and ``approach`` (m, displacement
    control). ``tolerance``: on the complementarity residual relative to the maximum
    pressure, in (0, 1). ``max_iterations`` >= 1.

    ``initial_pressure``: a warm start (Pa, shape (ny, nx); or a :class:`NormalContact`,
    e.g. the solution at a nearby load): the conjugate gradient starts from it (negative
    values set to 0; under force control scaled to the load). Same solution to the
    tolerance, fewer iterations when the guess is near it; ``method="active_set"`` ignores it.

    ``periodic=True``: the window is one period of a periodic surface (a rough flat on a
    flat, Westergaard's wavy surface; docs/theory/HALFSPACE.md 7): contact may reach the
    window's border, the load is the force per period, given as ``load`` (N) or as
    ``mean_pressure`` (Pa; the force is ``mean_pressure * Lx * Ly``), approach control and the
    active set are refused (the mean displacement of a periodic half-space is unbounded: the
    ``approach`` reported is measured from the mean plane of the deformed surface).
    ``kernel``: ``"element"`` (the default: the periodic sum of Love's element influence, the
    discretisation of the non-periodic solver) or ``"spectral"`` (the continuous multiplier
    ``2 / (E* |q|)`` at the grid frequencies, Tamaas's: compare with Tamaas like with like).

    Raises :class:`InputError` for bad input (also when the contact reaches the window's
    border of a non-periodic solve or there is no contact), :class:`ConvergenceError` (with
    ``.residual``) at the iteration limit. The GIL is released during the solve.
    """
    g = _grid_array("gap", gap)
    size = (float(size[0]), float(size[1]))
    d = _tribo.normal_contact(
        g,
        size,
        float(composite_modulus),
        _periodic_load(load, mean_pressure, size, bool(periodic)),
        None if approach is None else float(approach),
        float(tolerance),
        _iterations(max_iterations),
        str(method),
        _guess(initial_pressure, g.shape),
        bool(periodic),
        str(kernel),
    )
    return NormalContact(**d, size=size, periodic=bool(periodic))


def _guess(initial_pressure: Any, shape: Tuple[int, ...]) -> Optional[np.ndarray]:
    """A warm start's pressure (an array or a :class:`NormalContact`) as C-contiguous
    float64 of the gap's shape, or None."""
    if initial_pressure is None:
        return None
    p = _grid_array("initial_pressure", getattr(initial_pressure, "pressure", initial_pressure))
    if p.shape != tuple(shape):
        raise _input_error("initial_pressure",
                           f"the gap's shape {tuple(shape)} is needed, got {p.shape}", p.shape)
    return p


class NormalSolver:
    """Normal contact solves on one grid and one composite modulus, the FFT compliance
    operator built once and reused (a load sweep, many surfaces of one size).

    ``shape = (ny, nx)`` elements over ``size = (Lx, Ly)`` (m), ``composite_modulus`` E*
    (Pa); ``tolerance``, ``max_iterations``, ``method``, ``periodic`` and ``kernel`` as in
    :func:`normal_contact`.
    """

    __slots__ = ("_inner", "shape", "size", "periodic")

    def __init__(
        self,
        shape: Tuple[int, int],
        *,
        size: Tuple[float, float],
        composite_modulus: float,
        tolerance: float = 1e-10,
        max_iterations: int = 10_000,
        method: str = "cg",
        periodic: bool = False,
        kernel: str = "element",
    ) -> None:
        self.shape: Tuple[int, int] = (int(shape[0]), int(shape[1]))
        """The grid's shape (ny, nx)."""
        self.size: Tuple[float, float] = (float(size[0]), float(size[1]))
        """The window (Lx, Ly), m (periodic: the period)."""
        self.periodic: bool = bool(periodic)
        """Whether the window is one period of a periodic surface."""
        self._inner = _tribo.NormalSolver(
            self.shape,
            self.size,
            float(composite_modulus),
            float(tolerance),
            _iterations(max_iterations),
            str(method),
            self.periodic,
            str(kernel),
        )

    def solve(
        self,
        gap: Any,
        *,
        load: Optional[float] = None,
        approach: Optional[float] = None,
        mean_pressure: Optional[float] = None,
        initial_pressure: Any = None,
    ) -> NormalContact:
        """One solve: the gap (m, shape (ny, nx); converted as in :func:`normal_contact`)
        under exactly one of ``load`` (N), ``approach`` (m) and (periodic) ``mean_pressure``
        (Pa), from ``initial_pressure`` (Pa or a :class:`NormalContact`: a warm start, as in
        :func:`normal_contact`)."""
        g = _grid_array("gap", gap)
        d = self._inner.solve(
            g,
            _periodic_load(load, mean_pressure, self.size, self.periodic),
            None if approach is None else float(approach),
            _guess(initial_pressure, g.shape),
        )
        return NormalContact(**d, size=self.size, periodic=self.periodic)

    def load_path(
        self,
        gap: Any,
        *,
        loads: Optional[Sequence[float]] = None,
        approaches: Optional[Sequence[float]] = None,
        mean_pressures: Optional[Sequence[float]] = None,
        warm_start: bool = True,
    ) -> Iterator[NormalContact]:
        """The solutions along a load sequence, one at a time (a generator): exactly one of
        ``loads`` (N), ``approaches`` (m) and (periodic) ``mean_pressures`` (Pa). The gap is
        converted once; with ``warm_start`` each solve starts from the previous solution's
        pressure (same solutions to the tolerance, fewer iterations)."""
        given = [v is not None for v in (loads, approaches, mean_pressures)]
        if sum(given) != 1:
            raise _input_error("loads", "give exactly one of loads (N), approaches (m) and "
                               "mean_pressures (Pa)")
        g = _grid_array("gap", gap)
        previous = None
        if approaches is not None:
            steps = [(None, float(d)) for d in approaches]
        elif loads is not None:
            steps = [(float(f), None) for f in loads]
        else:
            steps = [(_periodic_load(None, float(p), self.size, self.periodic), None)
                     for p in mean_pressures]  # type: ignore[union-attr]
        for f, d in steps:
            r = NormalContact(**self._inner.solve(g, f, d, previous), size=self.size,
                              periodic=self.periodic)
            if warm_start:
                previous = r.pressure
            yield r

    def __repr__(self) -> str:
        periodic = ", periodic=True" if self.periodic else ""
        return f"NormalSolver(shape={self.shape}, size={self.size}{periodic})"


@_dataclass(frozen=True)
class TangentialContact:
    """The solution of a tangential contact problem on a grid, with its convergence record.

    Arrays have the shape (ny, nx) of the pressure given; tractions act on body 1.
    """

    traction_x: np.ndarray
    """Tangential traction q_x at element centres, Pa."""
    traction_y: np.ndarray
    """Tangential traction q_y at element centres, Pa."""
    slip: np.ndarray
    """Slip along the load direction, m (0 in the stick zone and outside the contact)."""
    stick: np.ndarray
    """Stick mask (in contact with |q| < f p), bool."""
    shift: float
    """Rigid tangential shift of body 2 relative to body 1 along the load, m (0 sliding)."""
    tangential_force: Tuple[float, float]
    """(Q_x, Q_y) = sum q dA, N."""
    stick_area: float
    """Area of the stick zone, m^2."""
    slip_area: float
    """Area of the slip zone (in contact, not sticking), m^2."""
    max_traction: float
    """Largest |q|, Pa."""
    iterations: int
    """Iterations done."""
    residual: float
    """Final residual (optimality conditions in units of the largest displacement)."""
    solve_time_s: float
    """Wall time of the solve inside the library, s."""


def tangential_contact(
    pressure: Any,
    *,
    size: Tuple[float, float],
    friction: float,
    E1: float,
    nu1: float,
    E2: float,
    nu2: float,
    tangential_load: Optional[float] = None,
    sliding: bool = False,
    angle: float = 0.0,
    tolerance: float = 1e-10,
    max_iterations: int = 10_000,
    direction: str = "parallel",
    periodic: bool = False,
    kernel: str = "element",
) -> TangentialContact:
    """Tangential contact with Coulomb friction (the paper's (8)) under a given pressure.

    Partial slip under the tangential force ``tangential_load`` (N, below ``friction`` times
    the normal force) along ``angle`` (rad from x), with the traction parallel to the load
    (Cattaneo-Mindlin's assumption, solved by constrained conjugate gradients on Love's
    tangential influence functions), or full sliding (``sliding=True``: q = f p along
    ``angle``). ``pressure`` (Pa, shape (ny, nx)) usually comes from :func:`normal_contact`
    on the same ``size = (Lx, Ly)`` (m); it is read in place when C-contiguous float64 and
    converted otherwise, as in :func:`normal_contact`. ``E1``, ``nu1``, ``E2``, ``nu2``:
    Young's moduli (Pa) and Poisson's ratios of both bodies. The normal-tangential coupling
    of dissimilar materials is left out here (a case with ``[contact] friction`` includes it).

    ``direction``: ``"parallel"`` (the traction parallel to the load, as above) or ``"free"``
    (the traction's direction free: the full 2D problem of Coulomb friction, the slip
    opposite to the traction in each slipping element; the stick zone and the traction
    then differ from Cattaneo-Mindlin's by the Poisson-ratio effect, docs/theory/HALFSPACE.md).

    ``periodic=True``: the window is one period (the periodic Cerruti compliances with the
    ``kernel`` of :func:`normal_contact`; a uniform shear moves the surface rigidly, so the
    displacements are measured from their mean), for the pressure of a periodic
    :func:`normal_contact`; ``tangential_load`` is the force per period (N).

    Raises :class:`InputError` (e.g. ``tangential_load`` at or above f F_N) and
    :class:`ConvergenceError` as :func:`normal_contact` does. The GIL is released.
    """
    if direction not in ("parallel", "free"):
        raise _input_error("direction", 'one of "parallel", "free"', direction)
    p = _grid_array("pressure", pressure)
    d = _tribo.tangential_contact(
        p,
        (float(size[0]), float(size[1])),
        float(friction),
        (float(E1), float(nu1), float(E2), float(nu2)),
        None if tangential_load is None else float(tangential_load),
        bool(sliding),
        float(angle),
        float(tolerance),
        _iterations(max_iterations),
        direction == "free",
        bool(periodic),
        str(kernel),
    )
    return TangentialContact(**d)


@_dataclass(frozen=True)
class CoupledContact:
    """The solution of the coupled normal-tangential problem of dissimilar bodies."""

    normal: NormalContact
    """The normal solution of the last pass (the pressure changed by the coupling)."""
    tangential: TangentialContact
    """The tangential solution of the last pass."""
    passes: int
    """Alternation passes done (1 where the coupling vanishes: similar materials)."""
    change: float
    """Largest relative change of p (to p_max) and q (to f p_max) in the last pass."""
    beta: float
    """Dundurs' beta of the pair (dimensionless)."""
    solve_time_s: float
    """Wall time of the solve inside the library, s."""


def coupled_contact(
    gap: Any,
    *,
    size: Tuple[float, float],
    friction: float,
    E1: float,
    nu1: float,
    E2: float,
    nu2: float,
    load: Optional[float] = None,
    approach: Optional[float] = None,
    tangential_load: Optional[float] = None,
    sliding: bool = False,
    angle: float = 0.0,
    direction: str = "parallel",
    tolerance: float = 1e-8,
    max_passes: int = 100,
) -> CoupledContact:
    """Normal and tangential contact of dissimilar bodies with the coupling between them
    (Johnson 1985 sec. 5.4; docs/theory/HALFSPACE.md 1.1): the pressure moves the surfaces
    tangentially and the traction normally in proportion to Dundurs' beta, so both problems
    are solved by alternation (the solver of a case with ``[contact] friction`` and two
    materials) until the largest change of p (relative to p_max) and of q (relative to
    f p_max) in a pass is below ``tolerance`` (> 0; each pass contracts by about |beta|).

    ``gap`` (m, shape (ny, nx)) and ``size`` as in :func:`normal_contact`; the materials
    ``E1``, ``E2`` (Pa), ``nu1``, ``nu2``; exactly one of ``load`` (N) and ``approach`` (m);
    exactly one of ``tangential_load`` (N, partial slip) and ``sliding=True`` along
    ``angle`` (rad from x); ``direction``: ``"parallel"`` or ``"free"`` as in
    :func:`tangential_contact`; ``friction`` f > 0. Raises :class:`InputError`, and
    :class:`ConvergenceError` (``.residual`` the last change) at ``max_passes``. The GIL is
    released.
    """
    if direction not in ("parallel", "free"):
        raise _input_error("direction", 'one of "parallel", "free"', direction)
    g = _grid_array("gap", gap)
    size = (float(size[0]), float(size[1]))
    d = _tribo.coupled_contact(
        g,
        size,
        (float(E1), float(nu1), float(E2), float(nu2)),
        float(friction),
        None if load is None else float(load),
        None if approach is None else float(approach),
        None if tangential_load is None else float(tangential_load),
        bool(sliding),
        float(angle),
        direction == "free",
        float(tolerance),
        int(max_passes),
    )
    return CoupledContact(
        normal=NormalContact(**d["normal"], solve_time_s=d["solve_time_s"], size=size),
        tangential=TangentialContact(**d["tangential"], solve_time_s=d["solve_time_s"]),
        passes=d["passes"],
        change=d["change"],
        beta=d["beta"],
        solve_time_s=d["solve_time_s"],
    )


def _plain(obj: Any) -> Any:
    """Nested mappings and sequences with numpy arrays and scalars turned into lists and
    Python numbers (what the case reader takes)."""
    if isinstance(obj, _Mapping):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (_np.ndarray, _np.generic)):
        return obj.tolist()
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    return obj


class Case:
    """A validated case of either kind: a half-space case or a 2D boundary element case
    (``kind = "bem2d"``), with the keys of a case file (docs/user/case-halfspace.md,
    docs/user/case-bem2d.md).

    Build one with :meth:`from_toml`, :meth:`from_dict` or :meth:`example`; run it with
    :func:`run`.
    """

    __slots__ = ("_inner",)

    def __init__(self, inner: "_tribo.Case") -> None:
        self._inner = inner

    @classmethod
    def from_toml(cls, source: Union[str, "os.PathLike[str]"]) -> "Case":
        """A case from a TOML file (a path, ``str`` or ``os.PathLike``) or a TOML text.

        A ``str`` is taken as a path when it has no newline and names an existing file (or
        ends in ``.toml``); otherwise as the case text. Relative paths inside a file (height
        maps, meshes) resolve against its folder; inside a text against the working
        directory. Raises :class:`InputError` naming the field and the rule (the parser's
        message with line and column for a bad file), or FileNotFoundError.
        """
        if isinstance(source, _os.PathLike) or (
            isinstance(source, str)
            and "\n" not in source
            and (source.endswith(".toml") or _os.path.isfile(source))
        ):
            path = _Path(source)
            text = path.read_text(encoding="utf-8")
            return cls(_tribo.Case.from_toml_text(text, str(path), str(path.parent)))
        return cls(_tribo.Case.from_toml_text(source, "<string>", None))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], base_dir: Optional[str] = None) -> "Case":
        """A case from nested dicts with the keys of a case file.

        Values are numbers in SI units, strings (also with units: ``"201 GPa"``), booleans,
        lists and dicts, numpy arrays and scalars (e.g. ``body1.surface.heights`` as a
        (ny, nx) array); ``None`` values are left out (the key's default). ``base_dir``
        resolves relative paths. Validated by the rules of a case file: :class:`InputError`
        names the field.
        """
        return cls(_tribo.Case.from_dict(_plain(data), "<dict>", base_dir))

    @classmethod
    def example(cls, name: str) -> "Case":
        """An embedded example case (:func:`examples` lists the names)."""
        return cls(_tribo.Case.example(name))

    @property
    def kind(self) -> str:
        """``"halfspace"`` or ``"bem2d"``."""
        return self._inner.kind

    @property
    def title(self) -> str:
        """The case's title."""
        return self._inner.title

    @property
    def toml(self) -> str:
        """The case's TOML text."""
        return self._inner.toml

    def __reduce__(self) -> Tuple[Any, Tuple[str, str, Optional[str]]]:
        # Pickled as its text, its name and its folder (read again on unpickling): a case
        # crosses to another process (multiprocessing, Dask workers) and is the same case.
        base = self._inner.base_dir
        return (_case_from_state, (self.toml, self._inner.source,
                                   None if base is None else str(base)))

    def __repr__(self) -> str:
        return f"Case(kind={self.kind!r}, title={self.title!r})"


def _case_from_state(text: str, source: str, base_dir: Optional[str]) -> Case:
    """A pickled :class:`Case` read back (``Case.__reduce__``)."""
    return Case(_tribo.Case.from_toml_text(text, source, base_dir))


class Results:
    """The results of :func:`run`: the summary (the numbers of ``tribo run --json``), the
    contact fields of a half-space run as numpy arrays, and :meth:`write` for the CLI's files.
    """

    __slots__ = ("_inner", "_summary", "case")

    def __init__(self, inner: "_tribo.Results", case: Case) -> None:
        self._inner = inner
        self._summary: Optional[Dict[str, Any]] = None
        self.case: Case = case
        """The case that was run."""

    @property
    def summary(self) -> Dict[str, Any]:
        """The summary as nested dicts: the keys and units of ``summary.json``
        (docs/user/outputs.md), the same numbers as ``tribo run --json`` (timings aside)."""
        if self._summary is None:
            self._summary = _json.loads(self._inner.summary_json())
        return self._summary

    def fields(self) -> Optional[Dict[str, np.ndarray]]:
        """The contact fields of a half-space run: ``pressure`` (Pa), ``gap`` (m) of shape
        (ny, nx), ``x``, ``y`` (m), and with friction ``traction_x``, ``traction_y`` (Pa) and
        the ``stick`` mask; the scalars of the normal solution as well. None for a 2D case."""
        return self._inner.fields()

    def field(self, as_xarray: Optional[bool] = None) -> Any:
        """The stress field of a half-space run with ``[field]``, as :func:`stress_field`
        returns it (an ``xarray.Dataset``, or a dict without xarray or with
        ``as_xarray=False``): the arrays of the CLI's ``stress.vti`` bit for bit, with the
        damage criteria's ``psi_<name>`` where the case has ``[damage]``; the case's
        evaluation method, edge treatment, body, E and nu (and the bulk stress superposed)
        in the attributes. None for a 2D case or a case without ``[field]``."""
        d = self._inner.field()
        return None if d is None else _to_field(d, as_xarray)

    def write(self, directory: Union[str, "os.PathLike[str]"]) -> List[str]:
        """Writes the files ``tribo run -o directory`` writes (CSV, VTK, PNG, summary.json)
        and returns their names (the ``outputs`` of the summary). The directory is created if
        needed; an earlier run's files in it are removed."""
        return self._inner.write(_os.fspath(directory))

    def __repr__(self) -> str:
        return f"Results(case={self.case!r})"


def run(case: Case) -> Results:
    """Runs a case through the pipeline of ``tribo run`` (the GIL released).

    Raises :class:`InputError` for a case the solver refuses (the contact reaching the
    window, no contact), :class:`ConvergenceError` (``.residual``) for a solver stopped
    before its tolerance.
    """
    if not isinstance(case, Case):
        raise TypeError(f"run() takes a tribo.Case, got {type(case).__name__}")
    return Results(_tribo.run(case._inner), case)


def examples() -> List[str]:
    """The names of the embedded example cases (``tribo example``)."""
    return list(_tribo.example_names())


# Imported last: tribo.study annotates with Case, defined above.
from . import study  # noqa: E402


def __dir__() -> List[str]:
    # Tab completion and dir() list the API alone; the typing names above are real module
    # attributes so that typing.get_type_hints() resolves the (string) annotations.
    return sorted(__all__)
