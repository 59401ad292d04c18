"""tribo.run mapped over cases on a Dask cluster, the results collected into a DataFrame.

A load and radius sweep of a steel ball on a steel flat (the Hertz contact of the example
``sphere-on-flat``), each case run by ``tribo.run`` on a worker of a
``dask.distributed.LocalCluster`` (processes, 2 workers of one thread each). The same code
runs on a cluster by giving the Client another cluster (``dask_jobqueue.SLURMCluster``, say).
Cases cross to the workers as their TOML text (``tribo.Case`` pickles so); what comes back is
a dict of numbers per case. Each worker computes with one thread (``RAYON_NUM_THREADS=1``):
the workers share the machine's cores, and the numbers are the same bits as a serial
``tribo.run`` (tests/python/test_dask.py checks it).

For a sweep over a case file's keys with resumable point directories, a results table and
SLURM scripts, ``tribo.study`` is the tool (docs/user/studies.md); this example shows the
other way, for users whose workflow is already Dask.

    pip install "dask[distributed]" pandas
    python examples/python/dask_sweep.py                 # prints the table
    python examples/python/dask_sweep.py --json out.json # and writes its rows (exact floats)
"""

import argparse
import json
import sys

import tribo

LOADS = [25.0, 50.0, 100.0, 200.0]  # N
RADII = [0.01, 0.02]  # m (the ball's radius)


def cases():
    """The cases of the sweep: a steel ball of each radius on a steel flat, at each load."""
    out = []
    for radius in RADII:
        for load in LOADS:
            out.append(tribo.Case.from_dict({
                "title": f"ball R = {radius * 1e3:g} mm, F = {load:g} N",
                "body1": {"E": "210 GPa", "nu": 0.3, "radii": [radius, radius]},
                "body2": {"E": "210 GPa", "nu": 0.3, "radii": ["inf", "inf"]},
                "contact": {"load": load},
                "grid": {"n": 48, "extent": 1.5},
            }))
    return out


def summarize(case):
    """Runs one case (on a worker) and returns the numbers of the table's row."""
    s = tribo.run(case).summary
    c = s["contact"]
    return {
        "title": case.title,
        "load_N": c["normal_load"],
        "max_pressure_Pa": c["max_pressure"],
        "hertz_p0_Pa": c["hertz"]["p0"],
        "contact_area_m2": c["contact_area"],
        "approach_m": c["approach"],
        "iterations": c["iterations"],
    }


def run_on_dask(case_list, n_workers=2):
    """``summarize`` mapped over the cases on a LocalCluster of ``n_workers`` processes;
    the rows in the cases' order."""
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                      dashboard_address=None, env={"RAYON_NUM_THREADS": "1"}) as cluster, \
            Client(cluster) as client:
        futures = client.map(summarize, case_list, pure=False)
        return client.gather(futures)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--json", help="write the rows here (a JSON list of dicts)")
    args = parser.parse_args(argv)
    rows = run_on_dask(cases(), args.workers)
    try:
        import pandas as pd
    except ImportError:
        table = rows
        print(json.dumps(rows, indent=1))
    else:
        table = pd.DataFrame(rows)
        print(table.to_string())
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f)  # Python's float repr: every double round-trips exactly
    return table


if __name__ == "__main__":  # the guard the workers' spawned processes need
    main()
    sys.exit(0)
