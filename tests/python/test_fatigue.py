"""tribo.fatigue: the Woehler fits with pyLife's keys (parity with `tribo fatigue fit`, the
pyLife fixture, and pyLife itself where it is installed) and the limiting-state diagram."""

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import tribo
from tribo import fatigue

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "crates" / "tribo-cli" / "examples" / "data" / "woehler-steel.csv"
PYLIFE = json.loads((ROOT / "crates" / "tribo-case" / "tests" / "fixtures" /
                     "pylife_woehler.json").read_text())

try:
    import pandas as pd
except ImportError:
    pd = None


def columns():
    """The data set as pyLife's columns: load (Pa), cycles, fracture."""
    rows = [line.split(",") for line in DATA.read_text().splitlines()
            if line and not line.startswith("#")][1:]
    load = np.array([float(r[0]) * 1e6 for r in rows])
    cycles = np.array([float(r[1]) for r in rows])
    fracture = np.array([r[2].strip() == "false" for r in rows])
    return {"load": load, "cycles": cycles, "fracture": fracture}


@pytest.fixture(scope="module")
def cli(tribo_bin, tmp_path_factory):
    out = tmp_path_factory.mktemp("fit")
    return json.loads(subprocess.run([tribo_bin, "fatigue", "fit", str(DATA), "--json", "-o",
                                      str(out)], check=True, capture_output=True,
                                     text=True).stdout)


def test_fit_report_equals_tribo_fatigue_fit(cli):
    report = fatigue.fit_report(columns())
    for key in ("regression", "max_likelihood", "tests", "fractures", "runouts", "mixed_levels",
                "notes", "kind", "measure"):
        assert report[key] == cli[key], key


def test_fit_returns_pylife_keys_with_the_cli_numbers(cli):
    data = pd.DataFrame(columns()) if pd is not None else columns()
    s = fatigue.fit(data)
    m = cli["max_likelihood"]
    expected = [m["curve"]["slope"], m["curve"]["knee_cycles"], m["curve"]["fatigue_limit"],
                m["scatter_cycles"], m["scatter_load"]]
    if pd is not None:
        assert isinstance(s, pd.Series)
        assert list(s.index) == ["k_1", "ND", "SD", "TN", "TS"]
        assert s.tolist() == expected
    else:
        assert list(s.values()) == expected
    # pyLife 2.3.1's MaxLikeFull on the same data (the fixture; tolerances of
    # crates/tribo-case/tests/fatigue.rs: pyLife stops its simplex at xtol = ftol = 1e-4).
    ref = PYLIFE["max_like_full"]
    for key, tol in [("SD", 1e-3), ("k_1", 1e-3), ("ND", 5e-3), ("TN", 1e-3), ("TS", 1e-3)]:
        assert s[key] == pytest.approx(ref[key], rel=tol), key
    # The regression: pyLife's Elementary (SD, k_1, ND to 1e-12: the same least squares).
    r = fatigue.fit(data, method="regression")
    ref = PYLIFE["elementary"]
    for key in ("SD", "k_1", "ND"):
        assert r[key] == pytest.approx(ref[key], rel=1e-12), key
    assert r["TS"] == pytest.approx(r["TN"] ** (1 / r["k_1"]), rel=1e-14)


def test_fit_takes_runout_columns_and_dicts():
    c = columns()
    a = fatigue.fit({"load": c["load"], "cycles": c["cycles"], "runout": ~c["fracture"]})
    b = fatigue.fit(c)
    if pd is None:
        assert a == b
    else:
        assert a.equals(b)


def test_fit_errors_name_the_rule():
    c = columns()
    with pytest.raises(tribo.InputError, match="fracture and runout"):
        fatigue.fit({"load": c["load"], "cycles": c["cycles"]})
    with pytest.raises(tribo.InputError) as err:
        fatigue.fit(c, kind="q")
    assert err.value.field == "kind"
    bad = dict(c)
    bad["load"] = c["load"].copy()
    bad["load"][0] = -1.0
    with pytest.raises(tribo.InputError):
        fatigue.fit(bad)
    with pytest.raises(tribo.InputError) as err:
        fatigue.fit(c, method="bayes")
    assert err.value.field == "method"


@pytest.mark.skipif(pd is None, reason="pyLife needs pandas")
def test_against_pylife_itself_where_installed():
    # Opt-in: runs where pyLife is installed in the test environment (pip install pylife).
    woehler = pytest.importorskip("pylife.materialdata.woehler")
    df = pd.DataFrame(columns())
    df["load"] = df["load"] / 1e6  # pyLife's fit is scaled for loads in MPa
    ml = woehler.MaxLikeFull(df).analyze()  # as bench/pylife_woehler.py calls it
    s = fatigue.fit(pd.DataFrame(columns()))
    assert s["SD"] == pytest.approx(ml["SD"] * 1e6, rel=1e-3)
    for key, tol in [("k_1", 1e-3), ("ND", 5e-3), ("TN", 1e-3), ("TS", 1e-3)]:
        assert s[key] == pytest.approx(ml[key], rel=tol), key


def test_diagram_equals_tribo_fatigue_diagram(tribo_bin, tmp_path):
    text = subprocess.run([tribo_bin, "example", "fatigue-diagram"], check=True,
                          capture_output=True, text=True).stdout
    (tmp_path / "d.toml").write_text(text)
    cli = json.loads(subprocess.run([tribo_bin, "fatigue", "diagram", str(tmp_path / "d.toml"),
                                     "--json", "-o", str(tmp_path / "out")], check=True,
                                    capture_output=True, text=True).stdout)
    from_text = fatigue.diagram(text)
    assert from_text["diagram"] == cli["diagram"] and from_text["state"] == cli["state"]
    as_dict = fatigue.diagram({
        "limits": {"sigma_1": "260 MPa", "p_f": 1.3e9, "sigma_1p": 403e6, "p_f_sigma": 1.586e9,
                   "sigma_p_contact_pressure": 800e6, "p_sigma_stress_amplitude": 80e6},
        "state": {"stress_amplitude": 150e6, "contact_pressure": 1e9},
    })
    assert as_dict["diagram"] == cli["diagram"] and as_dict["state"] == cli["state"]
    # A fitted curve stands for its fatigue limit SD.
    curve = fatigue.fit(columns())
    d = fatigue.diagram({"limits": {"sigma_1": curve, "p_f": 1.3e9, "sigma_1p": 403e6,
                                    "p_f_sigma": 1.586e9, "sigma_p_contact_pressure": 800e6,
                                    "p_sigma_stress_amplitude": 80e6}})
    assert d["sources"][0]["value"] == curve["SD"]
    with pytest.raises(tribo.InputError) as err:
        fatigue.diagram({"limits": {"sigma_1": 260e6}})
    assert "limits." in err.value.field
