#!/usr/bin/env python3
"""The paper's half-space case (docs/theory/HALFSPACE.md section 4) solved with tamaas, for the benchmark.

Usage: tamaas_case.py --n N [--tolerance T] [--max-iter M]
       tamaas_case.py --n N --evaluate FILE   (check another code's pressure, see below)
       tamaas_case.py --check-operator

Prints one JSON line: n, seconds (solve only), setup_seconds, iterations, tamaas_error (tamaas's
own convergence measure at the last check), residual (the common complementarity measure,
see below), eps_avg (paper's eq. 17), max_pressure, normal_load, approach, contact_elements,
peak_rss_bytes.

Setup (checked against tamaas 2.9.0):
- `ModelFactory.createModel(model_type.basic_2d, [L, L], [N, N])` with L = 3a: the window
  |x|, |y| <= 1.5a with N x N square elements; array index [i, j] is element (x_i, y_j) with
  centres x_i = -1.5a + (i + 1/2) L/N. The non-periodic operator is translation invariant, so
  only the spacing matters.
- `registerNonPeriodic(model, 'dcfft')` AND `solver.setIntegralOperator('dcfft')`; without the
  second call PolonskyKeerRey silently solves the periodic problem.
- Modulus: tamaas indents an elastic half-space (E, nu) with a rigid surface; its contact
  modulus is E_star = E / (1 - nu^2). We set nu = 0 and E = E* = 1.10440e11 Pa, so
  model.E_star = E* of the two steel bodies (computed, not the rounded 1.10440e11: the window
  is 1.5a, and a depends on E*, so both codes must use the same E* to have the same grid). (In 2.9.0 the dcfft operator applied to a unit
  pressure on one element gives exactly Love's centre value 8 c ln(1 + sqrt 2) / (pi E*) for a
  square of side 2c, and the point-load value far away: checked in `--check-operator`.)
- Gap: tamaas takes the rigid surface's height (apex highest); its gap is u - surface + shift.
  We pass surface = -h with h = 50 x^2 + 60 y^2, i.e. the same initial separation as tribo.
- Force control: `solve(mean_pressure)` with mean pressure F / L^2 (sum p dA = F checked).
- Hertz: exact elliptic-integral solution (AGM), a = 5.29641e-4, b = 4.69031e-4 m,
  p0 = 3.84404e9 Pa, as tribo's `HertzContact`: the same window and p_H in both codes.
- Tolerance: tamaas stops when  sum_i p_i g_i / (sum_i p_i * std(h)) < tol, g the gap shifted
  so that its minimum over the contact set is 0 (read off `computeError()`); the returned
  value is the error at the last check, one update before the final pressure. `residual`
  below recomputes that measure on the final pressure with an exact gap, so that tribo-bench
  can print the same number for tribo. `minmap_residual` is tribo's stopping measure,
  max_i |min(p_i / p_max, g_i / u_max)|, on the same pressure.
- `--evaluate FILE` reads N*N little-endian f64 pressures in tribo's layout (x fastest) and
  prints the same accuracy and residual measures for them, computed with tamaas's operator:
  an independent check of another solver's answer.
- Iterations: tamaas logs "iteration cost error" lines (level info) on the C++ stderr; we
  redirect file descriptor 2 during the solve and parse the last line.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import resource
import sys
import tempfile
import time

import numpy as np
import tamaas as tm

# The paper's case (docs/theory/HALFSPACE.md sections 3.1 and 4).
E_STAR = 1.0 / (2.0 * (1.0 - 0.3**2) / 2.01e11)  # Pa: E = 2.01e11, nu = 0.3 on both bodies (1.10440e11)
A_COEF, B_COEF = 50.0, 60.0  # h = A x^2 + B y^2, 1/m
LOAD = 2000.0  # N
HERTZ_A_REF, HERTZ_B_REF, HERTZ_P0_REF = 5.2964e-4, 4.6903e-4, 3.8440e9  # m, m, Pa (rounded)


def elliptic_ke(m: float) -> tuple[float, float]:
    """Complete elliptic integrals K(m), E(m) of parameter m = e^2, by the AGM."""
    a, b, c = 1.0, math.sqrt(1.0 - m), math.sqrt(m)
    total, power = 0.5 * c * c, 0.5
    for _ in range(40):  # quadratic convergence: ~6 steps to round-off
        if abs(c) <= 1e-16 * a:
            break
        a, b, c = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        power *= 2.0
        total += power * c * c
    k = math.pi / (2.0 * a)
    return k, k * (1.0 - total)


def hertz_exact(coef_a: float, coef_b: float, e_star: float, load: float) -> tuple[float, float, float, float]:
    """Exact elliptical Hertz contact for h = A x^2 + B y^2, A < B (docs/theory/HALFSPACE.md 3.1):
    long semi-axis a (along x), short b, p0, approach."""
    ratio = coef_b / coef_a

    def f(m: float) -> float:
        k, e = elliptic_ke(m)
        return (e / (1.0 - m) - k) / (k - e) - ratio

    lo, hi = 1e-12, 1.0 - 1e-12  # f increases with m
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
    m = 0.5 * (lo + hi)
    k, e = elliptic_ke(m)
    a = (3.0 * load * (k - e) / (2.0 * math.pi * e_star * m * coef_a)) ** (1.0 / 3.0)
    b = a * math.sqrt(1.0 - m)
    return a, b, 3.0 * load / (2.0 * math.pi * a * b), 3.0 * load * k / (2.0 * math.pi * a * e_star)


HERTZ_A, HERTZ_B, HERTZ_P0, HERTZ_APPROACH = hertz_exact(A_COEF, B_COEF, E_STAR, LOAD)
assert abs(HERTZ_A / HERTZ_A_REF - 1) < 1e-4 and abs(HERTZ_B / HERTZ_B_REF - 1) < 1e-4
assert abs(HERTZ_P0 / HERTZ_P0_REF - 1) < 1e-4
HALF_WIDTH = 1.5 * HERTZ_A  # m


def element_centres(n: int) -> np.ndarray:
    dx = 2.0 * HALF_WIDTH / n
    return -HALF_WIDTH + (np.arange(n) + 0.5) * dx


def hertz_pressure(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    r = 1.0 - (x / HERTZ_A) ** 2 - (y / HERTZ_B) ** 2
    return np.where(r > 0.0, HERTZ_P0 * np.sqrt(np.clip(r, 0.0, None)), 0.0)


def make_model(n: int):
    size = 2.0 * HALF_WIDTH
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [size, size], [n, n])
    model.E = E_STAR
    model.nu = 0.0
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    return model


def check_operator(n: int = 16) -> dict:
    """Unit pressure on the centre element: Love's centre value and the far-field point load."""
    model = make_model(n)
    dx = 2.0 * HALF_WIDTH / n
    t = np.zeros((n, n))
    t[n // 2, n // 2] = 1.0
    u = np.zeros((n, n))
    model.operators["dcfft"](t, u)
    love = 8.0 * (dx / 2) * math.log(1.0 + math.sqrt(2.0)) / (math.pi * E_STAR)
    d = (n // 2) * dx
    point = dx * dx / (math.pi * E_STAR * d)
    return {
        "E_star": model.E_star,
        "centre_over_love": u[n // 2, n // 2] / love,
        "far_x_over_point_load": u[0, n // 2] / point,
        "far_y_over_point_load": u[n // 2, 0] / point,
    }


def case_gap(n: int):
    x = element_centres(n)
    xx, yy = np.meshgrid(x, x, indexing="ij")
    return xx, yy, A_COEF * xx**2 + B_COEF * yy**2


def measures(model, p: np.ndarray, h: np.ndarray, xx: np.ndarray, yy: np.ndarray) -> dict:
    """Accuracy and complementarity of a pressure p (Pa, [ix, iy]) on the case."""
    n = p.shape[0]
    dx = 2.0 * HALF_WIDTH / n
    # Exact deformed gap of the pressure with the non-periodic operator.
    u = np.zeros((n, n))
    model.operators["dcfft"](np.ascontiguousarray(p), u)
    contact = p > 0.0
    approach = float(np.mean((u + h)[contact])) if contact.any() else float("nan")
    gap = u + h - approach
    shifted = gap - gap[contact].min() if contact.any() else gap
    p_h = hertz_pressure(xx, yy)
    # tribo's stopping measure: max |min(p / p_max, g / u_max)| (min-map residual).
    minmap = np.abs(np.minimum(p / p.max(), gap / np.abs(u).max())).max()
    return {
        "residual": float(np.sum(p * shifted) / (np.sum(p) * np.std(h))),
        "minmap_residual": float(minmap),
        "eps_avg": float(np.mean(np.abs(p_h - p)) / HERTZ_P0),
        "eps_max": float(np.max(np.abs(p_h - p)) / HERTZ_P0),
        "max_pressure": float(p.max()),
        "min_pressure": float(p.min()),
        "normal_load": float(p.sum() * dx * dx),
        "approach": approach,
        "contact_elements": int(contact.sum()),
        "gap_spread_in_contact": float(np.ptp(gap[contact])) if contact.any() else None,
        "min_gap_outside": float(gap[~contact].min()) if (~contact).any() else None,
    }


def evaluate(n: int, path: str) -> dict:
    raw = np.fromfile(path, dtype="<f8")
    if raw.size != n * n:
        raise SystemExit(f"{path}: {raw.size} values, expected {n * n}")
    p = raw.reshape(n, n).T  # tribo: index iy * n + ix; here [ix, iy]
    xx, yy, h = case_gap(n)
    return {"code": "tamaas-evaluate", "n": n, "file": path, **measures(make_model(n), p, h, xx, yy)}


def run(n: int, tolerance: float, max_iter: int) -> dict:
    xx, yy, h = case_gap(n)
    size = 2.0 * HALF_WIDTH

    t0 = time.perf_counter()
    model = make_model(n)
    solver = tm.PolonskyKeerRey(
        model, np.ascontiguousarray(-h), tolerance, tm.PolonskyKeerRey.pressure, tm.PolonskyKeerRey.pressure
    )
    solver.setIntegralOperator("dcfft")
    solver.max_iter = max_iter
    # Log only the final line (tamaas logs it at convergence whatever the frequency).
    solver.dump_freq = max_iter + 1
    setup = time.perf_counter() - t0

    # tamaas logs "iteration cost error" at level info on the C++ stderr: capture descriptor 2.
    tm.set_log_level(tm.LogLevel.info)
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as log:
        os.dup2(log.fileno(), 2)
        try:
            t0 = time.perf_counter()
            error = solver.solve(LOAD / (size * size))
            seconds = time.perf_counter() - t0
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            tm.set_log_level(tm.LogLevel.error)
        log.seek(0)
        text = log.read().decode(errors="replace")
    lines = [ln for ln in text.splitlines() if re.match(r"^\s*\d+\s+\S+\s+\S+\s*$", ln)]
    iterations = int(lines[-1].split()[0]) if lines else None

    p = np.array(model.traction, dtype=float).reshape(n, n)
    return {
        "code": "tamaas",
        "version": tm.__version__,
        "hertz": {"a": HERTZ_A, "b": HERTZ_B, "p0": HERTZ_P0, "approach": HERTZ_APPROACH},
        "n": n,
        "tolerance": tolerance,
        "seconds": seconds,
        "setup_seconds": setup,
        "iterations": iterations,
        "converged": bool(error < tolerance),
        "tamaas_error": error,
        **measures(model, p, h, xx, yy),  # outside the timing
        "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=None, help="elements per side")
    ap.add_argument("--tolerance", type=float, default=1e-10)
    ap.add_argument("--max-iter", type=int, default=10000)
    ap.add_argument("--evaluate", metavar="FILE", help="measure another code's pressure (f64 LE, x fastest)")
    ap.add_argument("--check-operator", action="store_true", help="check the dcfft operator and exit")
    args = ap.parse_args()
    tm.set_log_level(tm.LogLevel.error)
    if args.check_operator:
        print(json.dumps(check_operator()))
        return 0
    if args.n is None or args.n < 4:
        ap.error("--n N (N >= 4) is required")
    if args.evaluate:
        print(json.dumps(evaluate(args.n, args.evaluate)))
        return 0
    out = run(args.n, args.tolerance, args.max_iter)
    print(json.dumps(out))
    # Sanity: a periodic or wrongly scaled setup is far off Hertz.
    if not (abs(out["max_pressure"] / HERTZ_P0 - 1.0) < 0.05 and abs(out["normal_load"] / LOAD - 1.0) < 1e-6):
        print("tamaas_case: the answer is far from Hertz: setup wrong?", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
