"""A rough flat on a flat from Python: generate a self-affine surface, check its statistics
against its spectrum, and load it periodically: real contact area against load.

Run it with `python examples/python/rough_contact.py` after `pip install .`; the tests
(tests/python/test_surface.py) run it too. Units: SI (m, Pa). About a second at 128^2.
"""

import math

import numpy as np

import tribo
from tribo import surface

# 1. A Gaussian self-affine surface, periodic over 1 mm: Hurst 0.8, the power law from
#    4 to 32 wavelengths per period (2 pi k / L in rad/m), rms slope 0.1, seed 1.
L, n = 1e-3, 128
spectrum = dict(hurst=0.8, powerlaw_start=2 * math.pi * 4 / L, cutoff=2 * math.pi * 32 / L)
t = surface.self_affine((n, n), size=(L, L), rms_slope=0.1, seed=1, **spectrum)

# 2. Its statistics against the spectrum's: the rms slope is the target on average over
#    seeds (filtered noise), and the PSD's power law gives back the Hurst exponent.
m = surface.moments(t)
fit = surface.psd(t).fit(1.5 * spectrum["powerlaw_start"], 0.9 * spectrum["cutoff"])
print(f"surface: rms height {m['rms_height'] * 1e6:.3f} um, rms slope {m['rms_slope']:.4f} "
      f"(spectral; {m['rms_slope_fd']:.4f} by forward differences), "
      f"Hurst from the PSD {fit.hurst:.3f} (0.8)")

# 3. Periodic contact against a rigid flat (E* = 100 GPa): a load path with warm starts on one
#    operator. At small loads the real contact fraction is proportional to the mean pressure,
#    A / A0 = kappa p / (E* h'_rms), kappa about 2 on well-resolved surfaces (Hyun, Pei,
#    Molinari & Robbins 2004; Persson's theory gives sqrt(8 / pi) = 1.6). This grid has 4
#    points per shortest wavelength: the area counted in elements comes out larger (kappa
#    near 2.8 here); refine n with the cutoff fixed to see it fall.
E_star = 1e11
solver = tribo.NormalSolver(t.shape, size=t.size, composite_modulus=E_star, periodic=True)
pressures = E_star * m["rms_slope"] * np.array([0.005, 0.01, 0.02, 0.04])
for r in solver.load_path(t.gap(), mean_pressures=pressures):
    kappa = r.contact_fraction * E_star * m["rms_slope"] / r.mean_pressure
    print(f"p = {r.mean_pressure / 1e6:7.2f} MPa: contact fraction {r.contact_fraction:.4f}, "
          f"kappa {kappa:.2f}, {r.iterations} iterations, residual {r.residual:.1e}")
