#!/usr/bin/env python3
"""Plots of a `shaftlab bench` directory (DESIGN.md §6), from its results.csv, into DIR/plots/:

  fps_vs_resolution_<scene>.png  frames per second against pixels, one line per method (and per
                                 value of its swept parameters), log-log;
  error_vs_time_<scene>.png      relative RMSE of I_s against frame time, one panel per size, one
                                 curve per method with its swept parameter along the curve;
  scaling.png                    when three or more scenes are `multiple:N`: the beam tree (beams,
                                 region faces, build time) and each method's FPS against N.

Repetitions are combined as in table.md: median frame time, mean error. Every file is written
under a temporary name and renamed into place. Needs Debian's python3-matplotlib.

usage: experiments/plots.py DIR
"""
import csv
import os
import statistics
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def load(directory):
    with open(os.path.join(directory, "results.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    cells = OrderedDict()
    for r in rows:
        key = (r["scene"], int(r["width"]), int(r["height"]), r["method"], r["params"])
        cells.setdefault(key, []).append(r)
    out = []
    for (scene, w, h, method, params), reps in cells.items():
        errors = [number(r["rel_rmse"]) for r in reps if number(r["rel_rmse"]) is not None]
        frame_ms = statistics.median(float(r["frame_ms_median"]) for r in reps)
        settings = OrderedDict(p.split("=", 1) for p in params.split(";") if p)
        out.append({"scene": scene, "w": w, "h": h, "method": method, "settings": settings,
                    "frame_ms": frame_ms, "fps": 1000.0 / frame_ms,
                    "error": sum(errors) / len(errors) if errors else None, "row": reps[0]})
    return out


def varying(cells):
    """Per method, the parameters that take more than one value; the first is the one to put along
    a curve: numeric, with the most values."""
    values = defaultdict(set)
    for c in cells:
        for name, value in c["settings"].items():
            values[(c["method"], name)].add(value)
    result = defaultdict(list)
    for (method, name), vs in values.items():
        if len(vs) > 1:
            result[method].append(name)
    for method, names in result.items():
        names.sort(key=lambda n: (not all(number(v) is not None for v in values[(method, n)]),
                                  -len(values[(method, n)])))
    return result


def sort_value(text):
    v = number(text)
    return (0, v, "") if v is not None else (1, 0.0, text)


def save(figure, path):
    temporary = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp.png")
    figure.savefig(temporary, dpi=110, bbox_inches="tight")
    plt.close(figure)
    os.replace(temporary, path)


def fps_vs_resolution(cells, scene, vary, path):
    lines = OrderedDict()
    for c in cells:
        if c["scene"] != scene:
            continue
        label = c["method"] + "".join(
            f" {n}={c['settings'][n]}" for n in vary[c["method"]] if n in c["settings"])
        lines.setdefault(label, []).append((c["w"] * c["h"], c["fps"]))
    if not any(len(points) > 1 for points in lines.values()):
        return False
    figure, axes = plt.subplots(figsize=(7, 4.5))
    for label, points in lines.items():
        points.sort()
        axes.plot([p[0] / 1e6 for p in points], [p[1] for p in points], "o-", label=label)
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("megapixels")
    axes.set_ylabel("frames per second")
    axes.set_title(f"{scene}: FPS against resolution")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7, ncol=2)
    save(figure, path)
    return True


def error_vs_time(cells, scene, vary, path):
    mine = [c for c in cells if c["scene"] == scene and c["error"] is not None]
    if not mine:
        return False
    sizes = sorted({(c["w"], c["h"]) for c in mine}, key=lambda s: s[0] * s[1])
    figure, panels = plt.subplots(1, len(sizes), figsize=(5.5 * len(sizes), 4.5), squeeze=False)
    for panel, (w, h) in zip(panels[0], sizes):
        curves = OrderedDict()
        for c in mine:
            if (c["w"], c["h"]) != (w, h):
                continue
            along = vary[c["method"]][:1]  # the first swept parameter runs along the curve
            rest = [n for n in vary[c["method"]][1:] if n in c["settings"]]
            label = c["method"] + "".join(f" {n}={c['settings'][n]}" for n in rest)
            value = c["settings"].get(along[0]) if along else None
            curves.setdefault(label, []).append((value, along[0] if along else None, c))
        for label, points in curves.items():
            points.sort(key=lambda p: sort_value(p[0]) if p[0] is not None else (0, 0.0, ""))
            xs = [p[2]["frame_ms"] for p in points]
            ys = [max(p[2]["error"], 1e-6) for p in points]
            line, = panel.plot(xs, ys, "o-", label=label, markersize=4)
            for value, name, c in points:
                if value is not None:
                    panel.annotate(f"{name}={value}", (c["frame_ms"], max(c["error"], 1e-6)),
                                   fontsize=6, color=line.get_color(),
                                   xytext=(3, 3), textcoords="offset points")
        panel.set_xscale("log")
        panel.set_yscale("log")
        panel.set_xlabel("frame time (ms)")
        panel.set_ylabel("relative RMSE of I_s")
        panel.set_title(f"{scene} {w}x{h}")
        panel.grid(True, which="both", alpha=0.3)
        panel.legend(fontsize=7)
    figure.suptitle(f"{scene}: error against frame time")
    save(figure, path)
    return True


def scaling(cells, path):
    """Beam tree and frame rate against N for the generated scenes multiple:N."""
    mine = [c for c in cells if c["scene"].startswith("multiple:")]
    counts = sorted({int(c["scene"].split(":")[1]) for c in mine})
    if len(counts) < 3:
        return False
    figure, (tree, fps) = plt.subplots(1, 2, figsize=(11, 4.5))
    first = {}
    for c in mine:
        first.setdefault(int(c["scene"].split(":")[1]), c["row"])
    for key, label in (("beams", "beams"), ("region_faces", "region faces"),
                       ("cpu_ms_beamtree_regions", "tree + regions build (ms)")):
        tree.plot(counts, [float(first[n][key]) for n in counts], "o-", label=label)
    tree.set_xscale("log")
    tree.set_yscale("log")
    tree.set_xlabel("objects N")
    tree.set_title("beam tree against N")
    tree.grid(True, which="both", alpha=0.3)
    tree.legend(fontsize=8)
    methods = OrderedDict()
    for c in mine:
        methods.setdefault(c["method"], []).append((int(c["scene"].split(":")[1]), c["fps"]))
    for method, points in methods.items():
        points.sort()
        fps.plot([p[0] for p in points], [p[1] for p in points], "o-", label=method)
    fps.set_xscale("log")
    fps.set_yscale("log")
    fps.set_xlabel("objects N")
    fps.set_ylabel("frames per second")
    fps.set_title("frame rate against N")
    fps.grid(True, which="both", alpha=0.3)
    fps.legend(fontsize=8)
    save(figure, path)
    return True


def main(directory):
    cells = load(directory)
    plots = os.path.join(directory, "plots")
    os.makedirs(plots, exist_ok=True)
    vary = varying(cells)
    written = []
    for scene in OrderedDict.fromkeys(c["scene"] for c in cells):
        safe = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in scene)
        for name, plot in (("fps_vs_resolution", fps_vs_resolution),
                           ("error_vs_time", error_vs_time)):
            path = os.path.join(plots, f"{name}_{safe}.png")
            if plot(cells, scene, vary, path):
                written.append(path)
    if scaling(cells, os.path.join(plots, "scaling.png")):
        written.append("scaling.png")
    print(f"plots: {len(written)} in {plots}", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
