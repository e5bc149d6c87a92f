#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs the packages, builds, then either runs
# the main job or the whole test suite.
#   scripts/quickstart.sh run   the editor on the default preset; with no display, a headless
#                               render of that preset (prints where the image is)
#   scripts/quickstart.sh test  every test (ctest), as CI runs it, after the sanitizer build's
#                               tests and a two-minute fuzz run (tests/sanitize.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-run}
case "$mode" in run|test) ;; *) echo "usage: $0 run|test" >&2; exit 2 ;; esac

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --parallel "$(nproc)"

if [ "$mode" = test ]; then
  # The input-handling code under AddressSanitizer and UBSan, and a two-minute fuzz run.
  bash tests/sanitize.sh 120
  cd build
  exec ctest --output-on-failure --parallel "$(nproc)" --timeout 900
fi

if [ -n "${DISPLAY:-}" ] && [ -x build/app/gi-editor ]; then
  exec build/app/gi-editor --preset presets/default.json
fi
echo "No display: rendering presets/default.json headless instead of opening the editor."
build/app/gi-render presets/default.json --out out/default --views
echo "Image: $(pwd)/out/default/image.png (stats: out/default/stats.json, views: out/default/views/)"
