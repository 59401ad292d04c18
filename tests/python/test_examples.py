"""The example script runs (examples/python/quickstart.py), and the package is typed."""

import json
import subprocess
import sys
from pathlib import Path

import tribo

ROOT = Path(__file__).resolve().parents[2]


def test_quickstart_runs(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "quickstart.py"),
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert "partial slip: stick radius" in out.stdout
    assert (tmp_path / "out" / "summary.json").is_file()


def test_package_is_typed_and_documented():
    pkg = Path(tribo.__file__).parent
    assert (pkg / "py.typed").is_file() and (pkg / "_tribo.pyi").is_file()
    for name in tribo.__all__:
        obj = getattr(tribo, name)
        assert obj.__doc__ and obj.__doc__.strip(), name


def test_notebook_runs():
    # The notebook examples/python/tour.ipynb, executed cell by cell in one namespace in this
    # process (its JSON read with the standard library: no Jupyter kernel, nbclient or
    # nbformat needed); every code cell asserts what it shows.
    nb = json.loads((ROOT / "examples" / "python" / "tour.ipynb").read_text())
    assert nb["nbformat"] == 4
    namespace = {"__name__": "__notebook__"}
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    assert len(cells) >= 6
    for k, cell in enumerate(cells):
        source = "".join(cell["source"])
        exec(compile(source, f"tour.ipynb[cell {k}]", "exec"), namespace)  # noqa: S102
    assert namespace["d"].volume > 0
