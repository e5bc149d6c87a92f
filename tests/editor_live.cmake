# Drives gi-editor under Xvfb on the built-in default (VCT on the Cornell box) with --script and
# reads back --ui-stats: the GI renders the first frame, a preview at a quarter of the width and
# height for each frame of a drag, the full frame once the drag ends, nothing while the picture
# does not change, nothing while paused though a value changed, and the full frame on resume.
# Prints the UI frames that rendered no GI beside the GI frames (reported, not asserted: speed
# is measured, not tested). -DEDITOR and -DWORK (a scratch folder) come from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)
file(WRITE ${WORK}/live.txt
"wait
drag vct.nudge=2.5
drag vct.nudge=2.0
wait
wait
wait
wait
pause
set vct.nudge=1.5
wait
wait
resume
wait
wait
wait
")
execute_process(
  COMMAND ${XVFB_RUN} -a -s "-screen 0 1100x600x24" ${EDITOR} --width 1000 --height 360
          --script ${WORK}/live.txt --ui-stats ${WORK}/live.json
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 500)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gi-editor exited with ${rc}: ${out}${err}")
endif()
file(READ ${WORK}/live.json stats)

# The GI frames, as WIDTHxHEIGHT in order.
string(JSON count LENGTH "${stats}" giFrames)
set(sizes "")
set(giFrameUI "")
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON w GET "${stats}" giFrames ${i} width)
  string(JSON h GET "${stats}" giFrames ${i} height)
  string(JSON ui GET "${stats}" giFrames ${i} uiFrame)
  string(JSON ms GET "${stats}" giFrames ${i} ms)
  list(APPEND sizes "${w}x${h}")
  list(APPEND giFrameUI ${ui})
  message("GI frame ${i}: ${w}x${h}, ${ms} ms, in UI frame ${ui}")
endforeach()
string(REPLACE ";" " " sizes "${sizes}")
# The GI renders the viewport (the window less the docked columns), a quarter of it each way in a drag.
string(JSON vw GET "${stats}" editor viewport 1)
string(JSON vh GET "${stats}" editor viewport 2)
math(EXPR pw "${vw} / 4")
math(EXPR ph "${vh} / 4")
set(expected "${vw}x${vh} ${pw}x${ph} ${pw}x${ph} ${vw}x${vh} ${vw}x${vh}")
if(NOT "${sizes}" STREQUAL "${expected}")
  message(FATAL_ERROR "GI frames: got '${sizes}', expected '${expected}' "
                      "(first frame, two drag previews, the full frame after the drag, the full frame on resume)")
endif()
string(JSON paused GET "${stats}" editor paused)
string(JSON settled GET "${stats}" editor giSettled)
if(paused OR NOT settled)
  message(FATAL_ERROR "at exit: paused ${paused}, settled ${settled} (expected OFF, ON)")
endif()

# UI frames that rendered no GI (uiFrameMs[k] is the duration of UI frame k + 1, frames counted from 1).
string(JSON uiCount LENGTH "${stats}" uiFrameMs)
math(EXPR uiLast "${uiCount} - 1")
set(idle "")
foreach(k RANGE ${uiLast})
  math(EXPR frame "${k} + 1")
  list(FIND giFrameUI ${frame} rendered)
  if(rendered EQUAL -1)
    string(JSON ms GET "${stats}" uiFrameMs ${k})
    list(APPEND idle ${ms})
  endif()
endforeach()
list(LENGTH idle idleCount)
if(idleCount LESS 8)
  message(FATAL_ERROR "only ${idleCount} UI frames rendered no GI (expected the waits and the paused frames)")
endif()
message("UI frames without GI work (ms): ${idle}")
