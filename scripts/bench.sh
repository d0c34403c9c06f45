#!/usr/bin/env bash
# Benchmarks: set up and build, then run the beam-tree benchmark on one core and the `regions`
# command on the big scenes, and write results/beamtree.json (Google Benchmark's output) and
# results/beamtree.md (the tables).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
json="$repo/results/beamtree.json"
taskset -c 0 "$build_dir/beamtree_bench" --benchmark_repetitions=5 \
    --benchmark_report_aggregates_only=true --benchmark_out="$json.tmp" --benchmark_out_format=json
mv "$json.tmp" "$json"
# The whole `regions` command on the big scenes (all cores), for its own targets.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for scene in ibl-spheres multiple:4000; do
    start=$EPOCHREALTIME
    summary=$("$build_dir/shaftlab" regions --scene "$scene" --out "$scratch/out" | tr "\n" " ")
    end=$EPOCHREALTIME
    echo "$scene|$(awk "BEGIN { print $end - $start }")|$summary" >>"$scratch/regions.txt"
    rm -rf "$scratch/out"
done
python3 "$repo/scripts/beamtree_report.py" "$json" "$repo/results/beamtree.md" "$scratch/regions.txt"
echo "bench: $repo/results/beamtree.md"
