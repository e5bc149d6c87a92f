# Drives gi-editor under Xvfb with --script (actions through the same functions the panels and
# shortcuts call) and reads back --ui-stats and the files it saved:
#  1. edits, undo, a reset of one key and of a section, Save As: the saved file holds only the
#     changed keys, the history and the dirty flag are right;
#  2. Save on a shipped preset asks first and leaves the file as it was;
#  3. --preset BAD opens the editor on the default with the error shown; opening a good preset
#     clears it.
# -DEDITOR, -DPRESET_DIR, -DWORK (a scratch folder) are given by tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)

function(run_editor name preset script)
  file(WRITE ${WORK}/${name}.txt "${script}")
  execute_process(
    COMMAND ${XVFB_RUN} -a -s "-screen 0 800x600x24" ${EDITOR} --preset ${preset} --width 640 --height 480
            --script ${WORK}/${name}.txt --ui-stats ${WORK}/${name}.stats.json
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 600)
  message("${name}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: gi-editor exited with ${rc}")
  endif()
  file(READ ${WORK}/${name}.stats.json stats)
  set(stats "${stats}" PARENT_SCOPE)
endfunction()


# 1. Edits, undo, resets and Save As.
file(COPY ${PRESET_DIR}/basic.json DESTINATION ${WORK})
file(RENAME ${WORK}/basic.json ${WORK}/mine.json)
run_editor(edits ${WORK}/mine.json
"set vct.nudge=2.5
set ssao.radius=0.2
undo
set lpv.gridResolution=16
reset lpv.gridResolution
set camera.fovY=50
reset-section camera
save-as ${WORK}/saved.json
")
string(JSON n LENGTH "${stats}" editor history)
expect("history length" "${n}" 6)  # opened, nudge, lpv 16, lpv 32, fovY, camera reset (ssao undone, then dropped)
string(JSON label GET "${stats}" editor history 1)
expect("first step" "${label}" "vct.nudge 3.0 -> 2.5")
string(JSON dirty GET "${stats}" editor dirty)
expect("dirty after Save As" "${dirty}" "OFF")
file(READ ${WORK}/saved.json saved)
string(JSON nudge GET "${saved}" vct nudge)
expect("saved vct.nudge" "${nudge}" "2.5")
string(JSON vctKeys LENGTH "${saved}" vct)
expect("saved vct keys" "${vctKeys}" 1)
foreach(section ssao lpv camera)
  string(JSON missing ERROR_VARIABLE absent GET "${saved}" ${section})
  if(NOT absent)
    message(FATAL_ERROR "saved.json holds section '${section}', which is back at its defaults:\n${saved}")
  endif()
endforeach()

# 2. Save on a shipped preset asks first and does not write.
file(READ ${PRESET_DIR}/cornell_lamp.json shippedBefore)
run_editor(shipped ${PRESET_DIR}/cornell_lamp.json
"set toneMap.exposure=2
save
")
string(JSON status GET "${stats}" editor status)
if(NOT status MATCHES "shipped preset")
  file(READ ${PRESET_DIR}/cornell_lamp.json shippedAfter)
  file(WRITE ${PRESET_DIR}/cornell_lamp.json "${shippedBefore}")  # put the shipped file back before failing
  message(FATAL_ERROR "Save on a shipped preset did not ask: status '${status}'")
endif()
string(JSON dirty GET "${stats}" editor dirty)
expect("dirty after a refused save" "${dirty}" "ON")
file(READ ${PRESET_DIR}/cornell_lamp.json shippedAfter)
if(NOT shippedAfter STREQUAL shippedBefore)
  file(WRITE ${PRESET_DIR}/cornell_lamp.json "${shippedBefore}")  # put the shipped file back before failing
  message(FATAL_ERROR "Save wrote the shipped preset cornell_lamp.json (restored)")
endif()

# 3. A broken preset opens the editor with the error, and a good one clears it.
file(WRITE ${WORK}/broken.json "{\"schemaVersion\": 2, \"vct\": {\"nudge\": \"far\"}}")
run_editor(broken ${WORK}/broken.json "")
string(JSON error GET "${stats}" editor errors 0)
if(NOT error MATCHES "broken.json" OR NOT error MATCHES "vct.nudge")
  message(FATAL_ERROR "the error shown does not name the file and key: '${error}'")
endif()
run_editor(reopen ${WORK}/broken.json "open ${WORK}/mine.json
")
string(JSON errors LENGTH "${stats}" editor errors)
expect("errors after a good preset opened" "${errors}" 0)
string(JSON file GET "${stats}" editor file)
expect("file after open" "${file}" "${WORK}/mine.json")

# 4. Views: the current camera saved as a named view in the preset, a jump back to it after the
# camera changed, a jump to the file's camera 0, and the views written by Save As.
file(COPY ${PRESET_DIR}/basic.json DESTINATION ${WORK}/views)
run_editor(views ${WORK}/views/basic.json "set camera.fovY=55
bookmark wide
set camera.fovY=30
goto wide
save-as ${WORK}/views/saved.json
camera 0
")
string(JSON fov GET "${stats}" editor preset camera fovY)
expect("fovY after the jump to the file camera (55 before it)" "${fov}" "45.0")
file(READ ${WORK}/views/saved.json saved)
string(JSON name GET "${saved}" bookmarks 0 name)
string(JSON savedFov GET "${saved}" bookmarks 0 fovY)
string(JSON cameraFov GET "${saved}" camera fovY)
expect("saved view (name, fovY) and the camera after goto" "${name} ${savedFov} ${cameraFov}" "wide 55.0 55.0")
string(JSON label GET "${stats}" editor history 2)
expect("the bookmark's undo step" "${label}" "bookmarks 0 views -> 1 views")
message("editor script checks passed")
