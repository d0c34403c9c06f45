#!/usr/bin/env bash
# Translucent-material measurements for results/sss.md: Rohat's tables 6.1 (dragon), 6.3 (bunny)
# and 6.7 (bunny at three distances) re-run with `shaftlab sss bench` at 512x512 with the seed's
# r_max (eq. 4.3), table 6.3 again with the flux criterion, the sample-elimination time for 10k
# points (table 5.4), the materials' profiles, and the harness on experiments/sss.toml. Writes
# results/sss/ (or the directory given as the first argument).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/sss}
mkdir -p "$out"
shaftlab="$build_dir/shaftlab"
# Frames per configuration (median of `frames` after `warmup`); a GPU wants more than llvmpipe.
frames=(--frames "${SHAFTLAB_SSS_FRAMES:-5}" --warmup "${SHAFTLAB_SSS_WARMUP:-2}")

"$shaftlab" sss bench "${frames[@]}" --scene "$repo/experiments/sss-dragon-marble.scene.toml" \
    --grids 55x38,65x45,75x52,85x60,95x67 --out "$out/table61"
"$shaftlab" sss bench "${frames[@]}" --scene sss-bunny --grids 30x29,35x34,40x39,45x44,50x49,55x54 \
    --out "$out/table63"
"$shaftlab" sss bench "${frames[@]}" --scene sss-bunny --grids 30x29,35x34,40x39,45x44,50x49,55x54 \
    --radius flux --out "$out/table63-flux"
"$shaftlab" sss bench "${frames[@]}" --scene sss-bunny --models multipole --grids 50x49,60x59,70x69,80x79 \
    --distances 0.55,1,2.2 --out "$out/table67"
"$shaftlab" sss uniformity --mesh ChineseDragon-10kv.off --points 10000 --out "$out/uniformity-dragon"
"$shaftlab" sss uniformity --mesh bunny00.off --points 10000 --out "$out/uniformity-bunny"
for material in marble jade skin1 apple; do
    "$shaftlab" sss profile --material "$material" --out "$out/profiles"
done
"$shaftlab" bench "$repo/experiments/sss.toml" --out "$out/harness"
