#!/usr/bin/env bash
# Main job: set up, build, then render every canonical scene into results/scenes/ (PNG, EXR,
# JSON) with `none` and with `beamtree` scored against the reference (rel_rmse, max_abs, psnr in
# the JSON), and write its beam-tree regions into results/regions/<scene>/ (PLY, JSON, PNG).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/scenes}
regions=${2:-$repo/results/regions}
for scene in $("$build_dir/shaftlab" scenes --names); do
    "$build_dir/shaftlab" render --scene "$scene" --method none --size 960x540 --out "$out"
    "$build_dir/shaftlab" render --scene "$scene" --method beamtree --compare reference \
        --size 960x540 --out "$out"
    "$build_dir/shaftlab" regions --scene "$scene" --size 960x540 --out "$regions/$scene"
done
echo "run: images and timings in $out, beam-tree regions in $regions"
