"""tribo from Python in five steps: Hertz, grid contact with friction, a case, files, errors.

Run it with `python examples/python/quickstart.py [OUT_DIR]` after `pip install .`; the tests
(tests/python/test_examples.py) run it too. Units: SI (m, Pa, N).
"""

import math
import sys
import tempfile

import numpy as np

import tribo

# 1. The exact Hertz solution: a steel ball (R = 10 mm) on a steel flat, 100 N.
E_star = tribo.composite_modulus(210e9, 0.3, 210e9, 0.3)
h = tribo.hertz(load=100.0, radius=0.01, composite_modulus=E_star)
a = (3 * 100.0 * 0.01 / (4 * E_star)) ** (1 / 3)
print(f"Hertz: a = {h.radius * 1e3:.4f} mm (closed form {a * 1e3:.4f}), "
      f"p0 = {h.max_pressure / 1e9:.4f} GPa")

# 2. The same contact on a 128 x 128 grid from a gap array (shape (ny, nx), m), as one would
#    pass a measured surface: Polonsky & Keer's conjugate gradients, force control.
L, n = 1e-3, 128
x = (np.arange(n) + 0.5) * L / n - L / 2
X, Y = np.meshgrid(x, x)
r = tribo.normal_contact((X**2 + Y**2) / (2 * 0.01), size=(L, L), composite_modulus=E_star,
                         load=100.0)
print(f"grid:  p_max = {r.max_pressure / 1e9:.4f} GPa, area = {r.contact_area * 1e6:.5f} mm^2 "
      f"(Hertz {h.contact_area * 1e6:.5f}), {r.iterations} iterations, residual {r.residual:.1e}")
assert abs(r.max_pressure / h.max_pressure - 1) < 0.01

#    Friction on that pressure: partial slip under Q = 15 N with f = 0.3 (Cattaneo-Mindlin).
t = tribo.tangential_contact(r.pressure, size=(L, L), friction=0.3, tangential_load=15.0,
                             E1=210e9, nu1=0.3, E2=210e9, nu2=0.3)
print(f"grid partial slip: stick radius {math.sqrt(t.stick_area / math.pi) * 1e3:.4f} mm, "
      f"Q = {t.tangential_force[0]:.3f} N, {t.iterations} iterations")

# 3. A case with friction and partial slip (Cattaneo-Mindlin): a dict with a case file's keys.
case = tribo.Case.from_dict({
    "title": "ball on flat, partial slip",
    "body1": {"E": "210 GPa", "nu": 0.3, "radii": ["10 mm", "10 mm"]},
    "body2": {"E": "210 GPa", "nu": 0.3, "radii": ["inf", "inf"]},
    "contact": {"load": 100.0, "friction": 0.3, "tangential_load": 15.0},
    "grid": {"n": 64, "extent": 1.5},
})
res = tribo.run(case)
t = res.summary["tangential"]
c_cm = h.radius * (1 - 15.0 / (0.3 * 100.0)) ** (1 / 3)
print(f"partial slip: stick radius {t['stick_semi_major'] * 1e3:.4f} mm "
      f"(Cattaneo-Mindlin {c_cm * 1e3:.4f} mm)")
fields = res.fields()
print(f"  stick elements: {int(fields['stick'].sum())}, "
      f"max |q| = {np.hypot(fields['traction_x'], fields['traction_y']).max() / 1e6:.1f} MPa")

# 4. An example case of the CLI (the same numbers as `tribo run --json`), and its files.
out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="tribo-")
files = tribo.run(tribo.Case.example("sphere-on-flat")).write(out)
print(f"wrote {len(files)} files into {out}: {', '.join(files[:4])}, ...")

# 5. Errors are Python exceptions naming the field.
try:
    tribo.composite_modulus(210e9, 0.7, 210e9, 0.3)
except tribo.InputError as e:
    print(f"InputError: field {e.field!r}: {e.rule}")
assert math.isfinite(h.approach)
