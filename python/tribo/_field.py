"""The stress field under a contact as an ``xarray.Dataset`` (or a dict of numpy arrays without
xarray), and the damage measures on it: psi_q, V_q, Psi_q of the paper's (21)-(24) and the
energy criterion (34)-(35). Re-exported by the package ``tribo``."""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _tribo

#: Units of the named point arrays (those of the CLI's ``stress.vti``).
FIELD_UNITS: Dict[str, str] = {
    **{n: "Pa" for n in ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_yz", "sigma_xz",
                         "von_mises", "max_shear", "principal_1", "principal_2", "principal_3",
                         "hydrostatic", "octahedral_shear")},
    **{n: "J/m^3" for n in ("energy_density", "energy_volumetric", "energy_distortional")},
    **{n: "1" for n in ("strain_xx", "strain_yy", "strain_zz", "strain_xy", "strain_yz",
                        "strain_xz")},
}

_DESCRIPTIONS: Dict[str, str] = {
    "von_mises": "von Mises equivalent stress sigma_int",
    "max_shear": "largest shear stress (s1 - s3) / 2",
    "principal_1": "largest principal stress s1",
    "principal_2": "middle principal stress s2",
    "principal_3": "smallest principal stress s3",
    "hydrostatic": "hydrostatic stress tr(sigma) / 3",
    "octahedral_shear": "octahedral shear stress",
    "energy_density": "strain energy density u = sigma : eps / 2",
    "energy_volumetric": "volumetric part of u",
    "energy_distortional": "distortional part of u",
}

_COMPONENTS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_yz", "sigma_xz")

try:  # xarray is optional
    import xarray as _xr  # type: ignore[import-not-found]
except ImportError:  # pragma: no cover - exercised where xarray is absent
    _xr = None

#: A stress field: an ``xarray.Dataset`` with xarray, else a dict of numpy arrays.
Field = Any


def _to_field(d: Dict[str, Any], as_xarray: Optional[bool]) -> Field:
    """The field dict of the compiled core as a Dataset (xarray present and ``as_xarray`` not
    False) or a plain dict (arrays of shape (nz, ny, nx), coordinates ``x``, ``y``, ``z``,
    the descriptions under ``attrs``)."""
    coords = {k: d[k] for k in ("x", "y", "z")}
    arrays = {k: v for k, v in d.items() if k in FIELD_UNITS}
    psi = d.get("psi") or {}
    attrs = {
        "method": d["method"],
        "edge_refinement": d["edge_refinement"],
        "youngs_modulus": d["youngs_modulus"],
        "youngs_modulus_units": "Pa",
        "poisson_ratio": d["poisson_ratio"],
        "layout": "arrays of shape (nz, ny, nx): x fastest, z the depth into the body (m)",
    }
    if "body" in d:
        attrs["body"] = d["body"]
    if d.get("bulk") is not None:
        attrs["bulk_kind"], attrs["bulk_stress"] = d["bulk"][0], d["bulk"][1]
    use_xr = _xr is not None if as_xarray is None else as_xarray
    if use_xr and _xr is None:
        raise ImportError("as_xarray=True needs xarray (pip install xarray)")
    if not use_xr:
        out: Dict[str, Any] = dict(coords)
        out.update(arrays)
        for name, v in psi.items():
            out[f"psi_{name}"] = v
        out["attrs"] = attrs
        return out
    data_vars = {}
    for name, v in arrays.items():
        a = {"units": FIELD_UNITS[name]}
        if name in _DESCRIPTIONS:
            a["long_name"] = _DESCRIPTIONS[name]
        data_vars[name] = (("z", "y", "x"), v, a)
    for name, v in psi.items():
        data_vars[f"psi_{name}"] = (("z", "y", "x"), v,
                                    {"units": "1", "long_name": f"relative damage psi of {name} (21)"})
    ds = _xr.Dataset(
        data_vars,
        coords={
            "x": ("x", coords["x"], {"units": "m"}),
            "y": ("y", coords["y"], {"units": "m"}),
            "z": ("z", coords["z"], {"units": "m", "long_name": "depth into the body"}),
        },
        attrs=attrs,
    )
    return ds


def _edge_code(edge_refinement: Union[str, int]) -> int:
    """The core's code of ``edge_refinement``: 0 the band, else the factor."""
    if isinstance(edge_refinement, str):
        if edge_refinement == "band":
            return 0
        if edge_refinement == "none":
            return 1
        raise _input_error("edge_refinement", 'one of "band", "none" or an integer in [1, 16]',
                           edge_refinement)
    n = int(edge_refinement)
    if not 1 <= n <= 16:
        raise _input_error("edge_refinement", 'one of "band", "none" or an integer in [1, 16]', n)
    return n


def _input_error(field: str, rule: str, value: Any = "") -> "_tribo.InputError":
    err = _tribo.InputError(f"{field}: {rule}")
    err.field, err.value, err.rule = field, str(value), rule
    return err


def _real_1d(name: str, v: Any) -> Optional[list]:
    if v is None:
        return None
    a = np.asarray(v, dtype=np.float64).ravel()
    return a.tolist()


def stress_field(
    contact: Any,
    *,
    E: float,
    nu: float,
    z: Sequence[float],
    x: Optional[Sequence[float]] = None,
    y: Optional[Sequence[float]] = None,
    tangential: Any = None,
    body: str = "body1",
    size: Optional[Tuple[float, float]] = None,
    method: str = "direct",
    edge_refinement: Union[str, int] = "band",
    as_xarray: Optional[bool] = None,
) -> Field:
    """The subsurface stress field under a half-space contact, the paper's (11).

    ``contact``: a :class:`NormalContact` or the dict of :meth:`Results.fields` (its
    pressure and window), or a pressure array (Pa, shape (ny, nx); then give
    ``size = (Lx, Ly)``, m). ``tangential``: a :class:`TangentialContact` or a dict with
    ``traction_x``, ``traction_y`` (the tractions q on body 1, Pa), or None (frictionless). ``body``:
    ``"body1"`` (the tractions as given) or ``"body2"`` (the shear reversed: body 2 carries
    -q; z into body 2). ``E`` (Pa) and ``nu``: the elastic constants of that body (the
    strains and energies use both; the stresses only ``nu``).

    Points: ``x`` (nx,), ``y`` (ny,), ``z`` (nz,) in m, z >= 0 the depth (a tensor-product
    grid; any spacing); with ``x`` and ``y`` None the contact grid's element centres at the
    depths ``z``. ``method``: ``"direct"`` (the direct sum over the loaded elements, exact at
    any point) or ``"fft"`` (FFT on the extended grid + cubic interpolation; the depths are
    exact). ``edge_refinement``: ``"band"`` (the default: the element tractions with the
    edge band, surface stresses within 0.02 p0 of Hamilton's), ``"none"`` (the bilinear
    element tractions) or N in [2, 16] (edge-aware tractions N times finer);
    docs/theory/HALFSPACE.md 2.5. The choices and the numbers are those of a case's
    ``[field]``.

    Returns an ``xarray.Dataset`` (when xarray is installed, unless ``as_xarray=False``)
    with coordinates ``x``, ``y``, ``z`` (m) and the data variables of the CLI's
    ``stress.vti`` on dims (z, y, x): ``sigma_xx`` ... ``sigma_xz``, ``von_mises``,
    ``max_shear``, ``principal_1`` >= ``principal_2`` >= ``principal_3``, ``hydrostatic``,
    ``octahedral_shear`` (Pa), ``energy_density``, ``energy_volumetric``,
    ``energy_distortional`` (J/m^3), ``strain_xx`` ... (1); units in each variable's
    ``attrs["units"]``, the evaluation method, edge treatment, E and nu in the Dataset's
    ``attrs``. Without xarray a dict of the same arrays (shape (nz, ny, nx)), the
    coordinates, and ``"attrs"``. The GIL is released during the computation.
    """
    pressure = _get(contact, "pressure", contact)
    if size is None:
        size = _get(contact, "size", None)
    if size is None:
        raise _input_error("size", "give size = (Lx, Ly) (m) with a pressure array")
    p = _grid("pressure", pressure)
    qx = qy = None
    if tangential is not None:
        sign = {"body1": 1.0, "body2": -1.0}.get(body)
        if sign is None:
            raise _input_error("body", 'one of "body1", "body2"', body)
        qx = _grid("traction_x", sign * np.asarray(_get(tangential, "traction_x", None)))
        qy = _grid("traction_y", sign * np.asarray(_get(tangential, "traction_y", None)))
        # A shear component zero everywhere is left out (the case's field does the same).
        qx = qx if np.any(qx != 0.0) else None
        qy = qy if np.any(qy != 0.0) else None
    elif body not in ("body1", "body2"):
        raise _input_error("body", 'one of "body1", "body2"', body)
    d = _tribo.stress_field(
        p,
        (float(size[0]), float(size[1])),
        (float(E), float(nu)),
        _real_1d("z", z),
        _real_1d("x", x),
        _real_1d("y", y),
        qx,
        qy,
        str(method),
        _edge_code(edge_refinement),
    )
    d["body"] = body
    return _to_field(d, as_xarray)


def _get(obj: Any, key: str, default: Any) -> Any:
    """``obj.key`` or ``obj[key]`` (a result object or a dict such as
    :meth:`Results.fields`'s), else ``default``."""
    if isinstance(obj, Mapping):
        return obj.get(key, default)
    if isinstance(obj, np.ndarray):
        return default
    return getattr(obj, key, default)


def _grid(name: str, a: Any) -> np.ndarray:
    arr = np.asarray(a)
    if arr.dtype.kind not in "fiu":
        raise TypeError(f"{name}: an array of real numbers is needed, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise _input_error(name, f"an array of shape (ny, nx) is needed, got shape {arr.shape}")
    return np.ascontiguousarray(arr, dtype=np.float64)


def _field_parts(field: Field, E: Optional[float], nu: Optional[float]):
    """The six components, the coordinates and (E, nu) of a field (Dataset or dict)."""
    attrs = field.attrs if hasattr(field, "attrs") and not isinstance(field, dict) else field.get("attrs", {})
    E = attrs.get("youngs_modulus") if E is None else E
    nu = attrs.get("poisson_ratio") if nu is None else nu
    if E is None or nu is None:
        raise _input_error("E", "give E (Pa) and nu: the field does not carry them")
    comps = []
    for name in _COMPONENTS:
        try:
            v = field[name]
        except KeyError:
            raise _input_error(name, "the field needs the six stress components (Pa)") from None
        comps.append(np.asarray(getattr(v, "values", v), dtype=np.float64))
    coords = [np.asarray(getattr(field[c], "values", field[c]), dtype=np.float64).ravel().tolist()
              for c in ("x", "y", "z")]
    return comps, coords, (float(E), float(nu))


@dataclass(frozen=True)
class Damage:
    """The damage of one criterion on a stress field: the paper's (21)-(24) (or (34)-(35) for
    the energy criterion)."""

    name: str
    """The criterion (``damage.criteria`` of a case, ``"u_eff"`` for the energy criterion)."""
    unit: str
    """The unit of the quantity and its limit ("Pa", "1" or "J/m^3")."""
    limit: float
    """The limiting value phi_q^lim (u0 for the energy criterion), in ``unit``."""
    psi: Any
    """psi_q = phi_q / phi_q^lim at every point (21), dimensionless, dims (z, y, x) (a
    DataArray for a Dataset field, else a numpy array of shape (nz, ny, nx))."""
    psi_max: float
    """The largest psi_q."""
    psi_max_at: Tuple[float, float, float]
    """Where (x, y, z), m."""
    volume: float
    """The dangerous volume V_q = integral over {psi_q >= 1} of dV (22), m^3."""
    damageability: float
    """Psi_q = integral over {psi_q >= 1} of psi_q dV (24), m^3."""
    average: Optional[float]
    """Psi_q / V_q (24), dimensionless; None without a dangerous volume."""


def _wrap_psi(field: Field, psi: np.ndarray, name: str) -> Any:
    if _xr is not None and isinstance(field, _xr.Dataset):
        return _xr.DataArray(psi, coords={c: field[c] for c in ("x", "y", "z")},
                             dims=("z", "y", "x"), name=f"psi_{name}", attrs={"units": "1"})
    return psi


def damage(
    field: Field,
    limits: Mapping[str, float],
    *,
    E: Optional[float] = None,
    nu: Optional[float] = None,
) -> Dict[str, Damage]:
    """Volume damageability of a stress field: for each criterion of ``limits`` (name ->
    limiting value phi_q^lim in the quantity's unit: Pa for stresses, 1 for strains, J/m^3
    for ``"u"``) the relative damage psi_q = phi_q / phi_q^lim at every point (21), the
    dangerous volume V_q (22), the damageability Psi_q and Psi_q / V_q (24), with the cut
    cells counted by their fraction (exact for psi linear on the simplices of the grid's
    cells) -- the numbers of a case's ``[damage]`` on the same field.

    ``field``: a Dataset or dict from :func:`stress_field` or :meth:`Results.field` (any
    tensor-product grid with the six stress components, Pa). Names: ``"sigma_int"``
    (von Mises), ``"sigma_xx+"`` (tension), ``"sigma_zz-"`` (compression; limit < 0),
    ``"sigma_1+"``, ``"sigma_n"``, ``"sigma_tau"``, ``"eps_int"``, ``"u"``, ... (the
    vocabulary of ``damage.criteria``, docs/user/case-halfspace.md). ``E`` (Pa), ``nu``
    default to the field's. Raises :class:`InputError` for an unknown name or a limit of the
    wrong sign.
    """
    comps, (x, y, z), material = _field_parts(field, E, nu)
    out = {}
    for name, limit in limits.items():
        psi, region, unit = _tribo.damage(comps, x, y, z, material, str(name), float(limit))
        r = json.loads(region)
        out[name] = Damage(name=name, unit=unit, limit=float(limit),
                           psi=_wrap_psi(field, psi, name), psi_max=r["psi_max"],
                           psi_max_at=tuple(r["psi_max_at"]), volume=r["volume"],
                           damageability=r["damageability"], average=r["average"])
    return out


def energy_criterion(
    field: Field,
    *,
    u0: float,
    a_n: float = 1.0,
    a_tau: float = 1.0,
    a_t: float = 0.0,
    a_tau_n: float = 1.0,
    a_m_t: float = 1.0,
    temperature: Union[float, Any] = 293.15,
    E: Optional[float] = None,
    nu: Optional[float] = None,
) -> Damage:
    """The generalized energy criterion, the paper's (25), (33)-(35): the effective energy
    u_eff = A_M\\T [A_tau\\n (A_n u_n + A_tau u_tau) + A_T k T] (32) against the activation
    energy ``u0`` (J/m^3): psi_u = u_eff / u0 (34) at every point, V_u, Psi_u and Psi_u / V_u
    (35). Coefficients dimensionless except ``a_t`` (1/m^3); the defaults are the purely
    mechanical case (u_eff = u). ``temperature``: K, one value or an array of the field's
    shape. ``field``, ``E``, ``nu`` as in :func:`damage`. The numbers of a case's
    ``[damage.energy]`` on the same field.
    """
    comps, (x, y, z), material = _field_parts(field, E, nu)
    t = np.asarray(getattr(temperature, "values", temperature), dtype=np.float64).ravel().tolist()
    psi, text = _tribo.energy_damage(comps, x, y, z, material, float(u0),
                                     (float(a_n), float(a_tau), float(a_t), float(a_tau_n),
                                      float(a_m_t)), t)
    r = json.loads(text)["region"]
    return Damage(name="u_eff", unit="J/m^3", limit=float(u0), psi=_wrap_psi(field, psi, "u_eff"),
                  psi_max=r["psi_max"], psi_max_at=tuple(r["psi_max_at"]), volume=r["volume"],
                  damageability=r["damageability"], average=r["average"])
