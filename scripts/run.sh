#!/usr/bin/env bash
# Main job: set up, build, then run the default comparison (experiments/default.toml: every
# volumetric method on the canonical scenes at 640x360 against the exact reference) with the
# harness into results/default/ — results.csv, table.md (printed), env.json, plots/, images/ — and
# write each scene's beam-tree regions into results/regions/<scene>/. A run that was interrupted
# resumes where it stopped; pass a fresh directory to measure again.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/default}
regions=${2:-$repo/results/regions}
"$build_dir/shaftlab" bench "$repo/experiments/default.toml" --out "$out"
for scene in $("$build_dir/shaftlab" scenes --names); do
    "$build_dir/shaftlab" regions --scene "$scene" --size 960x540 --out "$regions/$scene"
done
echo "run: table, results.csv, plots and images in $out; beam-tree regions in $regions"
