#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [TARGET...]: builds the libFuzzer targets of tests/fuzz with clang 14,
# AddressSanitizer and UndefinedBehaviorSanitizer (in build-fuzz/, or $SHAFTLAB_FUZZ_BUILD_DIR),
# then runs each TARGET (default: all of them) for SECONDS (default 60) from its seed corpus in
# tests/fuzz/corpus/<target>/. The inputs it finds stay in build-fuzz/fuzz/corpus/<target>/ for
# the next run; a crash, leak, timeout (20 s) or out-of-memory (2 GiB) leaves its input in
# build-fuzz/fuzz/artifacts/<target>/ and makes the script exit non-zero. CI runs it for 30 s.
# Leaks inside Debian's assimp (a known importer bug) are suppressed: tests/fuzz/lsan.supp.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
shift || true
all=(scene off obj environment experiment animation bsp)
targets=("$@")
((${#targets[@]})) || targets=("${all[@]}")

source "$repo/scripts/packages.sh"
install_missing clang-14 libclang-rt-14-dev cmake ninja-build
build_dir=${SHAFTLAB_FUZZ_BUILD_DIR:-$repo/build-fuzz}
# SHAFTLAB_FUZZ_SKIP_BUILD=1 runs what is built (several runs side by side share one build).
if [ -z "${SHAFTLAB_FUZZ_SKIP_BUILD:-}" ]; then
    CC=clang-14 CXX=clang++-14 cmake -S "$repo" -B "$build_dir" -G Ninja \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHAFTLAB_FUZZ=ON >/dev/null
    cmake --build "$build_dir" --target fuzzers --parallel "$(nproc)"
fi

failed=()
for target in "${targets[@]}"; do
    binary=$build_dir/fuzz/${target}_fuzzer
    [ -x "$binary" ] || { echo "fuzz: unknown target '$target' (known: ${all[*]})" >&2; exit 2; }
    corpus=$build_dir/fuzz/corpus/$target
    artifacts=$build_dir/fuzz/artifacts/$target
    log=$build_dir/fuzz/$target.log
    mkdir -p "$corpus" "$artifacts"
    if ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
        LSAN_OPTIONS=suppressions=$repo/tests/fuzz/lsan.supp \
        UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        "$binary" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$artifacts/" \
        "$corpus" "$repo/tests/fuzz/corpus/$target" >"$log" 2>&1; then
        runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
        features=$(grep -o 'ft: [0-9]*' "$log" | tail -n 1 | grep -o '[0-9]*' || echo '?')
        echo "fuzz: $target: ${seconds} s, $runs inputs, $(ls "$corpus" | wc -l) in the corpus, $features features, nothing found"
    else
        echo "fuzz: $target: FOUND a problem (log $log, input in $artifacts):" >&2
        grep -E 'ERROR|SUMMARY|error message|Test unit written|==[0-9]+==' "$log" | head -n 12 >&2 || tail -n 30 "$log" >&2
        failed+=("$target")
    fi
done
if ((${#failed[@]})); then
    echo "fuzz: findings in ${failed[*]}" >&2
    exit 1
fi
