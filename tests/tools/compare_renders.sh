#!/usr/bin/env bash
# Compares two folders written by render_presets.sh: per preset, the largest absolute difference
# of the linear HDR image (image.exr) and of the tone-mapped PNG, as OpenImageIO's idiff gives it.
#   tests/tools/compare_renders.sh BEFORE AFTER
set -uo pipefail
before=$1
after=$2
status=0
printf '%-28s %14s %14s\n' preset "max |HDR diff|" "max |PNG diff|"
for dir in "$before"/*/; do
  name=$(basename "$dir")
  if [ ! -f "$after/$name/image.exr" ]; then
    printf '%-28s %s\n' "$name" "missing after"; status=1; continue
  fi
  hdr=$(idiff -a "$dir/image.exr" "$after/$name/image.exr" 2>&1 | awk '/Max error/ {print $4}')
  png=$(idiff -a "$dir/image.png" "$after/$name/image.png" 2>&1 | awk '/Max error/ {print $4}')
  printf '%-28s %14s %14s\n' "$name" "${hdr:-0}" "${png:-0}"
  [ "${hdr:-0}" = 0 ] && [ "${png:-0}" = 0 ] || status=1
done
exit $status
