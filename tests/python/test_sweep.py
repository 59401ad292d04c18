"""`tribo sweep`'s columnar file loads directly in pandas/xarray users' tools: results.nc read
with scipy.io.netcdf_file and xarray.open_dataset (skipped where they are not installed),
compared with results.csv, column by column."""

import csv
import math

import pytest
from study_helpers import BALLS, cli


@pytest.fixture(scope="module")
def study(tmp_path_factory, tribo_bin):
    root = tmp_path_factory.mktemp("sweep")
    (root / "s.toml").write_text(BALLS)
    for args in (["plan", str(root / "s.toml"), "-o", str(root / "s")],
                 ["run", str(root / "s"), "--jobs", "2", "-q"],
                 ["gather", str(root / "s")]):
        cli(tribo_bin, "sweep", *args)
    with open(root / "s" / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return root / "s", rows


def test_csv_has_every_point_and_the_failures(study):
    _, rows = study
    assert len(rows) == 8
    # nu = 0.7 is refused by the case: those points fail alone, with the reason.
    for r in rows:
        if r["body2.nu"] == "7e-1":
            assert r["status"].startswith("failed: body2.nu = 0.7")
            assert r["contact.max_pressure_Pa"] == ""
        else:
            assert r["status"] == "ok"
            assert 0.008 <= float(r["body1.radii[0]"]) <= 0.012


def _same(a, b):
    return (math.isnan(a) and b == "") or a == float(b)


def test_scipy_reads_results_nc(study):
    netcdf = pytest.importorskip("scipy.io").netcdf_file
    d, rows = study
    with netcdf(str(d / "results.nc"), "r", mmap=False) as f:
        p = f.variables["contact.max_pressure_Pa"]
        assert p.units == b"Pa"
        assert list(f.variables["index"][:]) == list(range(8))
        for i, r in enumerate(rows):
            assert _same(float(p[i]), r["contact.max_pressure_Pa"])
            status = b"".join(f.variables["status"][i]).rstrip(b"\0").decode()
            assert status == r["status"]


def test_xarray_opens_results_nc(study):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("scipy")
    d, rows = study
    ds = xr.open_dataset(d / "results.nc", engine="scipy")
    assert ds.sizes["point"] == 8
    assert ds["contact.hertz.p0_Pa"].attrs["units"] == "Pa"
    df = ds.to_dataframe()
    for i, r in enumerate(rows):
        assert _same(float(df["contact.hertz.p0_Pa"].iloc[i]), r["contact.hertz.p0_Pa"])
        assert str(df["status"].iloc[i]) == r["status"]
