#!/bin/bash
# Runs inside xvfb-run (tests/editor_keys.cmake): gi-editor with 1 s frames, and xdotool taps
# (press and release within a few milliseconds, so within one frame) into the presets panel's path
# field: End, Q, Backspace, Backspace. Every tap must arrive: the field ends as it began, less its
# last character. Usage: editor_keys.sh EDITOR PRESET STATS
set -u
editor=$1 preset=$2 stats=$3
# The GI renders once (nothing changes), so the frames are the 1 s delay; 24 of them outlast the
# taps. The left panel's layout does not depend on the size.
"$editor" --preset "$preset" --frames 24 --frame-delay-ms 1000 --ui-stats "$stats" --width 640 --height 480 &
pid=$!
xdotool search --sync --onlyvisible --name "GI Workbench" > /dev/null
sleep 6
xdotool mousemove 60 279 click 1    # the path field (fixed layout: no imgui.ini)
sleep 4                              # at least two frames: the field is active before the keys come
xdotool key End
sleep 0.2
xdotool type Q
sleep 0.2
xdotool key BackSpace
sleep 0.2
xdotool key BackSpace
wait $pid
