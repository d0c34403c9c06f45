#!/usr/bin/env bash
# Main job: set up, build, then render every canonical scene into results/ (PNG, EXR, JSON).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/scenes}
for scene in $("$build_dir/shaftlab" scenes --names); do
    "$build_dir/shaftlab" render --scene "$scene" --method none --size 960x540 --out "$out"
done
echo "run: images and timings in $out"
