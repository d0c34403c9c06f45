#!/usr/bin/env bash
# Tests: set up, build, then run the whole GoogleTest suite through ctest.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$repo/scripts/setup.sh"
ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" --timeout 900
