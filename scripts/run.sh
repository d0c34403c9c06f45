#!/usr/bin/env bash
# Main job: set up, build, then measure the default comparison (experiments/default.toml: every
# volumetric method on the canonical scenes at 640x360 against the exact reference) on this
# machine, into out/default/ (git-ignored): results.csv, table.md, env.json, plots/, images/.
# Prints its table, then each cell's FPS beside the committed run (results/default, measured on
# the machine its env.json names) as ratios (out/default/comparison.md), and writes each scene's
# beam-tree regions into out/regions/<scene>/. The working tree stays as it was.
#
#   ./scripts/run.sh              measure afresh (an earlier out/default is replaced)
#   ./scripts/run.sh --resume     continue an interrupted run in out/default
#   ./scripts/run.sh --refresh    measure into results/default and results/regions instead:
#                                 the committed results, refreshed only on purpose
#   --experiment FILE, --preset P another experiment or a preset of it (the tests run smoke)
# SHAFTLAB_OUT moves out/ elsewhere.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
experiment=$repo/experiments/default.toml
refresh=0
resume=0
presets=()
while (($#)); do
    case $1 in
        --refresh) refresh=1 ;;
        --resume) resume=1 ;;
        --experiment) experiment=$2; shift ;;
        --preset) presets+=(--preset "$2"); shift ;;
        *) echo "run: unknown option '$1' (see the top of scripts/run.sh)" >&2; exit 2 ;;
    esac
    shift
done
source "$repo/scripts/setup.sh"

name=$(basename "$experiment" .toml)
committed=$repo/results/$name
if ((refresh)); then
    out=$committed
    regions=$repo/results/regions
else
    root=${SHAFTLAB_OUT:-$repo/out}
    out=$root/$name
    regions=$root/regions
fi
if ((!resume)); then
    rm -rf "$out"
fi
arguments=(bench "$experiment" --out "$out" "${presets[@]}")
if ((!refresh)) && [ -d "$committed/cells" ]; then
    arguments+=(--baseline "$committed")
fi
"$build_dir/shaftlab" "${arguments[@]}"
if [ "$name" = default ]; then
    for scene in $("$build_dir/shaftlab" scenes --names); do
        "$build_dir/shaftlab" regions --scene "$scene" --all-lights --size 960x540 --out "$regions/$scene"
    done
    echo "run: table, results.csv, plots and images in $out; beam-tree regions in $regions"
else
    echo "run: table, results.csv, plots and images in $out"
fi
