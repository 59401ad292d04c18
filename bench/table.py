#!/usr/bin/env python3
"""Turn the JSON lines of bench/halfspace.sh into its markdown table (standard library only).

Usage: table.py RESULTS.jsonl
Each line is one JSON object with "code" in {"tribo", "tamaas", "tamaas-evaluate"} and "n".
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


def main() -> int:
    rows: dict[int, dict[str, dict]] = {}
    with open(sys.argv[1], encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            d = json.loads(line)
            rows.setdefault(int(d["n"]), {})[d["code"]] = d

    head = [
        "N",
        "tribo s",
        "tribo iters",
        "tribo eps_avg",
        "tribo peak MiB",
        "tamaas s",
        "tamaas iters",
        "tamaas eps_avg",
        "ratio tribo/tamaas",
        "tribo operator s",
        "tribo s/iter",
        "tribo apply s",
        "min-map res. tribo",
        "min-map res. tamaas",
        "tamaas res. tribo",
        "tamaas res. tamaas",
        "tribo p_max / GPa",
        "tamaas p_max / GPa",
        "tamaas peak MiB",
        "tamaas s/iter",
    ]
    print("| " + " | ".join(head) + " |")
    print("|" + "|".join("---:" for _ in head) + "|")
    notes = []
    for n in sorted(rows):
        r = rows[n]
        t = r.get("tribo", {})
        m = r.get("tamaas", {})
        e = r.get("tamaas-evaluate", {})
        if "error" in t:
            notes.append(f"N = {n}: tribo failed: {t['error']}")
        if "error" in m:
            notes.append(f"N = {n}: tamaas failed: {m['error']}")
        ratio = None
        if isinstance(t.get("seconds"), float) and isinstance(m.get("seconds"), float) and m["seconds"] > 0:
            ratio = t["seconds"] / m["seconds"]
        mib = lambda d: d["peak_rss_bytes"] / 2**20 if d.get("peak_rss_bytes") else None  # noqa: E731
        gpa = lambda d: d["max_pressure"] / 1e9 if d.get("max_pressure") is not None else None  # noqa: E731
        cells = [
            str(n),
            fmt(t.get("seconds"), ".3f"),
            fmt(t.get("iterations"), "d"),
            fmt(t.get("eps_avg"), ".3e"),
            fmt(mib(t), ".0f"),
            fmt(m.get("seconds"), ".3f"),
            fmt(m.get("iterations"), "d"),
            fmt(m.get("eps_avg"), ".3e"),
            fmt(ratio, ".3f"),
            fmt(t.get("operator_seconds"), ".3f"),
            fmt(t["seconds"] / t["iterations"] if t.get("iterations") else None, ".4f"),
            fmt(t.get("apply_seconds"), ".4f"),
            fmt(t.get("residual"), ".1e"),
            fmt(m.get("minmap_residual"), ".1e"),
            fmt(e.get("residual"), ".1e"),
            fmt(m.get("residual"), ".1e"),
            fmt(gpa(t), ".4f"),
            fmt(gpa(m), ".4f"),
            fmt(mib(m), ".0f"),
            fmt(m["seconds"] / m["iterations"] if m.get("iterations") else None, ".4f"),
        ]
        print("| " + " | ".join(cells) + " |")
    for note in notes:
        print(f"\n- {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
