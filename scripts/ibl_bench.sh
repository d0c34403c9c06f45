#!/usr/bin/env bash
# IBL measurements for results/ibl.md: (1) prefilter time of a 512² cube's full chain at 64, 200
# and 1024 samples per texel for both prefilters (every thread, and one thread at 200 samples:
# Moschos' 150 s / 30 s); (2) each prefilter's error against the brute-force lobe integral at
# several sample counts on a 64² cube (error at equal time); (3) each shading path's environment
# light against the exact reference (`shaftlab ibl reference`); (4) the harness on
# experiments/ibl.toml (surface-pass time of each shading path, with light shafts). Writes
# results/ibl/.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out="$repo/results/ibl"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
environment=${SHAFTLAB_IBL_ENVIRONMENT:-courtyard}

run() {  # name, arguments...
    local name=$1
    shift
    "$build_dir/shaftlab" ibl prefilter "$environment" --out "$work/$name" "$@" | tail -1
}
for samples in 64 200 1024; do
    run "timing-importance-$samples" --face-size 512 --samples "$samples"
    run "timing-cone-$samples" --method cone --face-size 512 --samples "$samples"
done
run timing-importance-200-1thread --face-size 512 --samples 200 --threads 1
run timing-cone-200-1thread --method cone --face-size 512 --samples 200 --threads 1
# Moschos' own set-up: a 1024² level 0, so that his first prefiltered level is 512².
run timing-cone-200-1thread-1024 --method cone --face-size 1024 --samples 200 --threads 1
run timing-cone-200-1024 --method cone --face-size 1024 --samples 200
for samples in 8 32 128 512; do
    run "error-importance-$samples" --face-size 64 --samples "$samples" --brute-force 96
    run "error-cone-$samples" --method cone --face-size 64 --samples "$samples" --brute-force 96
done
# The 1024-sample chains themselves, for looking at.
mkdir -p "$out/chain-importance" "$out/chain-cone"
cp "$work"/timing-importance-1024/*.png "$out/chain-importance/"
cp "$work"/timing-cone-1024/*.png "$out/chain-cone/"
python3 - "$work" "$out/prefilter.json" <<'PY'
import json, pathlib, sys
work, target = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
runs = {d.name: json.loads((d / "prefilter.json").read_text()) for d in sorted(work.iterdir())}
tmp = target.with_suffix(".json.tmp")
tmp.write_text(json.dumps(runs, indent=1) + "\n")
tmp.replace(target)
PY
# Each shading path's environment light against the exact reference (unoccluded: the integral the
# paths approximate; occluded: what a path tracer would show), per sphere.
scenes="ibl-spheres $repo/experiments/ibl-spheres-moschos.scene.toml"
scenes+=" $repo/experiments/ibl-spheres-cone-split-sum.scene.toml"
for scene in $scenes; do
    name=$(basename "$scene" .scene.toml)
    "$build_dir/shaftlab" ibl reference --scene "$scene" --size 480x270 --samples 2048 \
        --out "$out/reference/$name"
done
"$build_dir/shaftlab" ibl reference --scene ibl-spheres --size 480x270 --samples 2048 --occlusion \
    --out "$out/reference/ibl-spheres-occluded"
"$build_dir/shaftlab" bench "$repo/experiments/ibl.toml" --out "$out/harness"
echo "ibl bench: $out"
