#!/usr/bin/env bash
# The random-box class search as a benchmark: runs experiments/random_boxes.toml (beamtree, hybrid3 and
# lightvolume on the random box scenes boxes:SEED, where every object is its own bounding volume
# and the region methods must equal the reference) into results/random_boxes/, and writes the
# distribution of their errors against the reference (median, p95, worst; per method, medium
# model and eye) into results/random_boxes/distribution.md.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out="$repo/results/random_boxes"
"$build_dir/shaftlab" bench "$repo/experiments/random_boxes.toml" --out "$out" "$@"
python3 "$repo/scripts/random_boxes.py" "$out/results.csv" "$out/distribution.md"
echo "random boxes: $out/distribution.md"
