#!/usr/bin/env python3
"""The tables of results/ibl.md from scripts/ibl_bench.sh's outputs (results/ibl/)."""
import csv
import json
import pathlib
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "results/ibl")
runs = json.loads((root / "prefilter.json").read_text())

print("### Prefilter time, full chain (seconds)\n")
print("| prefilter | level-0 face | samples/texel | threads | levels | seconds |")
print("|---|---|---|---|---|---|")
for name, run in runs.items():
    if not name.startswith("timing"):
        continue
    threads = run["threads"] or "all (2)"
    print(f"| {run['method']} | {run['face_size']}² | {run['samples']} | {threads} | "
          f"{len(run['levels'])} | {run['prefilter_seconds']:.2f} |")

print("\n### Error against the brute-force lobe integral (64² level 0, 96²-per-face grid)\n")
print("| prefilter | samples/texel | seconds | scored levels (α: rel. RMSE) | mean |")
print("|---|---|---|---|---|")
for name, run in runs.items():
    if not name.startswith("error"):
        continue
    scored = [l for l in run["levels"] if "rel_rmse_vs_brute_force" in l]
    cells = ", ".join(f"{l['roughness']:.2f}: {l['rel_rmse_vs_brute_force']:.3f}" for l in scored)
    mean = sum(l["rel_rmse_vs_brute_force"] for l in scored) / max(len(scored), 1)
    print(f"| {run['method']} | {run['samples']} | {run['prefilter_seconds']:.3f} | {cells} | "
          f"{mean:.3f} |")

print("\n### Environment light against the exact reference (relative RMSE)\n")
references = sorted((root / "reference").glob("*/reference.json"))
summaries = {p.parent.name: json.loads(p.read_text()) for p in references}
objects = list(next(iter(summaries.values()))["objects"].keys())
print("| run | shading | prefilter | occlusion | all surfaces | " +
      " | ".join(objects) + " |")
print("|---" * (5 + len(objects)) + "|")
for name, s in summaries.items():
    cells = " | ".join(f"{s['objects'][o]['rel_rmse']:.3f}" for o in objects)
    print(f"| {name} | {s['shading']} | {s['prefilter'].split()[0]} | {s['occlusion']} | "
          f"{s['surface_rel_rmse']:.3f} | {cells} |")
first = next(iter(summaries.values()))
print("\nRoughness α per object: " + ", ".join(
    f"{o} {first['objects'][o]['roughness']:.2f}" for o in objects) + ".")

print("\n### Frame time per shading path (harness, experiments/ibl.toml, GPU ms, median)\n")
rows = list(csv.DictReader((root / "harness" / "results.csv").open()))
print("| scene | method | size | surface pass | volume pass | frame | fps |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    scene = pathlib.Path(r["scene"]).name.replace(".scene.toml", "")
    print(f"| {scene} | {r['method']} | {r['width']}×{r['height']} | "
          f"{float(r['gpu_ms_surface']):.1f} | {float(r['gpu_ms_volume'] or 0):.1f} | "
          f"{float(r['frame_ms_median']):.1f} | {float(r['fps']):.2f} |")
