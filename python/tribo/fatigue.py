"""Fatigue from test data: Woehler curves (the paper's Fig. 3) in pyLife's shapes, and the
limiting-state diagram of mechano-rolling fatigue (Fig. 4).

The same functions as ``tribo fatigue fit`` and ``tribo fatigue diagram`` (the same numbers;
docs/user/fatigue.md). pandas is optional: with it :func:`fit` takes a DataFrame and returns a
Series with pyLife's ``WoehlerCurve`` keys; without it a dict of arrays in and a dict out.
"""

from __future__ import annotations

import json as _json
from collections.abc import Mapping as _Mapping

import numpy as _np

from . import _tribo

# Names for the annotations (strings), bound for real so that typing.get_type_hints()
# resolves them; `__dir__` keeps them out of dir().
from typing import Any, Dict, List, Mapping, Optional, Union

import numpy as np

try:  # pandas is optional
    import pandas as _pd  # type: ignore[import-not-found]
except ImportError:  # pragma: no cover - exercised where pandas is absent
    _pd = None

del annotations  # the __future__ feature's name: not part of the API

__all__ = ["WOEHLER_KEYS", "diagram", "fit", "fit_report"]

#: pyLife's ``WoehlerCurve`` keys, in its order: the slope k_1, the knee ND (cycles), the
#: fatigue limit SD (Pa), the scatters TN (cycles) and TS (load) between 10 % and 90 %.
WOEHLER_KEYS = ("k_1", "ND", "SD", "TN", "TS")

# 2 x the standard normal 90 % quantile: T = 10^(2.5631 s) spans 10 % to 90 % (the
# library's SCATTER_FACTOR, tribo::analysis::woehler::stats).
_SCATTER_FACTOR = 2.5631031310892007


def _column(data: Any, names: tuple) -> Optional[np.ndarray]:
    for n in names:
        try:
            v = data[n]
        except (KeyError, IndexError, TypeError, ValueError):
            continue
        return _np.asarray(getattr(v, "values", v))
    return None


def _tests(data: Any):
    """(load, cycles, runout) of a DataFrame or mapping with pyLife's columns ``load``,
    ``cycles``, ``fracture`` (or ``runout``)."""
    load = _column(data, ("load", "load_Pa", "amplitude"))
    cycles = _column(data, ("cycles", "N"))
    fracture = _column(data, ("fracture",))
    runout = _column(data, ("runout",))
    if load is None or cycles is None:
        raise _input_error("data", "columns load (Pa) and cycles are required")
    if (fracture is None) == (runout is None):
        raise _input_error("data", "exactly one of the columns fracture and runout (bool)")
    flags = ~fracture.astype(bool) if fracture is not None else runout.astype(bool)
    return (_np.asarray(load, dtype=_np.float64).tolist(),
            _np.asarray(cycles, dtype=_np.float64).tolist(),
            [bool(f) for f in flags])


def _input_error(field: str, rule: str, value: Any = "") -> "_tribo.InputError":
    err = _tribo.InputError(f"{field}: {rule}")
    err.field, err.value, err.rule = field, str(value), rule
    return err


def fit_report(
    data: Any,
    *,
    kind: str = "sigma",
    measure: Optional[str] = None,
    confidence: float = 0.95,
) -> Dict[str, Any]:
    """Both Woehler fits of ``tribo fatigue fit`` as its ``woehler.json`` (nested dicts):
    the ASTM E739 regression (``"regression"``) and the maximum likelihood of the full model
    (``"max_likelihood"``: the curve, T_N, T_S, standard errors, the convergence record),
    each None where the data do not allow it (``"notes"`` says why).

    ``data``: a pandas DataFrame or a mapping of arrays with pyLife's columns ``load`` (Pa,
    in the measure), ``cycles``, and ``fracture`` (True: failed) or ``runout`` (True: did
    not fail). ``kind``: ``"sigma"`` (mechanical fatigue), ``"p"`` (rolling), ``"sigma_p"``,
    ``"p_sigma"`` (the paper's Fig. 3); ``measure``: ``"amplitude"``, ``"range"`` or
    ``"contact_pressure"`` (default: amplitude for the sigma kinds, contact pressure for the
    p kinds); ``confidence`` of the E739 bands, in (0, 1). Raises :class:`InputError` for
    bad data (the rule named).
    """
    load, cycles, runout = _tests(data)
    text = _tribo.fatigue_fit(load, cycles, runout, str(kind),
                              None if measure is None else str(measure), float(confidence))
    return _json.loads(text)


def fit(
    data: Any,
    *,
    kind: str = "sigma",
    measure: Optional[str] = None,
    method: str = "max_likelihood",
) -> Any:
    """A Woehler curve fitted to fatigue tests, as pyLife's ``WoehlerCurve`` data: a pandas
    Series (a dict without pandas) with the keys ``k_1`` (slope), ``ND`` (knee, cycles),
    ``SD`` (fatigue limit, Pa, in the data's measure), ``TN`` and ``TS`` (scatter in cycles
    and in load, 10 % to 90 %: T = 10^(2.5631 s) of the log10 standard deviation s).

    ``method``: ``"max_likelihood"`` (pyLife's ``MaxLikeFull``: Basquin with a log-normal
    scatter in N and a log-normal fatigue limit, run-outs censored; needs run-outs) or
    ``"regression"`` (pyLife's ``Elementary``: the E739 regression over the finite zone, SD
    the midpoint between the highest run-out level and the lowest finite level; k_1, ND and
    SD equal pyLife's; TN here is 10^(2.5631 s) of the regression's standard error s in
    log10 N, not pyLife's pearl-chain estimate, and TS = TN^(1/k_1)). ``data``, ``kind``, ``measure`` as in
    :func:`fit_report`; the numbers are those of ``tribo fatigue fit`` on the same data.
    """
    report = fit_report(data, kind=kind, measure=measure)
    if method == "max_likelihood":
        m = report["max_likelihood"]
        if m is None:
            raise _input_error("method", "the maximum likelihood fit is not possible on these "
                               f"data: {'; '.join(report['notes'])}", method)
        c = m["curve"]
        values = [c["slope"], c["knee_cycles"], c["fatigue_limit"], m["scatter_cycles"],
                  m["scatter_load"]]
    elif method == "regression":
        r = report["regression"]
        if r is None:
            raise _input_error("method", "the regression is not possible on these data: "
                               f"{'; '.join(report['notes'])}", method)
        c = r["curve"]
        if c is None:
            raise _input_error("method", "the regression estimates no fatigue limit without "
                               "run-outs", method)
        # The scatter of the E739 line: T_N = 10^(2.5631 s) of its standard error s in log10 N.
        tn = 10.0 ** (_SCATTER_FACTOR * r["regression"]["std_error"])
        values = [c["slope"], c["knee_cycles"], c["fatigue_limit"], tn,
                  tn ** (1.0 / c["slope"])]
    else:
        raise _input_error("method", 'one of "max_likelihood", "regression"', method)
    if _pd is not None:
        return _pd.Series(values, index=list(WOEHLER_KEYS), dtype=float)
    return dict(zip(WOEHLER_KEYS, values))


def diagram(limits: Union[Mapping[str, Any], str]) -> Dict[str, Any]:
    """The limiting-state diagram ABCD of mechano-rolling fatigue (the paper's Fig. 4) as
    ``tribo fatigue diagram`` writes it (``limit_diagram.json``, nested dicts): the points
    A, B, C, D in x = p0 / p_f, y = sigma_a / sigma_-1, the direct and back effects, and the
    check of a load state (load factor to the boundary along the ray from the origin,
    margin = factor - 1, inside or not).

    ``limits``: a dict with the keys of the diagram's input file (``{"limits": {"sigma_1":
    260e6, "p_f": 1.3e9, "sigma_1p": 403e6, "p_f_sigma": 1.586e9, "sigma_p_contact_pressure":
    800e6, "p_sigma_stress_amplitude": 80e6}, "state": {"stress_amplitude": 150e6,
    "contact_pressure": 1e9}}``; Pa, or strings with units), or that file's TOML text
    (``tribo example fatigue-diagram``). A fitted limit (the Series of :func:`fit`) may be
    given by its ``SD``. Raises :class:`InputError` naming the key.
    """
    if isinstance(limits, _Mapping):
        limits = _plain(limits)
    return _json.loads(_tribo.fatigue_diagram(limits))


def _plain(obj: Any) -> Any:
    if _pd is not None and isinstance(obj, _pd.Series) and "SD" in obj.index:
        return float(obj["SD"])
    if isinstance(obj, _Mapping):
        if set(WOEHLER_KEYS) <= set(obj.keys()):
            return float(obj["SD"])
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (_np.ndarray, _np.generic)):
        return obj.tolist()
    return obj


def __dir__() -> List[str]:
    # Tab completion and dir() list the API alone; the typing names above are real module
    # attributes so that typing.get_type_hints() resolves the (string) annotations.
    return sorted(__all__)
