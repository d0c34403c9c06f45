#!/usr/bin/env bash
# Benchmarks: set up and build, then run the beam-tree benchmark on one core and write
# results/beamtree.json (Google Benchmark's output) and results/beamtree.md (the table).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
json="$repo/results/beamtree.json"
taskset -c 0 "$build_dir/beamtree_bench" --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true --benchmark_out="$json.tmp" --benchmark_out_format=json
mv "$json.tmp" "$json"
python3 "$repo/scripts/beamtree_report.py" "$json" "$repo/results/beamtree.md"
echo "bench: $repo/results/beamtree.md"
