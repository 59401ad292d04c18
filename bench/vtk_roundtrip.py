"""Reads tribo's binary VTK files with VTK's own XML readers and with pyvista and checks them.

usage: python bench/vtk_roundtrip.py NEW_DIR [OLD_DIR]

For every .vti / .vtu in NEW_DIR: both readers must read it (no reader error), agree with each
other bit for bit, and hold finite values. Where NEW_DIR has pressure.csv / gap.csv, fields.vti's
cell arrays must equal the CSV columns exactly (the CSV prints f64 in shortest round-trip form).
With OLD_DIR (the same case written by the former ASCII writers), every array of every VTK file
must equal the old file's array exactly, with the same geometry (extent, origin, spacing, points,
cells). Exit 0 when all checks pass; prints one line per file.
"""
import os
import sys

import numpy as np
import pyvista as pv
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def vtk_read(path):
    if path.endswith(".vti"):
        r = vtk.vtkXMLImageDataReader()
    else:
        r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    errors = vtk.vtkFileOutputWindow()  # keep VTK's messages off the terminal
    r.Update()
    if r.GetErrorCode() != 0:
        raise SystemExit(f"{path}: VTK reader error code {r.GetErrorCode()}")
    return r.GetOutput()


def arrays(ds):
    out = {}
    for data in (ds.GetPointData(), ds.GetCellData()):
        for k in range(data.GetNumberOfArrays()):
            a = data.GetArray(k)
            out[a.GetName()] = vtk_to_numpy(a).copy()
    return out


def geometry(ds, path):
    if path.endswith(".vti"):
        return {
            "extent": np.array(ds.GetExtent()),
            "origin": np.array(ds.GetOrigin()),
            "spacing": np.array(ds.GetSpacing()),
        }
    cells = ds.GetCells()
    return {
        "points": vtk_to_numpy(ds.GetPoints().GetData()).copy(),
        "connectivity": vtk_to_numpy(cells.GetConnectivityArray()).copy(),
        "offsets": vtk_to_numpy(cells.GetOffsetsArray()).copy(),
        "types": vtk_to_numpy(ds.GetCellTypes() if hasattr(ds, "GetCellTypes") and callable(getattr(ds, "GetCellTypes")) and ds.GetCellTypes() is not None else ds.GetCellTypesArray()).copy(),
    }


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and np.array_equal(a, b)


def check(new_dir, old_dir):
    failures = 0
    names = sorted(f for f in os.listdir(new_dir) if f.endswith((".vti", ".vtu")))
    if not names:
        raise SystemExit(f"{new_dir}: no VTK files")
    for name in names:
        path = os.path.join(new_dir, name)
        ds = vtk_read(path)
        a = arrays(ds)
        mesh = pv.read(path)
        pa = {k: np.asarray(mesh.point_data[k]) for k in mesh.point_data.keys()}
        pa.update({k: np.asarray(mesh.cell_data[k]) for k in mesh.cell_data.keys()})
        problems = []
        if set(pa) != set(a):
            problems.append(f"pyvista arrays {sorted(pa)} != vtk {sorted(a)}")
        for k, v in a.items():
            if k in pa and not same(v, pa[k]):
                problems.append(f"{k}: pyvista differs from vtk")
            if v.dtype.kind == "f" and not np.all(np.isfinite(v)):
                problems.append(f"{k}: non-finite")
        if name == "fields.vti":
            for csv, key in (("pressure.csv", "pressure_Pa"), ("gap.csv", "gap_m")):
                p = os.path.join(new_dir, csv)
                if os.path.exists(p):
                    col = np.loadtxt(p, delimiter=",", skiprows=1)[:, 2]
                    if not same(col, a[key]):
                        problems.append(f"{key} != {csv}")
        compared = ""
        if old_dir:
            old = vtk_read(os.path.join(old_dir, name))
            oa = arrays(old)
            if set(oa) != set(a):
                problems.append(f"arrays {sorted(a)} != old {sorted(oa)}")
            for k in oa:
                if k in a and not same(oa[k], a[k]):
                    d = np.max(np.abs(oa[k].astype(float) - a[k].astype(float)))
                    problems.append(f"{k}: differs from the ASCII file (max |diff| {d:g})")
            go, gn = geometry(old, name), geometry(ds, name)
            for k in go:
                if not same(go[k], gn[k]):
                    problems.append(f"geometry {k} differs from the ASCII file")
            compared = f", equal to the ASCII file ({os.path.getsize(os.path.join(old_dir, name))} bytes)"
        n = ds.GetNumberOfPoints()
        status = "ok" if not problems else "FAIL: " + "; ".join(problems)
        print(f"{name}: {os.path.getsize(path)} bytes, {n} points, {ds.GetNumberOfCells()} cells, "
              f"{len(a)} arrays, vtk == pyvista{compared}: {status}")
        failures += bool(problems)
    return failures


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__)
    sys.exit(1 if check(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else None) else 0)
