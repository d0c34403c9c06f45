#!/usr/bin/env bash
# One-step set-up on a fresh Debian 12 machine: installs the Debian packages shaftlab needs (only
# those missing), configures a Release build in ./build and builds it. Sourced by run.sh and
# test.sh; safe to run again (it does only what is missing).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# A machine that cannot install packages (a GPU box without network) runs the scripts against a
# build made elsewhere: SHAFTLAB_PREBUILT names its build directory and set-up is skipped.
if [ -n "${SHAFTLAB_PREBUILT:-}" ]; then
    build_dir=$SHAFTLAB_PREBUILT
    return 0
fi

packages=(
    build-essential cmake ninja-build pkg-config clang-format
    libgl-dev libegl-dev libosmesa6-dev libglfw3-dev libglm-dev
    libcgal-dev libcgal-demo libembree-dev libtbb-dev
    libimgui-dev libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
    libstb-dev libopenexr-dev libfftw3-dev libassimp-dev libminizip-dev assimp-testmodels
    libgtest-dev libbenchmark-dev xvfb python3 python3-matplotlib blender-data parallel
    openarena-081-maps
)

source "$repo/scripts/packages.sh"
install_missing "${packages[@]}"

build_type=${SHAFTLAB_BUILD_TYPE:-Release}
build_dir=${SHAFTLAB_BUILD_DIR:-$repo/build}
cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" ${SHAFTLAB_CMAKE_ARGS:-}
cmake --build "$build_dir" --parallel "$(nproc)"
