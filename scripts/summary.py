#!/usr/bin/env python3
"""Summarises the main job's render JSONs (DIR/<scene>.<method>.json) as DIR/summary.md: per
scene and method, frames per second (median frame wall time), the volume pass's GPU time and the
relative RMSE of I_s against the reference. Written atomically.

usage: scripts/summary.py DIR METHOD...
"""
import json
import os
import sys


def main(directory, methods):
    scenes = sorted({f.split(".")[0] for f in os.listdir(directory) if f.endswith(".json")})
    lines = ["# Main job: methods against the reference", "",
             "960×540, llvmpipe unless stated; plane methods at dz = 0.1 with VSM, marching "
             "methods at N = 64 with PCF. Cells: FPS (frame wall time), volume-pass ms, relative "
             "RMSE of I_s.", "",
             "| scene | " + " | ".join(methods) + " |",
             "|---|" + "---:|" * len(methods)]
    for scene in scenes:
        cells = []
        for method in methods:
            path = os.path.join(directory, f"{scene}.{method}.json")
            if not os.path.exists(path):
                cells.append("–")
                continue
            with open(path) as f:
                r = json.load(f)
            t = r["timings_ms"]
            cells.append(f"{1000 / t['frame_cpu']:.1f} fps, {t['gpu']['volume']:.0f} ms, "
                         f"{100 * r['error']['rel_rmse']:.2f}%")
        lines.append(f"| {scene} | " + " | ".join(cells) + " |")
    path = os.path.join(directory, "summary.md")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: summary.py DIR METHOD...")
    main(sys.argv[1], sys.argv[2:])
