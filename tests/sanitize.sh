#!/usr/bin/env bash
# The sanitizer build: the code that reads input (glTF loader, presets, settings, metrics,
# reference) and the fuzzers built with -fsanitize=address,undefined, their tests run, then a
# time-boxed fuzz run with a fixed seed. scripts/quickstart.sh test runs it before the main suite.
#   tests/sanitize.sh [FUZZ_SECONDS]     (default 120)
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds=${1:-120}

# clang brings libFuzzer (the gi-libfuzzer-* harnesses); GCC's sanitizers serve without it.
compilers=()
if command -v clang++ >/dev/null && command -v clang >/dev/null; then compilers=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++); fi
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGI_SANITIZE=ON -DGI_BUILD_EDITOR=OFF "${compilers[@]}" >/dev/null
cmake --build build-asan --parallel "$(nproc)"

# Mesa's driver is unloaded at exit, after which LeakSanitizer cannot name its frames: keep it
# mapped so the suppressions (tests/fuzz/lsan.supp) recognise its allocations, and report only
# the project's own leaks. A single allocation past 1 GiB is a finding: the budget in the fuzz
# run is 256 MiB.
dri=$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null | head -n 1 || true)
export LD_PRELOAD=${dri}
export ASAN_OPTIONS=detect_leaks=1:max_allocation_size_mb=1024:allocator_may_return_null=0:abort_on_error=1:print_summary=1
export LSAN_OPTIONS=suppressions=$(pwd)/tests/fuzz/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export GI_CACHE_DIR=$(pwd)/build-asan/reference-cache

ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)" --timeout 900
echo "sanitize: fuzz run of ${fuzz_seconds} s, seed 1"
build-asan/tests/gi-fuzz --seed 1 --seconds "${fuzz_seconds}" --render-every 25 --timeout-s 60
