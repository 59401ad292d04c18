#!/usr/bin/env python3
"""Periodic normal contact of a self-affine rough surface solved with tamaas (issue 16's benchmark).

Usage: tamaas_periodic.py --n N [--tolerance T] [--seed S] [--surface-out STEM] [--pressure-out FILE]
       tamaas_periodic.py --n N --surface-only --surface-out STEM [--seed S]   (no solve)

Prints one JSON line: n, seconds (solve only), setup_seconds, iterations, tamaas_error,
mean_pressure, contact_fraction, max_pressure, peak_rss_bytes, and the surface's statistics.

The case (issue 16, "Speed and memory"), dimensionless: a square periodic window of side
L = 1, E* = 1 (tamaas: E = 1, nu = 0, so its contact modulus E / (1 - nu^2) is 1); a rigid
self-affine surface, Hurst exponent H = 0.8, rms slope 1; mean pressure 0.1 E*; tamaas's
PolonskyKeerRey on its periodic (default) operator, tolerance 1e-10 (tamaas's own measure,
see bench/README.md).

The surface is made here with numpy, not with tamaas's generator, so that it is written to
disk and tribo solves the same one (`--surface-out STEM`: STEM.npy, [ix, iy], and STEM.bin,
N*N little-endian f64 with x fastest, tribo's layout). Isotropic power spectrum
C(q) ~ q^(-2(1 + H)) for wave numbers 4 <= |k| <= N/4 (|k| in units of 2 pi / L: a roll-off
at 4 wavelengths per window, the short cutoff at 4 elements per wavelength so that the
surface is resolved; no content below 4 wavelengths per window), random phases
from numpy's PCG64 with `--seed`; mean removed; scaled so that the rms slope
sqrt(<|grad h|^2>), computed spectrally, is exactly 1.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import sys
import tempfile
import time

import numpy as np
import tamaas as tm

HURST = 0.8
RMS_SLOPE = 1.0
MEAN_PRESSURE = 0.1  # units of E*
ROLL_OFF = 4  # smallest wave number |k| (wavelengths per window)


def self_affine_surface(n: int, seed: int) -> np.ndarray:
    """The surface h[ix, iy] on an n x n periodic grid of the unit square (module docs)."""
    rng = np.random.Generator(np.random.PCG64(seed))
    k = np.fft.fftfreq(n, d=1.0 / n)  # integer wave numbers
    kx, ky = np.meshgrid(k, k, indexing="ij")
    q = np.hypot(kx, ky)
    band = (q >= ROLL_OFF) & (q <= n / 4)
    amplitude = np.zeros_like(q)
    amplitude[band] = q[band] ** (-(1.0 + HURST))  # sqrt of C(q) ~ q^(-2(1+H))
    phases = np.exp(2j * np.pi * rng.random((n, n)))
    # The real part of the inverse transform of a random-phase spectrum: a real field with
    # the same (isotropic) power spectrum up to a factor.
    h = np.real(np.fft.ifft2(amplitude * phases))
    h -= h.mean()
    return h / rms_slope(h)


def rms_slope(h: np.ndarray) -> float:
    """sqrt(<|grad h|^2>) by spectral differentiation on the unit square."""
    n = h.shape[0]
    k = 2.0 * np.pi * np.fft.fftfreq(n, d=1.0 / n)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    spectrum = np.fft.fft2(h)
    gx = np.real(np.fft.ifft2(1j * kx * spectrum))
    gy = np.real(np.fft.ifft2(1j * ky * spectrum))
    return float(np.sqrt(np.mean(gx**2 + gy**2)))


def write_surface(surface: np.ndarray, stem: str) -> None:
    """STEM.npy ([ix, iy]) and STEM.bin (little-endian f64, x fastest: index iy * n + ix)."""
    np.save(stem + ".npy", surface)
    surface.T.astype("<f8").tofile(stem + ".bin")


def run(n: int, tolerance: float, seed: int, surface_out: str | None, pressure_out: str | None) -> dict:
    surface = self_affine_surface(n, seed)
    if surface_out:
        write_surface(surface, surface_out)

    t0 = time.perf_counter()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E = 1.0
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(
        model, np.ascontiguousarray(surface), tolerance, tm.PolonskyKeerRey.pressure, tm.PolonskyKeerRey.pressure
    )
    solver.max_iter = 100000
    solver.dump_freq = solver.max_iter + 1
    setup = time.perf_counter() - t0

    # tamaas logs "iteration cost error" at level info on the C++ stderr: capture descriptor 2.
    tm.set_log_level(tm.LogLevel.info)
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as log:
        os.dup2(log.fileno(), 2)
        try:
            t0 = time.perf_counter()
            cpu0 = time.process_time()
            error = solver.solve(MEAN_PRESSURE)
            cpu = time.process_time() - cpu0
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
    if pressure_out:
        p.T.astype("<f8").tofile(pressure_out)
    return {
        "code": "tamaas-periodic",
        "version": tm.__version__,
        "n": n,
        "seed": seed,
        "hurst": HURST,
        "rms_slope": rms_slope(surface),
        "rms_height": float(np.std(surface)),
        "wave_numbers": [ROLL_OFF, n // 4],
        "tolerance": tolerance,
        "seconds": seconds,
        "cpu_seconds": cpu,
        "setup_seconds": setup,
        "iterations": iterations,
        "converged": bool(error < tolerance),
        "tamaas_error": error,
        "mean_pressure": float(p.mean()),
        "max_pressure": float(p.max()),
        "contact_fraction": float(np.mean(p > 0.0)),
        "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, required=True, help="elements per side")
    ap.add_argument("--tolerance", type=float, default=1e-10)
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--surface-out", metavar="STEM", help="write the surface to STEM.npy and STEM.bin")
    ap.add_argument("--pressure-out", metavar="FILE", help="write the pressure (f64 LE, x fastest)")
    ap.add_argument(
        "--surface-only", action="store_true", help="write the surface (--surface-out) and exit without solving"
    )
    args = ap.parse_args()
    if args.n < 16 or args.n % 2:
        ap.error("--n must be even and >= 16")
    if args.surface_only:
        if not args.surface_out:
            ap.error("--surface-only needs --surface-out")
        surface = self_affine_surface(args.n, args.seed)
        write_surface(surface, args.surface_out)
        print(json.dumps({"code": "surface", "n": args.n, "seed": args.seed, "rms_slope": rms_slope(surface)}))
        return 0
    tm.set_log_level(tm.LogLevel.error)
    out = run(args.n, args.tolerance, args.seed, args.surface_out, args.pressure_out)
    print(json.dumps(out))
    if abs(out["mean_pressure"] / MEAN_PRESSURE - 1.0) > 1e-6:
        print("tamaas_periodic: the mean pressure is not the prescribed one", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
