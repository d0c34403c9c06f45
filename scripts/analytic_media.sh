#!/usr/bin/env bash
# Measurements for results/analytic_media.md: the size and build time of each medium's lookup
# table and the GLSL integral's largest error against the C++ closed forms per table resolution
# (GpuMethod.DISABLED_MediumTableResolution), and the smooth falloff's approximation error per
# piece count against the exact integral (InScattering.DISABLED_FalloffPiecesPerCount). Run on a
# quiet machine: the build times are wall times of one process using every core.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
cmake --build "$build_dir" --target shaftlab_tests >/dev/null
out=$repo/results/analytic_media.md
work=$(mktemp)
trap 'rm -f "$work"' EXIT
measure() {  # test filter
    "$build_dir/tests/shaftlab_tests" --gtest_also_run_disabled_tests --gtest_filter="$1" |
        grep '^|'
}
renderer=$(SHAFTLAB_GL=${SHAFTLAB_GL:-osmesa} "$build_dir/shaftlab" gl-info | sed -n 's/^renderer *//p')
{
    cat "$repo/results/analytic_media.intro.md"
    echo
    echo "Measured by \`scripts/analytic_media.sh\` on $(date -u +%Y-%m-%d), $(nproc) cores" \
        "($(lscpu | sed -n 's/^Model name: *//p' | head -n 1)), GL: $renderer."
    echo
    echo "## Tables: size, build time, and the GPU integral against C++"
    echo
    echo "Largest |GPU − C++| of E(0, t) over the 96×54 test pattern's pixel rays of the boxes scene"
    echo "(tests/shaders/in_scattering.frag), relative to max(|C++|, the image's peak), and relative to"
    echo "max(|C++|, 1% of the peak). Build: wall time of the first build of that table in the process."
    echo
    measure 'GpuMethod.DISABLED_MediumTableResolution'
    echo
    echo "## Smooth cone edge: pieces per shell interval against the exact integral"
    echo
    echo "400 random rays and media (every model and phase function; falloff over 20–100% of the"
    echo "cone), error of \`in_scattering_pieces\` against \`in_scattering\` (closed form inside the inner"
    echo "cone, adaptive quadrature over the shell). The GPU uses kFalloffPieces = 16."
    echo
    measure 'InScattering.DISABLED_FalloffPiecesPerCount'
} >"$work"
mv "$work" "$out"
trap - EXIT
echo "analytic_media: wrote $out"
