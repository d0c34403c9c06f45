#!/usr/bin/env bash
# Main job: set up, build, then render every canonical scene into results/scenes/ (PNG, EXR,
# JSON) with `none` and with every volumetric method scored against the reference (rel_rmse,
# max_abs, psnr in the JSON), write a summary table results/scenes/summary.md (FPS and error per
# scene and method), and write each scene's beam-tree regions into results/regions/<scene>/.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/scenes}
regions=${2:-$repo/results/regions}
methods="beamtree planes hybrid1 hybrid2 march hybrid3"
for scene in $("$build_dir/shaftlab" scenes --names); do
    "$build_dir/shaftlab" render --scene "$scene" --method none --size 960x540 --out "$out"
    for method in $methods; do
        case $method in
            planes | hybrid1 | hybrid2) settings=(--set dz=0.1 --set shadow=vsm) ;;
            march | hybrid3) settings=(--set samples=64) ;;
            *) settings=() ;;
        esac
        "$build_dir/shaftlab" render --scene "$scene" --method "$method" --compare reference \
            --size 960x540 "${settings[@]}" --out "$out"
    done
    "$build_dir/shaftlab" regions --scene "$scene" --size 960x540 --out "$regions/$scene"
done
python3 "$repo/scripts/summary.py" "$out" $methods
echo "run: images, timings and summary.md in $out, beam-tree regions in $regions"
