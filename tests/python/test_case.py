"""tribo.Case / tribo.run: parity with `tribo run --json`, case construction, errors, files."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tribo

# The TOML reader of the standard library (Python >= 3.11) turns example files into dicts for
# the from_dict tests; the package itself needs Python 3.9 and no TOML reader.
tomllib = pytest.importorskip("tomllib") if sys.version_info >= (3, 11) else None
needs_tomllib = pytest.mark.skipif(tomllib is None, reason="tomllib needs Python >= 3.11")

# Keys of wall times (they differ from run to run; bench/compare_outputs.sh drops the same, and
# the dynamic cases' dynamics.convolution_s).
TIMING_KEYS = {"time_s", "timings", "solve_s", "setup_s", "steps_s", "fields_s", "damage_s",
               "comparison_s", "total_s", "seconds", "convolution_s", "march_s", "recovery_s"}

ROOT = Path(__file__).resolve().parents[2]
GMSH_CASE = ROOT / "crates" / "tribo-cli" / "examples" / "gmsh" / "hertz-cylinder.toml"

# The embedded examples by cost (measured with the CLI on a shared 2-core machine): the cheap
# ones (under ~3 s each) always; the slow ones (the Sec. 6 damage study 200 s, the Sec. 7
# clamp 28 s, the dynamic cavity and column minutes, the dynamic contact rod impact 8 s and
# clamp-knife-base impact 40 s) with TRIBO_PY_SLOW=1.
CHEAP = ["roller-shaft", "roller-shaft-normal", "roller-shaft-approach", "roller-shaft-bending",
         "sphere-on-flat", "steel-on-cast-iron", "crowned-roller", "height-map",
         "roller-shaft-probabilistic", "rough-flat", "rough-ball", "rough-roller"]
SLOW = ["roller-shaft-sec6", "clamp-knife-base", "cavity", "column", "rod-impact",
        "clamp-knife-base-impact"]
NOT_RUN = ["fatigue-diagram"]  # the input of `tribo fatigue diagram`, not of `tribo run`
# Examples that read a data file beside the case (`tribo example NAME -o DIR` writes both):
# run by crates/tribo-cli/tests/cli.rs (`examples_with_data_files_run`), not from their text.
WITH_DATA = ["measured-x3p"]
RUN_EXAMPLES = CHEAP + (SLOW if os.environ.get("TRIBO_PY_SLOW") == "1" else [])


def test_every_example_is_classified():
    # A new example must be put in CHEAP or SLOW (or NOT_RUN) by whoever adds it.
    assert sorted(CHEAP + SLOW + NOT_RUN + WITH_DATA) == sorted(tribo.examples())


def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items()
                if not (k in TIMING_KEYS or k.endswith("time_s") or "timing" in k)}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o


@pytest.mark.parametrize("name", RUN_EXAMPLES + ["gmsh:hertz-cylinder"])
def test_parity_with_the_cli(name, tribo_bin, tmp_path):
    # The same pipeline: every number of the summary is the same bit for bit (the JSON text
    # of both is parsed by Python's json, so equal floats compare equal). The gmsh case is a
    # 2D case with a mesh file beside it (relative paths resolve against the case's folder).
    if name.startswith("gmsh:"):
        case_file = GMSH_CASE
    else:
        case_file = tmp_path / f"{name}.toml"
        case_file.write_text(
            subprocess.run([tribo_bin, "example", name], check=True, capture_output=True,
                           text=True).stdout)
    cli = subprocess.run([tribo_bin, "run", str(case_file), "--json", "-q", "-o",
                          str(tmp_path / "cli")], check=True, capture_output=True, text=True)
    expected = strip(json.loads(cli.stdout))
    res = tribo.run(tribo.Case.from_toml(case_file))
    assert strip(res.summary) == expected
    # And the files: the same names as the CLI's.
    written = res.write(tmp_path / "py")
    assert written == json.loads(cli.stdout)["outputs"]
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == sorted(
        p.name for p in (tmp_path / "cli").iterdir())


SPHERE = """
title = "sphere on flat"
[body1]
E = "210 GPa"
nu = 0.3
radii = [0.01, 0.01]
[body2]
E = 210e9
nu = 0.3
radii = ["inf", "inf"]
[load]
normal_force = 100.0
[grid]
n = 32
"""


@needs_tomllib
def test_from_toml_text_path_and_dict_are_the_same_case(tmp_path):
    ex = tribo.Case.example("sphere-on-flat")
    p = tmp_path / "s.toml"
    p.write_text(ex.toml)
    by_path = tribo.Case.from_toml(p)
    by_str_path = tribo.Case.from_toml(str(p))
    by_text = tribo.Case.from_toml(ex.toml)
    by_dict = tribo.Case.from_dict(tomllib.loads(ex.toml))
    sums = [strip(tribo.run(c).summary) for c in (by_path, by_str_path, by_text, by_dict)]
    for s in sums[1:]:
        s["case_source"] = sums[0]["case_source"]
        assert s == sums[0]
    assert by_path.kind == "halfspace" and by_path.title == ex.title


def test_bem_case_kind():
    c = tribo.Case.example("clamp-knife-base")
    assert c.kind == "bem2d"
    assert "Case(kind='bem2d'" in repr(c)


@needs_tomllib
def test_field_errors_name_the_field():
    ex = tribo.Case.example("sphere-on-flat")
    d = tomllib.loads(ex.toml)
    d["body1"]["nu"] = 0.7
    with pytest.raises(tribo.InputError) as err:
        tribo.Case.from_dict(d)
    assert err.value.field == "body1.nu"
    assert "0.7" in err.value.value
    assert isinstance(err.value, ValueError)
    with pytest.raises(tribo.InputError, match="line"):
        tribo.Case.from_toml("title = \n[oops")
    with pytest.raises(tribo.InputError):
        tribo.Case.from_dict({"title": "x", "body1": {"E": object()}})
    with pytest.raises(tribo.InputError):
        tribo.Case.example("no-such-example")
    with pytest.raises(FileNotFoundError):
        tribo.Case.from_toml("missing.toml")


@needs_tomllib
def test_non_convergence_is_a_convergence_error():
    d = tomllib.loads(tribo.Case.example("sphere-on-flat").toml)
    d.setdefault("solver", {})["max_iterations"] = 2
    with pytest.raises(tribo.ConvergenceError) as err:
        tribo.run(tribo.Case.from_dict(d))
    assert err.value.residual > err.value.tolerance


def test_fields_of_a_half_space_run():
    res = tribo.run(tribo.Case.example("sphere-on-flat"))
    f = res.fields()
    s = res.summary["contact"]
    assert f["pressure"].shape == (len(f["y"]), len(f["x"]))
    assert f["pressure"].max() == s["max_pressure"]
    assert f["normal_load"] == s["normal_load"]
    assert tribo.run(tribo.Case.from_toml(GMSH_CASE)).fields() is None


@needs_tomllib
def test_from_dict_takes_numpy_arrays(tribo_bin, tmp_path):
    # The height-map example with its heights as a numpy array (and a numpy scalar): the
    # same case, so the same summary as the TOML text.
    ex = tribo.Case.example("height-map")
    d = tomllib.loads(ex.toml)
    d["body1"]["surface"]["heights"] = np.array(d["body1"]["surface"]["heights"])
    d["body1"]["nu"] = np.float64(d["body1"]["nu"])
    a = strip(tribo.run(tribo.Case.from_dict(d)).summary)
    b = strip(tribo.run(ex).summary)
    a.pop("case_source")
    b.pop("case_source")
    assert a == b
