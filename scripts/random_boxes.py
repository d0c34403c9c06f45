#!/usr/bin/env python3
"""The error distribution of a random_boxes run (experiments/random_boxes.toml): for each method,
the median, 95th percentile and worst relative RMSE against the reference over the scenes, over
all of them and per medium model and eye (boxes:SEED: the eye inside the cone on odd seeds, the
physical model where (SEED / 2) is odd: scenes/generators.cpp), with the worst scenes named.

Usage: random_boxes.py RESULTS_CSV OUT_MD
"""
import csv
import math
import re
import sys


def percentile(values, q):
    """The q-quantile by linear interpolation between the order statistics."""
    ordered = sorted(values)
    position = q * (len(ordered) - 1)
    lo = math.floor(position)
    hi = min(lo + 1, len(ordered) - 1)
    return ordered[lo] + (ordered[hi] - ordered[lo]) * (position - lo)


def summary(values):
    return percentile(values, 0.5), percentile(values, 0.95), max(values)


def main(csv_path, out_path):
    rows = {}
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            match = re.fullmatch(r"boxes[-:_](\d+)(\.scene)?", row["scene"])
            if not match or not row["rel_rmse"]:
                continue
            seed = int(match.group(1))
            rows.setdefault(row["method"], []).append((seed, float(row["rel_rmse"])))
    if not rows:
        sys.exit(f"{csv_path}: no boxes:SEED rows with a rel_rmse")
    groups = [
        ("all scenes", lambda s: True),
        ("simplified model", lambda s: (s // 2) % 2 == 0),
        ("physical model", lambda s: (s // 2) % 2 == 1),
        ("eye outside the cone", lambda s: s % 2 == 0),
        ("eye inside the cone", lambda s: s % 2 == 1),
    ]
    lines = [
        "# Random box scenes: the region methods against the reference",
        "",
        "Relative RMSE of I_s against the exact reference on the random box scenes boxes:SEED",
        "(`experiments/random_boxes.toml`, `scripts/random_boxes.sh`): rotated boxes that are their",
        "own bounding volumes, so nothing is uncertain and `beamtree` and `hybrid3` must equal the",
        "reference; `lightvolume` integrates the same closed form over the shadow map's volume.",
        "Environment: `env.json` beside this file.",
        "",
        "| method | scenes | group | median | p95 | worst |",
        "|---|---:|---|---:|---:|---:|",
    ]
    for method, values in rows.items():
        for label, keep in groups:
            errors = [e for s, e in values if keep(s)]
            if not errors:
                continue
            median, p95, worst = summary(errors)
            lines.append(
                f"| {method} | {len(errors)} | {label} | {median:.2e} | {p95:.2e} | {worst:.2e} |"
            )
    lines += ["", "Worst scenes per method:", ""]
    for method, values in rows.items():
        worst = sorted(values, key=lambda v: -v[1])[:3]
        named = ", ".join(f"boxes:{s} ({e:.2e})" for s, e in worst)
        lines.append(f"- {method}: {named}")
    with open(out_path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
