"""The full stress tensor under a circular Hertz pressure with tamaas's volume operators.

usage: tamaas_stress.py --n N [--layers L] [--padding P]

The peer side of bench/stress_field.sh (tribo: src/bin/tribo-bench-stress.rs). tamaas 2.9.0
computes subsurface fields with its volume operators on a periodic surface grid
(`model_type.volume_2d`, `ModelFactory.registerVolumeOperators`, then the operators
"boussinesq_gradient" and "hooke", as in tamaas's own `python -m tamaas volume` command). The
surface is the window [0, L)^2 with L = 3a * P (P = padding, default 1: the same window as
tribo, |x|, |y| <= 1.5a), N*P points per side, the Hertz pressure p0 sqrt(1 - r^2/a^2) sampled
at the grid points and centred at L/2 (a grid point, so the axis is a column of the grid);
depths z_k = 1.5a k/(L-1) (tamaas spaces the layers over [0, Lz] end points included). The
von Mises error on the axis is measured against Huber's closed form (1904; Johnson 1985
eq. (3.45)), in units of p0. Prints one line of JSON.

Lengths are in units of a, stresses in units of p0 (the field is linear and scale-free).
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import time

import numpy as np
import tamaas as tm

NU = 0.3


def huber_von_mises(zeta: float) -> float:
    """Von Mises stress on the axis under Hertz pressure (units of p0), zeta = z / a."""
    s_z = -1.0 / (1.0 + zeta * zeta)
    if zeta > 0.0:
        s_r = -((1.0 + NU) * (1.0 - zeta * math.atan(1.0 / zeta)) - 0.5 / (1.0 + zeta * zeta))
    else:
        s_r = -(1.0 + 2.0 * NU) / 2.0
    return abs(s_r - s_z)


def von_mises(s: np.ndarray) -> np.ndarray:
    """Voigt order (11, 22, 33, 23, 13, 12)."""
    xx, yy, zz, yz, xz, xy = (s[..., i] for i in range(6))
    return np.sqrt(
        0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (xy**2 + yz**2 + xz**2)
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, required=True)
    parser.add_argument("--layers", type=int, default=20)
    parser.add_argument("--padding", type=int, default=1)
    args = parser.parse_args()
    n_side = args.n * args.padding
    size = 3.0 * args.padding
    depth = 1.5
    model = tm.Model(tm.model_type.volume_2d, [depth, size, size], [args.layers, n_side, n_side])
    model.E = 1.0
    model.nu = NU
    tm.ModelFactory.registerVolumeOperators(model)
    x = np.arange(n_side) * size / n_side
    xx, yy = np.meshgrid(x, x, indexing="ij")
    r2 = (xx - size / 2) ** 2 + (yy - size / 2) ** 2
    model.traction[..., 2] = np.sqrt(np.maximum(0.0, 1.0 - r2))

    start = time.perf_counter()
    model.operators["boussinesq_gradient"](model.traction, model["strain"])
    model.operators["hooke"](model["strain"], model["stress"])
    seconds = time.perf_counter() - start

    stress = model["stress"]
    centre = n_side // 2
    axis = von_mises(stress[:, centre, centre, :])
    errors = [
        abs(axis[k] - huber_von_mises(depth * k / (args.layers - 1)))
        for k in range(args.layers)
    ]
    print(
        json.dumps(
            {
                "code": "tamaas",
                "version": tm.__version__,
                "n": args.n,
                "layers": args.layers,
                "padding": args.padding,
                "points": args.n * args.n * args.layers,
                "seconds": seconds,
                "von_mises_error_axis": max(errors),
                "von_mises_error_axis_below_surface": max(errors[1:]),
                "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
            }
        )
    )


if __name__ == "__main__":
    main()
