"""Studies from Python: the engine of ``tribo sweep`` (docs/user/studies.md).

A study file names a base case, the key paths that vary over it (grids, zipped lists, random
samples) and the numbers to collect from each run's summary. This module binds the same
engine as the command line (the Rust crate ``tribo-study``): the study is checked and
expanded there, each point runs there into its own directory (written atomically: a study
killed at any moment resumes where it stopped), and the table is gathered there, so the
``results.csv`` and ``results.nc`` written here are the bytes ``tribo sweep gather`` writes.

::

    import tribo.study
    s = tribo.study.load("fig2a.toml")        # a path, a TOML text or a dict
    s = tribo.study.example("fig2a")          # or an embedded study (tribo sweep example)
    s.plan()                                  # DataFrame: index, seed, the parameters
    report = s.run("fig2a", jobs=2, progress=True)   # plans into fig2a/ and runs (resumable)
    s.status()                                # done, failed (with reasons), missing
    df = s.gather()                           # DataFrame; also writes results.csv/.nc
    ds = s.gather(as_xarray=True)             # the same columns as an xarray.Dataset
    s.slurm(chunk=10, cpus_per_task=4)        # the SLURM scripts of `tribo sweep slurm`
    s = tribo.study.open("fig2a")             # a planned study directory (from either tool)

Without pandas the tables come as dicts of numpy arrays (strings as object arrays).
Errors: bad input in the study raises :class:`tribo.InputError` naming the item
(``grid[0].key``, ``study.seed``, ``random[1].sd``, a field of the base case), as
``tribo sweep`` exits 2; a point whose case breaks a rule is not an error of the study: it
is recorded with the point (``status()``, the ``status`` column) and the others go on.
"""

from __future__ import annotations

import json as _json
import os as _os
import shutil as _shutil
import subprocess as _subprocess
import sys as _sys
import time as _time
from collections.abc import Mapping as _Mapping
from dataclasses import dataclass as _dataclass
from pathlib import Path as _Path

import numpy as _np

from . import _tribo

# Bound for real (typing.get_type_hints resolves the string annotations); `__dir__` keeps
# them out of dir(). tribo/__init__.py imports this module after defining Case.
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import Case

del annotations  # the __future__ feature's name: not part of the API

__all__ = ["RunReport", "Status", "Study", "example", "examples", "load", "open"]


def _input_error(field: str, rule: str, value: Any = "") -> Exception:
    err = _tribo.InputError(f"{field}: {rule}")
    err.field, err.value, err.rule = field, str(value), rule
    return err


def _is_path(source: Any) -> bool:
    return isinstance(source, _os.PathLike) or (
        isinstance(source, str)
        and "\n" not in source
        and (source.endswith(".toml") or _os.path.isfile(source))
    )


@_dataclass(frozen=True)
class RunReport:
    """What :meth:`Study.run` did."""

    done: int
    """Points computed now."""
    failed: Dict[int, str]
    """Points that failed now, with the reasons (``failed: ...``)."""
    skipped: int
    """Points skipped because they were already done (a resumed study)."""
    seconds: float
    """Wall time of the run, s."""
    point_seconds: float
    """The sum of the points' own wall times (compute and write), s."""
    jobs: int
    """Points computed at once."""


@_dataclass(frozen=True)
class Status:
    """The state of a study directory's points (``tribo sweep status``)."""

    done: List[int]
    """Points computed."""
    failed: Dict[int, str]
    """Points that failed, with the reasons."""
    missing: List[int]
    """Points neither done nor failed."""
    chunk: int
    """Points per SLURM array task (the one of :meth:`Study.slurm`, else 1)."""

    @property
    def complete(self) -> bool:
        """Every point done."""
        return not self.failed and not self.missing

    @property
    def resubmit(self) -> str:
        """The array tasks holding failed or missing points in SLURM's ``--array=`` form
        (``0-3,7``; empty when there are none): ``sbatch --array=... slurm/array.sbatch``."""
        tasks = sorted({i // self.chunk for i in list(self.failed) + self.missing})
        return _tribo.slurm_ranges(tasks)

    def __repr__(self) -> str:
        return (f"Status(done={len(self.done)}, failed={len(self.failed)}, "
                f"missing={len(self.missing)})")


def _table(columns: Sequence[Tuple[str, list]], as_pandas: Optional[bool]) -> Any:
    """Columns as a pandas DataFrame (where pandas is installed and ``as_pandas`` is not
    False) or a dict of numpy arrays."""
    if as_pandas is not False:
        try:
            import pandas as pd
        except ImportError:
            if as_pandas:
                raise
        else:
            # Text columns as lists: pandas gives them its default string dtype, as
            # `pandas.read_csv("results.csv")` does.
            data = {}
            for name, values in columns:
                col = _column(values)
                data[name] = values if col.dtype == object else col
            return pd.DataFrame(data)
    return {name: _column(values) for name, values in columns}


def _column(values: list) -> _np.ndarray:
    """A column as a numpy array: int64, float64, bool, or object for text and mixed values."""
    kinds = {type(v) for v in values}
    if kinds <= {int}:
        return _np.array(values, dtype=_np.int64)
    if kinds <= {float, int} and kinds:
        return _np.array(values, dtype=_np.float64)
    if kinds == {bool}:
        return _np.array(values, dtype=bool)
    return _np.array(values, dtype=object)


def _printer(name: str) -> Callable[[int, int], None]:
    """A progress line on stderr: the points done, the elapsed time and the ETA."""
    start = _time.monotonic()

    def show(done: int, total: int) -> None:
        elapsed = _time.monotonic() - start
        eta = f"{elapsed / done * (total - done):.0f} s" if done else "?"
        end = "\n" if done >= total else ""
        _sys.stderr.write(f"\r{name}: {done}/{total} points, {elapsed:.0f} s, ETA {eta}{end}")
        _sys.stderr.flush()

    return show


class Study:
    """A checked study: its points, and (once planned) its directory.

    Build one with :func:`load`, :func:`example` or :func:`open`. ``len(study)`` is the
    number of points.
    """

    __slots__ = ("_inner", "_dir")

    def __init__(self, inner: "_tribo.Study", directory: "Optional[_tribo.StudyDir]" = None):
        self._inner = inner
        self._dir = directory

    # ---- what the study is ---------------------------------------------------------------

    @property
    def name(self) -> str:
        """The study's name (``study.name``, else the file's stem)."""
        return self._inner.name

    @property
    def seed(self) -> int:
        """The study seed (``study.seed``)."""
        return self._inner.seed

    @property
    def kind(self) -> str:
        """The kind of the base case: ``"halfspace"`` or ``"bem2d"``."""
        return self._inner.kind

    @property
    def text(self) -> str:
        """The study file's TOML text."""
        return self._inner.text

    @property
    def parameters(self) -> List[str]:
        """The parameters' key paths, in column order (grid, zip, random)."""
        return [key for key, _, _ in self._inner.parameters]

    @property
    def collect(self) -> List[str]:
        """The collected columns: key path and unit (``contact.max_pressure_Pa``)."""
        return [column for column, _, _ in self._inner.collect]

    @property
    def units(self) -> Dict[str, str]:
        """The unit of each collected column (``"1"``: dimensionless)."""
        return {column: unit for column, _, unit in self._inner.collect}

    @property
    def directory(self) -> Optional[_Path]:
        """The study directory once planned (:meth:`plan`, :meth:`run`, :func:`open`)."""
        return None if self._dir is None else _Path(self._dir.directory)

    def __len__(self) -> int:
        return len(self._inner)

    def __repr__(self) -> str:
        where = "" if self._dir is None else f", directory={str(self.directory)!r}"
        return f"Study(name={self.name!r}, points={len(self)}{where})"

    def points(self, as_pandas: Optional[bool] = None) -> Any:
        """The points (``points.csv``): ``index``, ``seed`` (the point's own seed, below
        2**53) and each parameter's value by its key path, one row per point. A pandas
        DataFrame, or a dict of numpy arrays without pandas (or with ``as_pandas=False``)."""
        return _table(self._inner.points(), as_pandas)

    def case(self, index: int) -> Case:
        """Point ``index``'s case (the base case with the point's parameters set), e.g. to
        run one point alone with :func:`tribo.run`. Raises :class:`tribo.InputError` when
        the point's parameters make an invalid case."""
        text = self._inner.case_toml(int(index))
        base = str(self._inner.base_dir) or None
        return Case(_tribo.Case.from_toml_text(text, f"{self.name} point {int(index):06}", base))

    # ---- the directory -------------------------------------------------------------------

    def plan(
        self,
        directory: Union[str, "_os.PathLike[str]", None] = None,
        as_pandas: Optional[bool] = None,
    ) -> Any:
        """The points, as :meth:`points` gives them (``tribo sweep plan``'s ``points.csv``):
        a DataFrame of ``index``, ``seed`` and the parameters. With a ``directory`` the study
        is also planned into it (``tribo sweep plan -o``: ``study.toml``, ``base.toml``,
        ``plan.json``, ``points.csv``) and bound to it. A directory that holds the same study
        is kept with its computed points; one that holds another study (or other files)
        raises :class:`tribo.InputError` (field ``directory``)."""
        if directory is not None:
            self._dir = self._inner.plan(_os.fspath(directory))
        return self.points(as_pandas)

    def _planned(self, directory: Any) -> "_tribo.StudyDir":
        if directory is not None:
            path = _os.fspath(directory)
            if self._dir is None or _Path(self._dir.directory) != _Path(path):
                self._dir = self._inner.plan(path)
        if self._dir is None:
            raise _input_error("directory", "the study is not planned yet: give its directory "
                               "(run(directory) plans into it)")
        return self._dir

    def run(
        self,
        directory: Union[str, "_os.PathLike[str]", None] = None,
        *,
        jobs: Optional[int] = None,
        points: Optional[Sequence[int]] = None,
        progress: Union[bool, Callable[[int, int], Any], None] = None,
    ) -> RunReport:
        """Runs the points not done yet (``tribo sweep run``): plans into ``directory``
        first where it is given (a directory of the same study is resumed), else runs in the
        study's directory.

        ``jobs``: points computed at once (default: the CPUs available), each on one thread,
        so the numbers are the same bits for any ``jobs``. ``points``: only these indices.
        ``progress``: True for a line on stderr with the ETA, or a callable
        ``progress(done, total)`` called after each point. The GIL is released while the
        points run; Ctrl-C (or an exception raised by ``progress``) stops the run once the
        points in flight are written, and is raised then: run again to resume.

        A point whose case is invalid or whose solver fails does not raise: it is recorded
        (``RunReport.failed``, :meth:`status`, the ``status`` column) and the others go on.
        """
        sd = self._planned(directory)
        callback = _printer(self.name) if progress is True else (progress or None)
        r = sd.run(None if points is None else [int(i) for i in points],
                   None if jobs is None else int(jobs), callback)
        return RunReport(done=r["done"], failed=dict(r["failed"]), skipped=r["skipped"],
                         seconds=r["seconds"], point_seconds=r["point_seconds"], jobs=r["jobs"])

    def status(self, directory: Union[str, "_os.PathLike[str]", None] = None) -> Status:
        """Done, failed (with the reasons) and missing points (``tribo sweep status``)."""
        sd = self._planned(directory)
        done, failed, missing = [], {}, []
        for i, (state, reason) in enumerate(sd.states()):
            if state == "done":
                done.append(i)
            elif state == "failed":
                failed[i] = reason
            else:
                missing.append(i)
        chunk = 1
        settings = _Path(sd.directory) / "slurm" / "settings.json"
        if settings.is_file():
            try:
                chunk = int(_json.loads(settings.read_text())["chunk"]) or 1
            except (ValueError, KeyError, TypeError):
                chunk = 1
        return Status(done=done, failed=failed, missing=missing, chunk=chunk)

    def gather(
        self,
        directory: Union[str, "_os.PathLike[str]", None] = None,
        *,
        write: bool = True,
        as_xarray: bool = False,
        as_pandas: Optional[bool] = None,
    ) -> Any:
        """The results table (``tribo sweep gather``): one row per point, in point order:
        ``index``, ``seed``, the parameters, the collected numbers (column names with their
        unit, NaN where a point has none) and ``status`` (``ok``, ``failed: <reason>``,
        ``missing``). With ``write`` (default) ``results.csv`` and ``results.nc`` are written
        into the directory as well: the bytes of ``tribo sweep gather``.

        A pandas DataFrame (the numbers of ``results.csv`` bit for bit), a dict of numpy
        arrays without pandas, or with ``as_xarray=True`` an ``xarray.Dataset`` over the
        dimension ``point`` with the variables, units and attributes of ``results.nc``.

        The plot pages of ``tribo sweep gather`` (``plots/<column>.png``: histograms,
        exceedance curves with their confidence band, rank correlations, scatter and grid
        plots; docs/user/studies.md, "Plots") are not drawn here: run ``tribo sweep gather``
        on the same directory for them, or plot the table with pandas.
        """
        sd = self._planned(directory)
        t = sd.gather(bool(write))
        if as_xarray:
            import xarray as xr

            data = {}
            for name, values in t["columns"]:
                attrs = {}
                if name in t["units"]:
                    attrs["units"] = t["units"][name]
                if name in t["keys"]:
                    attrs["key"] = t["keys"][name]
                data[name] = xr.Variable(("point",), _column(values), attrs)
            return xr.Dataset(data, attrs=dict(t["attrs"]))
        return _table(t["columns"], as_pandas)

    def slurm(
        self,
        directory: Union[str, "_os.PathLike[str]", None] = None,
        *,
        chunk: Optional[int] = None,
        partition: Optional[str] = None,
        time: str = "01:00:00",
        cpus_per_task: int = 1,
        max_running: Optional[int] = None,
        tribo: Union[str, "_os.PathLike[str]", None] = None,
        submit: bool = False,
    ) -> Dict[str, Any]:
        """Writes the SLURM scripts of ``tribo sweep slurm`` into ``DIR/slurm`` (the same
        files): an array job of ``chunk`` points per task (default: 1, or enough to keep the
        array within 1001 tasks), ``cpus_per_task`` points at once in each, ``time`` per task
        (``[D-]HH:MM:SS``), an optional ``partition`` and ``max_running`` (``%K``), and a
        gather job. The tasks run the command line: ``tribo`` is its path (default: ``tribo``
        on PATH). With ``submit`` both are submitted with ``sbatch`` (the gather job
        ``--dependency=afterany`` on the array).

        Returns a dict: ``array`` and ``gather`` (the scripts' paths), and with ``submit``
        ``array_job`` and ``gather_job`` (the job ids).
        """
        sd = self._planned(directory)
        exe = _os.fspath(tribo) if tribo is not None else _shutil.which("tribo")
        if exe is None:
            raise _input_error("tribo", "no tribo binary on PATH: give its path (tribo=...)")
        exe = _os.path.abspath(exe)
        array, gather = sd.slurm(exe, None if chunk is None else int(chunk), partition,
                                 str(time), int(cpus_per_task),
                                 None if max_running is None else int(max_running))
        out: Dict[str, Any] = {"array": _Path(array), "gather": _Path(gather)}
        if submit:
            out["array_job"] = _sbatch([_os.fspath(array)])
            out["gather_job"] = _sbatch([f"--dependency=afterany:{out['array_job']}",
                                         _os.fspath(gather)])
        return out


def _sbatch(args: List[str]) -> int:
    """Runs ``sbatch ARGS`` and returns the job id it answers."""
    done = _subprocess.run(["sbatch", *args], capture_output=True, text=True)
    job = _tribo.slurm_job_id(done.stdout) if done.returncode == 0 else None
    if job is None:
        raise _tribo.SolverError(
            f"sbatch {' '.join(args)}: exit {done.returncode}: "
            f"{(done.stderr or done.stdout).strip()}")
    return job


def load(
    source: Union[str, "_os.PathLike[str]", Mapping[str, Any]],
    base_dir: Union[str, "_os.PathLike[str]", None] = None,
) -> Study:
    """A study from a study file (a path), a TOML text, or a dict with the keys of a study
    file (``{"study": {...}, "grid": [{...}], ...}``), checked as ``tribo sweep plan``
    checks it. A relative ``study.base`` resolves against the file's folder, else against
    ``base_dir`` (default: the working directory). Raises :class:`tribo.InputError` naming
    the item, or FileNotFoundError."""
    from . import _plain

    if isinstance(source, _Mapping):
        folder = _os.fspath(base_dir) if base_dir is not None else _os.getcwd()
        return Study(_tribo.Study.from_dict(_plain(source), "<dict>", folder))
    if _is_path(source):
        from . import _input_error

        path = _Path(source)
        # Read no further than the case-file limit of the CLI (16 MiB): an endless file
        # (/dev/zero) is refused instead of read forever.
        limit = 16 << 20
        with path.open("rb") as f:
            data = f.read(limit + 1)
        if len(data) > limit:
            raise _input_error(
                "study",
                "larger than 16 MiB (a study file is a few hundred lines of TOML)",
                str(path),
            )
        text = data.decode("utf-8")
        return Study(_tribo.Study.from_toml_text(text, str(path), str(path.parent)))
    folder = _os.fspath(base_dir) if base_dir is not None else _os.getcwd()
    return Study(_tribo.Study.from_toml_text(str(source), "<string>", folder))


def example(name: str) -> Study:
    """An embedded study file (``tribo sweep example NAME``); :func:`examples` lists them."""
    return Study(_tribo.Study.example(name))


def examples() -> Dict[str, str]:
    """The embedded study files: name -> one-line description."""
    return dict(_tribo.study_examples())


def open(directory: Union[str, "_os.PathLike[str]"]) -> Study:  # noqa: A001 (as xarray's)
    """A planned study directory (from :meth:`Study.plan`/:meth:`Study.run` or from
    ``tribo sweep plan``), its study read back from it: :meth:`Study.run` resumes it,
    :meth:`Study.status` and :meth:`Study.gather` read it."""
    sd = _tribo.StudyDir.open(_os.fspath(directory))
    return Study(sd.study, sd)


def __dir__() -> List[str]:
    # Tab completion and dir() list the API alone; the typing names above are real module
    # attributes so that typing.get_type_hints() resolves the (string) annotations.
    return sorted(__all__)
