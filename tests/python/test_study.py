"""tribo.study: the engine of `tribo sweep` from Python. The same tables as the command line
(bytes of results.csv and results.nc, and the DataFrame's numbers), the same plan, resuming,
per-point failures, errors naming the item, progress and stopping, the SLURM scripts, and the
package's namespace (dir(tribo) shows the API only)."""

import json
import math
import os
import pickle
import shutil
import sys
import subprocess
import threading
import time
import types
from pathlib import Path

import numpy as np
import pytest

import tribo
import tribo.study
from study_helpers import BALLS, cli


@pytest.fixture(scope="module")
def fig2a(tmp_path_factory, tribo_bin):
    # The paper's Fig. 2a study (9 points of the roller/shaft case) through `tribo sweep` and
    # through tribo.study, both with 2 jobs.
    root = tmp_path_factory.mktemp("fig2a")
    (root / "fig2a.toml").write_text(cli(tribo_bin, "sweep", "example", "fig2a"))
    cli(tribo_bin, "sweep", "plan", str(root / "fig2a.toml"), "-o", str(root / "cli"))
    cli(tribo_bin, "sweep", "run", str(root / "cli"), "--jobs", "2", "-q")
    cli(tribo_bin, "sweep", "gather", str(root / "cli"))
    s = tribo.study.load(root / "fig2a.toml")
    report = s.run(root / "py", jobs=2)
    table = s.gather()
    return root, s, report, table


def test_fig2a_tables_are_the_clis_bit_for_bit(fig2a):
    root, s, report, _ = fig2a
    assert report.done == 9 and not report.failed and report.skipped == 0
    for name in ("points.csv", "results.csv", "results.nc"):
        assert (root / "py" / name).read_bytes() == (root / "cli" / name).read_bytes(), name
    # Each point's summary too, but for the wall times.
    for i in range(9):
        a = json.loads((root / "py" / "points" / f"{i:06}" / "summary.json").read_text())
        b = json.loads((root / "cli" / "points" / f"{i:06}" / "summary.json").read_text())
        assert untimed(a) == untimed(b), i


def untimed(o):
    """A summary without its wall times (`time_s`, `timings`; their units stay)."""
    if isinstance(o, dict):
        return {k: untimed(v) for k, v in o.items() if k not in ("time_s", "timings")}
    return o


def test_fig2a_dataframe_holds_the_csv_numbers(fig2a):
    pd = pytest.importorskip("pandas")
    root, s, _, table = fig2a
    # The CSV holds each double's shortest round-trip form; pandas before 3 parses it
    # exactly only with float_precision="round_trip" (3 does by default, and deprecates it).
    exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
    csv = pd.read_csv(root / "cli" / "results.csv", **exact)
    assert list(table.columns) == list(csv.columns)
    pd.testing.assert_frame_equal(table, csv, check_exact=True)
    ratio = table["back_effect.operating.bending.force_ratio"]
    # The paper's Fig. 2a: +27 % / -25 % at sigma_a = -/+ 6.4e8 Pa (docs/user/studies.md).
    assert ratio.iloc[0] == pytest.approx(1.27, abs=0.01)
    assert ratio.iloc[-1] == pytest.approx(0.75, abs=0.01)
    assert (table["status"] == "ok").all()


def test_fig2a_points_are_points_csv(fig2a):
    root, s, _, _ = fig2a
    pts = s.plan(as_pandas=False)  # no directory: the points only
    assert s.directory == root / "py"
    lines = (root / "cli" / "points.csv").read_text().splitlines()
    assert lines[0].split(",") == ["index", "seed", "bulk.stress"] == list(pts)
    for i, line in enumerate(lines[1:]):
        index, seed, stress = line.split(",")
        assert (pts["index"][i], pts["seed"][i]) == (int(index), int(seed))
        assert pts["bulk.stress"][i] == float(stress)
    assert pts["bulk.stress"].dtype == np.float64


def test_fig2a_xarray_is_results_nc(fig2a):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("scipy")
    root, s, _, _ = fig2a
    ds = s.gather(as_xarray=True, write=False)
    nc = xr.open_dataset(root / "cli" / "results.nc", engine="scipy")
    assert list(ds.data_vars) == list(nc.data_vars)
    for name in nc.data_vars:
        if nc[name].dtype.kind == "f":
            np.testing.assert_array_equal(ds[name].values, nc[name].values)
        assert ds[name].attrs.get("units") == nc[name].attrs.get("units"), name
    assert ds.attrs["title"] == nc.attrs["title"] == "fig2a"
    assert [str(v) for v in ds["status"].values] == ["ok"] * 9


def test_open_reads_a_cli_directory(fig2a):
    root, s, _, table = fig2a
    again = tribo.study.open(root / "cli")
    assert again.name == "fig2a" and len(again) == 9 and again.directory == root / "cli"
    st = again.status()
    assert st.complete and st.done == list(range(9)) and st.resubmit == ""
    # Running a complete study computes nothing.
    r = again.run(jobs=1)
    assert (r.done, r.skipped) == (0, 9)


def test_resume_failures_and_progress(tmp_path, tribo_bin):
    s = tribo.study.load(BALLS)
    assert len(s) == 8 and s.parameters == ["contact.load", "body2.nu", "body1.radii[0]"]
    assert s.units["contact.max_pressure_Pa"] == "Pa"
    calls = []
    r = s.run(tmp_path / "b", jobs=1, points=[0, 1, 2],
              progress=lambda done, total: calls.append((done, total)))
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]
    # Points 2 and 3 have nu = 0.7: an invalid case, recorded with the point.
    assert r.done == 2 and list(r.failed) == [2]
    assert r.failed[2].startswith("failed: body2.nu = 0.7")
    st = s.status()
    assert st.done == [0, 1] and list(st.failed) == [2] and st.missing == [3, 4, 5, 6, 7]
    assert st.resubmit == "2-7"
    # The command line reads the same directory the same way.
    out = cli(tribo_bin, "sweep", "status", str(tmp_path / "b"))
    assert "2 done, 1 failed, 5 missing" in out and "--array=2-7 " in out
    # Resumed: the done points are skipped, the failed one is tried again.
    r = s.run(jobs=2)
    assert (r.done, r.skipped, sorted(r.failed)) == (2, 2, [2, 3, 6, 7])
    t = s.gather(as_pandas=False)
    assert list(t["status"]).count("ok") == 4
    assert all(math.isnan(x) for x, st in zip(t["contact.max_pressure_Pa"], t["status"])
               if st != "ok")
    assert t["index"].dtype == np.int64 and t["contact.iterations"].dtype == np.float64


def test_a_raising_progress_stops_the_run_and_it_resumes(tmp_path):
    # 48 x 48 grids: a point takes tens of ms, the callback microseconds.
    s = tribo.study.load(BALLS.replace("n = 16", "n = 48"))
    todo = [0, 1, 4, 5]

    def stop_after_one(done, total):
        if done >= 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        s.run(tmp_path / "b", jobs=1, points=todo, progress=stop_after_one)
    st = s.status()
    # One worker: point 0 done, at most the point in flight when the callback raised (1)
    # finished after it, nothing started later.
    assert st.done[:1] == [0] and set(st.done) <= {0, 1} and not st.failed
    r = s.run(points=todo, jobs=1)
    assert (r.done, r.skipped) == (4 - len(st.done), len(st.done))
    assert s.status().done == todo


def test_run_releases_the_gil(tmp_path):
    s = tribo.study.load(BALLS.replace("n = 16", "n = 48"))
    done = threading.Event()
    t = threading.Thread(target=lambda: (s.run(tmp_path / "b", jobs=1), done.set()))
    t.start()
    turns = 0
    while not done.is_set():
        turns += 1
        time.sleep(0)
    t.join()
    assert turns > 50, turns


def test_point_case_runs_alone(tmp_path):
    s = tribo.study.load(BALLS)
    case = s.case(5)
    assert isinstance(case, tribo.Case)
    assert "body1" in case.toml and case.kind == "halfspace"
    s.run(tmp_path / "b", points=[5], jobs=1)
    summary = tribo.run(case).summary
    t = s.gather(as_pandas=False, write=False)
    assert t["contact.max_pressure_Pa"][5] == summary["contact"]["max_pressure"]
    with pytest.raises(tribo.InputError) as e:
        s.case(2)  # nu = 0.7
    assert e.value.field == "body2.nu"


@pytest.mark.parametrize("change, item", [
    (("key = \"contact.load\"", "key = \"contact.lod\""), "grid[0].key"),
    (("seed = 3", "seed = -1"), "study.seed"),
    (("low = 0.008", "low = 0.02"), "random[0]"),
    (("samples = 2", "samples = 0"), "study.samples"),
    (("E = \"210 GPa\"", "E = \"-210 GPa\""), "body1.E"),
])
def test_bad_input_names_the_item(change, item, tribo_bin, tmp_path):
    text = BALLS.replace(*change, 1)
    with pytest.raises(tribo.InputError) as e:
        tribo.study.load(text)
    assert e.value.field.startswith(item), (e.value.field, str(e.value))
    # The command line refuses the same file with exit 2 and the same message.
    (tmp_path / "s.toml").write_text(text)
    out = subprocess.run([tribo_bin, "sweep", "plan", str(tmp_path / "s.toml")],
                         capture_output=True, text=True)
    assert out.returncode == 2 and item in out.stderr


def test_load_from_dict_path_and_example(tmp_path):
    s = tribo.study.load({
        "study": {"name": "d", "example": "sphere-on-flat", "collect": ["contact.max_pressure"]},
        "set": {"grid.n": 16},
        "grid": [{"key": "contact.load", "values": [50.0, 100.0]}],
    })
    assert (s.name, len(s), s.collect) == ("d", 2, ["contact.max_pressure_Pa"])
    (tmp_path / "balls.toml").write_text(BALLS)
    assert len(tribo.study.load(tmp_path / "balls.toml")) == 8
    assert len(tribo.study.load(str(tmp_path / "balls.toml"))) == 8
    assert set(tribo.study.examples()) >= {"fig2a", "sec6", "sec7-knife", "roller-monte-carlo",
                                          "roller-random-limit"}
    assert len(tribo.study.example("fig2a")) == 9
    with pytest.raises(tribo.InputError):
        tribo.study.example("nope")
    with pytest.raises(FileNotFoundError):
        tribo.study.load(tmp_path / "missing.toml")
    # An endless file is refused at the size limit, not read forever.
    if os.path.exists("/dev/zero"):
        with pytest.raises(tribo.InputError) as e:
            tribo.study.load(Path("/dev/zero"))
        assert e.value.field == "study"


def test_directory_errors(tmp_path):
    s = tribo.study.load(BALLS)
    with pytest.raises(tribo.InputError) as e:
        s.status()
    assert e.value.field == "directory"
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "file.txt").write_text("x")
    with pytest.raises(tribo.InputError) as e:
        s.run(tmp_path / "other")
    assert e.value.field == "directory"
    with pytest.raises(tribo.InputError) as e:
        tribo.study.open(tmp_path / "nothing-here")
    assert e.value.field == "directory"
    s.plan(tmp_path / "b")
    with pytest.raises(tribo.InputError) as e:
        tribo.study.load(BALLS.replace("seed = 3", "seed = 4")).plan(tmp_path / "b")
    assert e.value.field == "directory" and "another study" in str(e.value)
    with pytest.raises(tribo.InputError) as e:
        s.run(jobs=0)
    assert e.value.field == "jobs"
    with pytest.raises(tribo.InputError) as e:
        s.run(points=[8])
    assert e.value.field == "points"
    # A newline in the partition would end the #SBATCH line and make the rest shell code.
    s.plan(tmp_path / "c")
    with pytest.raises(tribo.InputError) as e:
        s.slurm(tribo=sys.executable, partition="a\nrm -rf /tmp/x")
    assert e.value.field == "partition"
    with pytest.raises(tribo.InputError) as e:
        s.slurm(tribo=sys.executable, time="99:99:99")
    assert e.value.field == "time"


def test_slurm_scripts_are_the_clis(tmp_path, tribo_bin, monkeypatch):
    exe = os.path.realpath(tribo_bin)  # the CLI writes its own path (current_exe)
    s = tribo.study.load(BALLS)
    s.plan(tmp_path / "b")
    opts = dict(chunk=3, partition="debug", time="00:10:00", cpus_per_task=2, max_running=4)
    paths = s.slurm(tribo=exe, **opts)
    slurm = tmp_path / "b" / "slurm"
    assert paths == {"array": slurm / "array.sbatch", "gather": slurm / "gather.sbatch"}
    ours = {p.name: p.read_bytes() for p in slurm.iterdir() if p.is_file()}
    assert set(ours) == {"array.sbatch", "gather.sbatch", "settings.json"}
    assert b"--array=0-2%4" in ours["array.sbatch"]
    shutil.rmtree(slurm)
    cli(exe, "sweep", "slurm", str(tmp_path / "b"), "--chunk", "3", "--partition", "debug",
        "--time", "00:10:00", "--cpus-per-task", "2", "--max-running", "4")
    assert {p.name: p.read_bytes() for p in slurm.iterdir() if p.is_file()} == ours
    assert s.status().chunk == 3

    # --submit through a stand-in sbatch on PATH that records its arguments.
    bindir = tmp_path / "bin"
    bindir.mkdir()
    log = tmp_path / "sbatch.log"
    (bindir / "sbatch").write_text(
        f"#!/bin/sh\necho \"$@\" >> {log}\nn=$(wc -l < {log})\necho \"Submitted batch job 4$n\"\n")
    (bindir / "sbatch").chmod(0o755)
    monkeypatch.setenv("PATH", f"{bindir}{os.pathsep}{os.environ['PATH']}")
    out = s.slurm(tribo=exe, chunk=3, submit=True)
    assert (out["array_job"], out["gather_job"]) == (41, 42)
    assert log.read_text().splitlines() == [
        str(slurm / "array.sbatch"), f"--dependency=afterany:41 {slurm / 'gather.sbatch'}"]

    for bad, field in ((dict(chunk=0), "chunk"), (dict(time="1h"), "time"),
                       (dict(cpus_per_task=0), "cpus_per_task"),
                       (dict(tribo=str(tmp_path / "no-tribo")), "tribo")):
        with pytest.raises(tribo.InputError) as e:
            s.slurm(**{"tribo": exe, **bad})
        assert e.value.field == field


def test_cases_pickle():
    case = tribo.Case.example("sphere-on-flat")
    back = pickle.loads(pickle.dumps(case))
    assert (back.toml, back.title, back.kind) == (case.toml, case.title, case.kind)


@pytest.mark.parametrize("module", [tribo, tribo.study, tribo.fatigue, tribo.surface])
def test_dir_shows_the_api_only(module):
    # Tab completion lists dir(module): every public name is in __all__ or is a submodule
    # (the module's __dir__).
    def submodule(obj):
        return (isinstance(obj, types.ModuleType)
                and obj.__name__.startswith(tribo.__name__ + "."))

    extra = [name for name in dir(module) if not name.startswith("_")
             and name not in module.__all__ and not submodule(getattr(module, name))]
    assert extra == []
    for name in module.__all__:
        assert getattr(module, name).__doc__, name


@pytest.mark.parametrize("module", [tribo, tribo.study, tribo.fatigue, tribo.surface])
def test_annotations_resolve(module):
    # typing.get_type_hints() evaluates the string annotations (PEP 563) in the module's
    # namespace: every name they use must be bound there (it raised NameError when the
    # typing names were imported for type checkers only).
    import inspect
    import typing

    checked = 0
    for name in module.__all__:
        obj = getattr(module, name)
        if isinstance(obj, types.ModuleType):
            continue
        members = [obj]
        if inspect.isclass(obj):
            members += [m for k, m in vars(obj).items()
                        if inspect.isfunction(m) and not k.startswith("_")]
            members += [p.fget for p in vars(obj).values() if isinstance(p, property)]
        for m in members:
            if inspect.isfunction(m) or inspect.isclass(m):
                typing.get_type_hints(m)
                checked += 1
    assert checked > 0


def test_study_stub_covers_the_bindings():
    stub = (Path(tribo.__file__).parent / "_tribo.pyi").read_text()
    for name in ("class Study", "class StudyDir", "def slurm_ranges", "def slurm_job_id",
                 "def study_examples", "def from_toml_text", "def gather", "def states",
                 "def case_toml", "def base_dir"):
        assert name in stub, name
    for cls in (tribo._tribo.Study, tribo._tribo.StudyDir):
        for attr in dir(cls):
            if not attr.startswith("_"):
                assert f"def {attr}(" in stub, f"{cls.__name__}.{attr}"
