"""Fit a fatigue data set with pyLife's Elementary and MaxLikeFull analysers; print JSON.

usage: python pylife_woehler.py DATA.csv

DATA.csv: tribo's format (comment lines '#', header with load_MPa or load_Pa or load,
cycles, runout or fracture). Loads are given to pyLife in MPa (pyLife is unit-agnostic;
MaxLikeFull's likelihood is invariant to the load unit) and reported back in Pa.
"""
import datetime
import json
import sys
import warnings

import numpy as np
import pandas as pd
import pylife
from pylife.materialdata import woehler


def read(path):
    df = pd.read_csv(path, comment="#")
    if "load_MPa" in df:
        load = df["load_MPa"].astype(float)
    elif "load_Pa" in df:
        load = df["load_Pa"].astype(float) / 1e6
    else:
        load = df["load"].astype(float) / 1e6
    if "runout" in df:
        fracture = ~df["runout"].astype(str).str.lower().isin(["true", "1", "yes"])
    else:
        fracture = df["fracture"].astype(str).str.lower().isin(["true", "1", "yes"])
    return pd.DataFrame({"load": load, "cycles": df["cycles"].astype(float), "fracture": fracture})


def as_dict(wc):
    out = {}
    for key in ["SD", "k_1", "ND", "TN", "TS"]:
        v = float(wc[key])
        out[key] = v * 1e6 if key == "SD" else v
    return out


def main():
    df = read(sys.argv[1])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        elementary = woehler.Elementary(df).analyze()
        mlf = woehler.MaxLikeFull(df)
        full = mlf.analyze()
        ll = float(mlf._lh.likelihood_total(full["SD"], full["TS"], full["k_1"], full["ND"], full["TN"]))
    print(json.dumps({
        "pylife_version": pylife.__version__,
        "numpy_version": np.__version__,
        "pandas_version": pd.__version__,
        "date": datetime.date.today().isoformat(),
        "data": sys.argv[1],
        "units": "SD in Pa (stress amplitude); ND cycles; TN, TS 10%/90% scatter ratios",
        "elementary": as_dict(elementary),
        "max_like_full": dict(as_dict(full), log_likelihood=ll,
                              likelihood="LikelihoodHighestMixedLevel (default)",
                              optimiser="scipy.optimize.fmin (Nelder-Mead), maxiter=maxfun=1e4"),
        "warnings": [str(w.message) for w in caught],
    }, indent=2))


if __name__ == "__main__":
    main()
