#!/usr/bin/env python3
"""Turn the JSON lines of bench/periodic.sh into its markdown table (standard library only).

Usage: periodic_table.py RESULTS.jsonl
Each line is one JSON object with "n" and "code" in {"tamaas-periodic", "tribo-periodic",
"surface"} (bench/tamaas_periodic.py, tribo-bench-periodic, tamaas_periodic.py --surface-only).
"""

from __future__ import annotations

import json
import sys


def fmt(v, spec: str) -> str:
    if v is None:
        return "-"
    try:
        return format(v, spec)
    except (TypeError, ValueError):
        return str(v)


def mib(v) -> str:
    return "-" if v is None else f"{v / 2**20:.0f}"


def main() -> int:
    rows: dict[int, dict[str, dict]] = {}
    with open(sys.argv[1], encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if line:
                d = json.loads(line)
                rows.setdefault(int(d["n"]), {})[d["code"]] = d

    head = [
        "N",
        "tamaas s",
        "tamaas CPU s",
        "tamaas iters",
        "tamaas peak MiB",
        "tribo s",
        "tribo CPU s",
        "tribo iters",
        "tribo s/iter",
        "FFT pair s",
        "tribo peak MiB",
        "ratio",
        "max|dp|/max p",
        "contact mismatch",
        "min-map res. tribo / tamaas",
        "tamaas res. tribo / tamaas",
    ]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    errors = []
    for n in sorted(rows):
        r = rows[n]
        ta = r.get("tamaas-periodic", {})
        tr = r.get("tribo-periodic", {})
        for code, d in (("tamaas", ta), ("tribo", tr)):
            if "error" in d:
                errors.append(f"N = {n}, {code}: {d['error']}")
        ref = tr.get("reference") or {}
        res = tr.get("residuals") or {}
        ref_res = ref.get("residuals") or {}
        ratio = None
        if isinstance(tr.get("seconds"), float) and isinstance(ta.get("seconds"), float) and ta["seconds"] > 0:
            ratio = tr["seconds"] / ta["seconds"]
        cells = [
            str(n),
            fmt(ta.get("seconds"), ".3g"),
            fmt(ta.get("cpu_seconds"), ".3g"),
            fmt(ta.get("iterations"), "d"),
            mib(ta.get("peak_rss_bytes")),
            fmt(tr.get("seconds"), ".3g"),
            fmt(tr.get("cpu_seconds"), ".3g"),
            fmt(tr.get("iterations"), "d"),
            fmt(tr.get("seconds_per_iteration"), ".3g"),
            fmt(tr.get("apply_seconds"), ".3g"),
            mib(tr.get("peak_rss_bytes")),
            fmt(ratio, ".3f"),
            fmt(ref.get("max_pressure_difference"), ".1e"),
            fmt(ref.get("contact_mismatch"), "d"),
            f"{fmt(res.get('min_map'), '.1e')} / {fmt(ref_res.get('min_map'), '.1e')}",
            f"{fmt(res.get('tamaas'), '.1e')} / {fmt(ref_res.get('tamaas'), '.1e')}",
        ]
        print("| " + " | ".join(cells) + " |")
    if errors:
        print()
        for e in errors:
            print(f"- {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
