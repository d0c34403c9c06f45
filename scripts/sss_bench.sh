#!/usr/bin/env bash
# Translucent-material measurements for results/sss.md: Rohat's tables 6.1 (dragon), 6.3 (bunny)
# and 6.7 (bunny at three distances) re-run in the harness (experiments/sss_splats.toml, a preset
# each) at 512x512 with the seed's
# r_max (eq. 4.3), table 6.3 again with the flux criterion, the sample-elimination time for 10k
# points (table 5.4), the materials' profiles, and the harness on experiments/sss.toml. Writes
# results/sss/ (or the directory given as the first argument).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
out=${1:-$repo/results/sss}
mkdir -p "$out"
shaftlab="$build_dir/shaftlab"
# Rohat's tables in the harness. Frames per configuration (median of `frames` after `warmup`); a
# GPU wants more than llvmpipe.
frame_settings=(--set "protocol.frames=${SHAFTLAB_SSS_FRAMES:-5}" --set "protocol.warmup=${SHAFTLAB_SSS_WARMUP:-2}")
for table in table61 table63 table63-flux table67; do
    "$shaftlab" bench "$repo/experiments/sss_splats.toml" --preset "$table" "${frame_settings[@]}" \
        --out "$out/$table"
done
"$shaftlab" sss uniformity --mesh ChineseDragon-10kv.off --points 10000 --out "$out/uniformity-dragon"
"$shaftlab" sss uniformity --mesh bunny00.off --points 10000 --out "$out/uniformity-bunny"
for material in marble jade skin1 apple; do
    "$shaftlab" sss profile --material "$material" --out "$out/profiles"
done
"$shaftlab" bench "$repo/experiments/sss.toml" --out "$out/harness"
