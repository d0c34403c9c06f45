#!/usr/bin/env bash
# results/moving.md: the per-frame CPU work of moving scenes on one core (build/moving_bench),
# the serial and pipelined frame loops (`shaftlab animate --mode both`, per-frame CSVs in
# results/moving/), and the viewer's latency from a change to the frame that shows it. Run it on
# a quiet machine: the frame loops share the CPU with llvmpipe.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out="$repo/results/moving"
frames=${SHAFTLAB_MOVING_FRAMES:-30}
size=${SHAFTLAB_MOVING_SIZE:-320x180}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

taskset -c 0 "$build_dir/moving_bench" >"$scratch/cpu.md"
for scene in toplight-orbit parallel-walk multiple-moving; do
    for method in beamtree hybrid2 hybrid3; do
        for route in walk mesh; do
            "$build_dir/shaftlab" animate --scene "$scene" --method "$method" --mode both \
                --set route=$route --frames "$frames" --size "$size" \
                --out "$scratch/loops-$route" >/dev/null
            for mode in serial pipelined; do
                cp "$scratch/loops-$route/$scene.$method.$mode.frames.csv" \
                    "$scratch/$scene.$method.$route.$mode.frames.csv"
            done
        done
    done
done
# A picture to look at: multiple-moving at 2 s, the swapping pairs inside each other.
"$build_dir/shaftlab" animate --scene multiple-moving --method hybrid3 --set route=walk --frames 61 --size 480x270 \
    --mode pipelined --warmup 0 --out "$scratch/picture" >/dev/null
latency=$(xvfb-run -a "$build_dir/shaftlab" view --scene parallel-walk --method hybrid2 \
    --frames 8 --size 640x360 --hidden | grep "scene changes")
renderer=$("$build_dir/shaftlab" gl-info 2>/dev/null | grep -i renderer | head -1 || true)
rm -rf "$out.tmp" && mkdir -p "$out.tmp"
cp "$scratch"/*.frames.csv "$out.tmp/"
cp "$scratch/picture/multiple-moving.hybrid3.pipelined.last.png" "$out.tmp/multiple-moving.hybrid3.t2s.png"
python3 - "$scratch/cpu.md" "$out.tmp" "$frames" "$size" "$latency" "$renderer" \
    >"$repo/results/moving.md.tmp" <<'PY'
import csv, glob, os, statistics, sys
cpu, folder, frames, size, latency, renderer = sys.argv[1:]
print("# Moving scenes: the per-frame CPU work, and the CPU beside the GPU\n")
print("Regenerate with `scripts/moving_bench.sh` on a quiet machine. The CPU tables come from "
      "`build/moving_bench` on one core (`taskset -c 0`, TBB limited to one thread); the frame "
      f"loops from `shaftlab animate --mode both`, {frames} frames at {size} on this machine's "
      f"GL ({renderer.strip() or 'llvmpipe'}), per-frame CSVs in `results/moving/`.\n")
print("The budget, at most 2 ms of CPU per frame for a light move (docs/design.md §14), is "
      "measured twice. The first tables time the update itself, stage by stage, as serial work, "
      "for both routes from the tree to the GPU: *mesh* (regions and boundary meshes each frame) "
      "and *walk* (the tree alone; the GPU walks it per eye ray). The frame-loop table's "
      "*critical CPU* column is what the GL thread still waits for when the update runs on the "
      "worker beside the GPU, and its *GPU ms* what the walk costs the GPU in exchange.\n")
print(open(cpu).read())
print("\n## Serial and pipelined frame loops\n")
print("Medians over frames 1.. (frame 0 pays the first build). *update*: the method's CPU update "
      "(`cpu_update`: volumes, tree, regions, meshes); *critical CPU*: what the GL thread waited "
      "for on the CPU (serial: update + upload; pipelined: upload + any wait for the worker); "
      "*overlap*: the part of the next frame's update that ran during this frame's draw.\n")
print("| scene | method | route | mode | frame ms | critical CPU ms | update ms | GPU ms | "
      "overlap ms | pipelined / serial frame |")
print("|---|---|---|---|---:|---:|---:|---:|---:|---:|")
def med(rows, key):
    return statistics.median(float(r[key]) for r in rows[1:]) if len(rows) > 1 else 0.0
for scene in ["toplight-orbit", "parallel-walk", "multiple-moving"]:
    for method in ["beamtree", "hybrid2", "hybrid3"]:
        for route in ["walk", "mesh"]:
            medians = {}
            for mode in ["serial", "pipelined"]:
                path = os.path.join(folder, f"{scene}.{method}.{route}.{mode}.frames.csv")
                rows = list(csv.DictReader(open(path)))
                medians[mode] = {k: med(rows, k) for k in
                                 ["frame_ms", "critical_cpu_ms", "update_ms", "gpu_ms",
                                  "overlap_ms"]}
            ratio = medians["pipelined"]["frame_ms"] / medians["serial"]["frame_ms"]
            for mode in ["serial", "pipelined"]:
                m = medians[mode]
                last = f"{ratio:.2f}" if mode == "pipelined" else ""
                print(f"| {scene} | {method} | {route} | {mode} | {m['frame_ms']:.1f} | "
                      f"{m['critical_cpu_ms']:.2f} | {m['update_ms']:.1f} | {m['gpu_ms']:.1f} | "
                      f"{m['overlap_ms']:.1f} | {last} |")
print("\n![multiple-moving at 2 s, hybrid3](moving/multiple-moving.hybrid3.t2s.png)\n")
print("*multiple-moving* at t = 2 s (frame 60, `hybrid3` on the walk route, pipelined): the four swapping pairs "
      "are half way, inside each other's outer volumes.\n")
print("\n## The viewer: from a change to the first frame that shows it\n")
print("`shaftlab view --scene parallel-walk --method hybrid2 --frames 8 --size 640x360` "
      "(scripted, serial: the change, the method's update and the overlay's regions, then the "
      "frame):\n")
print("    " + latency.replace("shaftlab view: ", ""))
PY
rm -rf "$out" && mv "$out.tmp" "$out"
mv "$repo/results/moving.md.tmp" "$repo/results/moving.md"
echo "moving: $repo/results/moving.md"
