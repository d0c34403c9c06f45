#!/usr/bin/env bash
# scripts/gpu_bench.sh: the equal-error comparison (or any experiments) on a machine with a GPU
# that has no Debian packages and no network, in one prepared call.
#
#   scripts/gpu_bench.sh package
#       Here (Debian 12, set-up done by scripts/setup.sh): builds shaftlab for EGL only
#       (-DSHAFTLAB_WITH_OSMESA=OFF, Release) in build-gpu/ (or $SHAFTLAB_GPU_BUILD_DIR) and packs
#       gpu-package.tar.xz (git-ignored) with the binary, the shared libraries it loads but the C
#       runtime and the GPU driver's own (glvnd's libEGL/libGLdispatch are carried: they dispatch
#       to the vendor's EGL), the extracted meshes, the studio lights the scenes name, the scene
#       and experiment files, and this script.
#
#   scripts/gpu_bench.sh run [--limit SECONDS] [EXPERIMENT ...]
#       There: unpacks gpu-package.tar.xz into a temporary folder, records the GL renderer
#       (`shaftlab gl-info` through EGL), and runs each experiment (default: walk, the GPU walk
#       of beam trees of 5·10^3 to 7·10^5 nodes, the game level among them, by node layout and
#       stack size; then equal_error, every method against the cheapest without regions,
#       epipolar and the level included; then animated: every
#       method along the canonical animations, the region methods on both routes from the beam
#       tree to the GPU, walk and mesh, docs/design.md §14) with
#       `shaftlab bench`, each under `timeout` so the whole call ends within --limit seconds
#       (default 480): an experiment cut short keeps the cells it finished (bench resumes).
#       Results go to $OUT/gpu-<renderer>/<experiment>/ ($OUT as the device tool sets it, else
#       out/), beside gl-info.txt; copy them to results/gpu-<renderer>/ here.
#
#   SHAFTLAB_GL=egl scripts/gpu_bench.sh run --limit 120 smoke
#       The packaging test on this machine: the same package through Mesa's EGL device.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
package=${SHAFTLAB_GPU_PACKAGE:-$repo/gpu-package.tar.xz}

usage() {
    sed -n '2,27p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

pack() {
    local build=${SHAFTLAB_GPU_BUILD_DIR:-$repo/build-gpu}
    source "$repo/scripts/packages.sh"
    install_missing cmake ninja-build xz-utils blender-data
    cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHAFTLAB_WITH_OSMESA=OFF \
        >/dev/null
    cmake --build "$build" --target shaftlab --parallel "$(nproc)"
    local stage
    stage=$(mktemp -d)
    trap 'rm -rf "$stage"' RETURN
    mkdir -p "$stage/shaftlab/bin" "$stage/shaftlab/lib" "$stage/shaftlab/environments"
    cp "$build/shaftlab" "$stage/shaftlab/bin/"
    # Every library the binary loads, but the C runtime and the loader (the GPU machine's own
    # match its kernel) and libGL/libOpenGL (not used: EGL only).
    ldd "$build/shaftlab" | awk '/=> \//{print $3}' | while read -r lib; do
        case $(basename "$lib") in
        libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | ld-linux*) ;;
        libGL.so.* | libOpenGL.so.* | libGLX*.so.*) ;;
        *) cp -L "$lib" "$stage/shaftlab/lib/" ;;
        esac
    done
    cp -r "$build/data" "$stage/shaftlab/data"
    cp -r "$repo/scenes" "$repo/experiments" "$stage/shaftlab/"
    cp "${BASH_SOURCE[0]}" "$stage/shaftlab/gpu_bench.sh"
    # The studio lights the scene files name (Blender's, from blender-data).
    local lights
    lights=$(find /usr/share/blender -path '*studiolights/world' -type d | head -n 1)
    grep -h '^file *= *"' "$repo"/scenes/*.toml "$repo"/experiments/*.toml 2>/dev/null |
        grep -o '"[^"/]*"' | tr -d '"' | sort -u | while read -r name; do
        if [ -f "$lights/$name.exr" ]; then
            cp "$lights/$name.exr" "$stage/shaftlab/environments/"
        fi
    done
    tar -C "$stage" -cJf "$package.tmp" shaftlab
    mv "$package.tmp" "$package"
    echo "gpu_bench: $package ($(du -h "$package" | cut -f1))"
}

run() {
    local limit=480 experiments=()
    while (($#)); do
        case $1 in
        --limit) limit=$2; shift 2 ;;
        -*) usage ;;
        *) experiments+=("$1"); shift ;;
        esac
    done
    ((${#experiments[@]})) || experiments=(walk equal_error animated)
    [ -f "$package" ] || { echo "gpu_bench: no $package (run 'scripts/gpu_bench.sh package' first)" >&2; exit 2; }
    local start=$SECONDS
    root=$(mktemp -d)  # global: the EXIT trap runs after this function has returned
    trap 'rm -rf "$root"' EXIT
    tar -C "$root" -xJf "$package"
    local p=$root/shaftlab
    export LD_LIBRARY_PATH=$p/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
    export SHAFTLAB_GL=${SHAFTLAB_GL:-egl} SHAFTLAB_SCENES=$p/scenes SHAFTLAB_DATA=$p/data
    export SHAFTLAB_ENVIRONMENTS=$p/environments
    local info
    info=$("$p/bin/shaftlab" gl-info)
    local renderer
    renderer=$(sed -n 's/^renderer *//p' <<<"$info" | head -n 1)
    local name
    name=$(tr 'A-Z' 'a-z' <<<"$renderer" | grep -o '[a-z]*[0-9][0-9a-z]*\|llvmpipe' | head -n 1)
    name=${name:-gpu}
    local out=${OUT:-$repo/out}/gpu-$name
    mkdir -p "$out"
    printf '%s\n' "$info" >"$out/gl-info.txt"
    echo "gpu_bench: $renderer -> $out"
    for x in "${experiments[@]}"; do
        local left=$((limit - (SECONDS - start) - 10))
        if ((left < 30)); then
            echo "gpu_bench: no time left for $x" >&2
            continue
        fi
        timeout --signal=INT --kill-after=10 "$left" \
            "$p/bin/shaftlab" bench "$p/experiments/$x.toml" --out "$out/$x" ||
            echo "gpu_bench: $x ended early (status $?); its finished cells are in $out/$x" >&2
    done
}

case ${1:-} in
package) shift; pack "$@" ;;
run) shift; run "$@" ;;
*) usage ;;
esac
