#!/usr/bin/env python3
"""Plots of a `shaftlab bench` directory (docs/design.md §6), from its results.csv, into DIR/plots/:

  fps_vs_resolution_<scene>.png  frames per second against pixels, one line per method (and per
                                 value of its swept parameters), log-log;
  error_vs_time_<scene>.png      relative RMSE of I_s against frame time, one panel per size, one
                                 curve per method with its swept parameter along the curve;
  scaling.png                    when three or more scenes are `multiple:N`: the beam tree (beams,
                                 region faces, build time) and each method's FPS against N;
  per_frame.png                  animation cells (frames.csv): frame time and error against the
                                 frame index, one column of panels per scene, one line per cell
                                 (the frame time the median over repetitions, the error of
                                 repetition 0 on its scored frames).

Repetitions are combined as in table.md: median frame time, mean error. Every file is written
under a temporary name and renamed into place. Needs Debian's python3-matplotlib.

usage: experiments/plots.py DIR
"""
import csv
import math
import os
import statistics
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402


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


def plain_log_ticks(axes):
    """Log axes labelled in plain numbers (30, 50, 0.002) at 1-2-3-5 steps, not 4×10¹, 9×10¹."""
    for axis in (axes.xaxis, axes.yaxis):
        if axis.get_scale() != "log":
            continue
        axis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 3.0, 5.0)))
        axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_locator(ticker.LogLocator(base=10, subs=(4.0, 6.0, 7.0, 8.0, 9.0)))
        axis.set_minor_formatter(ticker.NullFormatter())


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
    plain_log_ticks(axes)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7, ncol=2)
    save(figure, path)
    return True


def error_vs_time(cells, scene, vary, path):
    mine = [c for c in cells if c["scene"] == scene and c["error"] is not None]
    if not mine:
        return False
    sizes = sorted({(c["w"], c["h"]) for c in mine}, key=lambda s: s[0] * s[1])
    figure, panels = plt.subplots(1, len(sizes), figsize=(6.5 * len(sizes), 4.8), squeeze=False)
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
        placed = []  # (log x, log y, text) of the labels drawn: one of each where curves meet
        for label, points in curves.items():
            points.sort(key=lambda p: sort_value(p[0]) if p[0] is not None else (0, 0.0, ""))
            xs = [p[2]["frame_ms"] for p in points]
            ys = [max(p[2]["error"], 1e-6) for p in points]
            name = points[0][1]
            line, = panel.plot(xs, ys, "o-", markersize=3.5, linewidth=1.2,
                               label=f"{label} ({name} {points[0][0]}…{points[-1][0]})"
                               if name and len(points) > 1 else label)
            # Only a curve's two ends are labelled (its range is in the legend): labels on every
            # probe of a search pile up where the curves meet.
            ends = [points[0], points[-1]] if len(points) > 1 else points
            for i, (value, parameter, c) in enumerate(ends):
                if value is None:
                    continue
                text = f"{parameter}={value}"
                lx, ly = math.log10(c["frame_ms"]), math.log10(max(c["error"], 1e-6))
                if any(t == text and abs(px - lx) < 0.06 and abs(py - ly) < 0.06
                       for px, py, t in placed):
                    continue
                placed.append((lx, ly, text))
                panel.annotate(text, (c["frame_ms"], max(c["error"], 1e-6)), fontsize=6.5,
                               color=line.get_color(), xytext=(4, 4 if i == 0 else -9),
                               textcoords="offset points")
        panel.set_xscale("log")
        panel.set_yscale("log")
        plain_log_ticks(panel)
        panel.set_xlabel("frame time (ms)")
        panel.set_ylabel("relative RMSE of I_s")
        panel.set_title(f"{w}x{h}")
        panel.grid(True, which="major", alpha=0.35)
        panel.grid(True, which="minor", alpha=0.12)
    handles, labels = panels[0][0].get_legend_handles_labels()
    figure.legend(handles, labels, fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    figure.suptitle(f"{scene}: error against frame time")
    figure.tight_layout()
    save(figure, path)
    return True


def per_frame(directory, path):
    """Frame time and error against the frame index of every animation cell, a column per scene."""
    frames_path = os.path.join(directory, "frames.csv")
    if not os.path.exists(frames_path):
        return False
    with open(frames_path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return False
    scenes = list(OrderedDict.fromkeys(r["scene"] for r in rows))
    # (scene, label) -> frame -> [frame_ms over repetitions], and the error of repetition 0.
    times = OrderedDict()
    errors = OrderedDict()
    for r in rows:
        label = r["method"] + (f" {r['params']}" if r["params"] else "")
        key = (r["scene"], label)
        times.setdefault(key, defaultdict(list))[int(r["frame"])].append(float(r["frame_ms"]))
        if r["rep"] == "0" and number(r["rel_rmse"]) is not None:
            errors.setdefault(key, []).append((int(r["frame"]), float(r["rel_rmse"])))
    figure, panels = plt.subplots(2, len(scenes), figsize=(5.2 * len(scenes), 7.0),
                                  squeeze=False, sharex="col")
    colors = {}
    for column, scene in enumerate(scenes):
        top, bottom = panels[0][column], panels[1][column]
        for (s, label), by_frame in times.items():
            if s != scene:
                continue
            color = colors.setdefault(label, f"C{len(colors) % 10}")
            frames = sorted(by_frame)
            top.plot(frames, [statistics.median(by_frame[k]) for k in frames], "-",
                     color=color, linewidth=1.0, label=label)
            if (s, label) in errors:
                points = sorted(errors[(s, label)])
                bottom.plot([p[0] for p in points], [max(p[1], 1e-6) for p in points], ".-",
                            color=color, linewidth=1.0, markersize=3, label=label)
        top.set_title(scene)
        top.set_ylabel("frame time (ms)")
        top.set_yscale("log")
        bottom.set_yscale("log")
        plain_log_ticks(top)
        plain_log_ticks(bottom)
        bottom.set_ylabel("relative RMSE of I_s")
        bottom.set_xlabel("frame")
        for axes in (top, bottom):
            axes.grid(True, which="major", alpha=0.35)
            axes.grid(True, which="minor", alpha=0.12)
    handles, labels = [], []
    for axes in panels[0]:
        for h, l in zip(*axes.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    figure.legend(handles, labels, fontsize=7.5, loc="lower center", ncol=min(len(labels), 4),
                  bbox_to_anchor=(0.5, -0.02))
    figure.suptitle("along the animation: frame time (median over repetitions) and error per frame")
    figure.tight_layout(rect=(0, 0.06, 1, 1))
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
    plain_log_ticks(tree)
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
    plain_log_ticks(fps)
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
    if per_frame(directory, os.path.join(plots, "per_frame.png")):
        written.append("per_frame.png")
    print(f"plots: {len(written)} in {plots}", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
