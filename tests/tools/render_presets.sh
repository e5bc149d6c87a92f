#!/usr/bin/env bash
# Renders every shipped preset at 256x192 into OUT/<preset>/ (image.exr, image.png, stats.json),
# for comparing two builds pixel by pixel (tests/tools/compare_renders.sh):
#   tests/tools/render_presets.sh BUILD_DIR OUT [SHADER_DIR]
# SHADER_DIR (default: this tree's shaders/) lets an older build render with its own shaders.
# RENDER_ARGS (environment) go to every gi-render, e.g. RENDER_ARGS="--set ssao.enabled=true".
# Presets that need ../shared/scenes are skipped when it is absent.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$1
out=$2
shaders=${3:-$(pwd)/shaders}
mkdir -p "$out"
for preset in presets/*.json; do
  name=$(basename "$preset" .json)
  if grep -q '"scene": *"\(sponza\|spheres\)' "$preset" && [ ! -d ../shared/scenes ]; then
    echo "skip $name (no ../shared/scenes)"
    continue
  fi
  GI_SHADER_DIR="$shaders" "$build/app/gi-render" "$preset" ${RENDER_ARGS:-} --width 256 --height 192 --out "$out/$name" >/dev/null 2>"$out/$name.log" ||
    { echo "FAILED $name (see $out/$name.log)"; continue; }
  echo "rendered $name"
done
