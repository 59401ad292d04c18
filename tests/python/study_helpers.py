"""Helpers shared by the study tests (test_study.py, test_sweep.py): a cheap study and the
command line."""

import subprocess

# A cheap study (16 x 16 grids: milliseconds a point): 2 loads x 2 zip values x 2 samples;
# nu = 0.7 makes an invalid case (those points fail alone).
BALLS = """
[study]
name = "balls"
seed = 3
samples = 2
collect = ["contact.max_pressure", "contact.hertz.p0", "contact.iterations"]

[base]
[base.body1]
E = "210 GPa"
nu = 0.3
radii = ["10 mm", "10 mm"]
[base.body2]
E = "210 GPa"
nu = 0.3
radii = ["inf", "inf"]
[base.contact]
load = 100.0
[base.grid]
n = 16

[[grid]]
key = "contact.load"
values = [50.0, 100.0]

[[zip]]
key = "body2.nu"
values = [0.3, 0.7]

[[random]]
key = "body1.radii[0]"
dist = "uniform"
low = 0.008
high = 0.012
"""


def cli(tribo_bin, *args):
    out = subprocess.run([tribo_bin, *args], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    return out.stdout
