# The docked layout under Xvfb (issue 14 item 3): the panels stand in two columns at the window's
# sides and the scene is drawn between them; after the window is resized the right column moves
# with the window's edge and the viewport takes the new room. The help window opens, and the
# screenshot action writes the window and the viewport. The user's layout file sets the
# column widths, the previewers shown and the drag preview at start and is written back at exit.
# -DEDITOR, -DCHECKER and -DWORK (a scratch folder) come from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)
file(WRITE ${WORK}/layout.json
  "{\"leftWidth\": 380, \"rightWidth\": 300, \"previewers\": {\"vct.cones\": true}, \"dragPreview\": 2, "
  "\"sections\": {\"presets\": false, \"lpv\": true, \"lpv/developer\": true}}\n")
file(WRITE ${WORK}/script.txt "wait\nsection render/developer open\nsection quality open\nresize 1200x700\nwait\nwait\nwait\nwait\nwait\nwait\nhelp\nwait\nscreenshot ${WORK}/shot\nwait\n")
run_under_xvfb(1400x900x24 ${EDITOR} --width 1000 --height 600 --layout ${WORK}/layout.json
               --script ${WORK}/script.txt --ui-stats ${WORK}/stats.json --screenshot ${WORK}/resized.png)
file(READ ${WORK}/stats.json stats)
string(JSON w GET "${stats}" editor window 0)
string(JSON h GET "${stats}" editor window 1)
expect("window after the resize" "${w}x${h}" "1200x700")
string(JSON left GET "${stats}" editor leftColumnWidth)
expect("left column (from the layout file)" "${left}" "380")
string(JSON rightX GET "${stats}" editor rightColumnX)
expect("right column's left edge (window width - 300)" "${rightX}" "900")
string(JSON vx GET "${stats}" editor viewport 0)
string(JSON vw GET "${stats}" editor viewport 1)
string(JSON vh GET "${stats}" editor viewport 2)
expect("viewport (x, width, height) between the columns" "${vx} ${vw} ${vh}" "380 520 700")
execute_process(COMMAND ${CHECKER} ${WORK}/resized.png 1200 700 RESULT_VARIABLE rc2 OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
message("${out2}${err2}")
if(NOT rc2 EQUAL 0)
  message(FATAL_ERROR "screenshot check failed")
endif()
# The screenshot action (F12's): the window, and the viewport alone (the scene between the columns).
foreach(part "window 1200 700" "viewport 520 700")
  separate_arguments(args UNIX_COMMAND "${part}")
  list(GET args 0 name)
  list(GET args 1 w)
  list(GET args 2 h)
  execute_process(COMMAND ${CHECKER} ${WORK}/shot-${name}.png ${w} ${h} RESULT_VARIABLE rc3 OUTPUT_VARIABLE out3 ERROR_VARIABLE err3)
  message("${out3}${err3}")
  if(NOT rc3 EQUAL 0)
    message(FATAL_ERROR "the ${name} screenshot is missing or wrong (expected ${w}x${h}, not blank)")
  endif()
endforeach()
file(READ ${WORK}/layout.json saved)
string(JSON savedLeft GET "${saved}" leftWidth)
string(JSON savedPreview GET "${saved}" dragPreview)
string(JSON cones GET "${saved}" previewers vct.cones)
expect("saved layout (leftWidth, dragPreview, vct.cones)" "${savedLeft} ${savedPreview} ${cones}" "380.0 2 ON")
# Sections open or closed as the layout file had them (presets closed, lpv open, against their
# defaults), and written back.
string(JSON open GET "${stats}" editor openSections)
string(REGEX REPLACE "[ \n]" "" open "${open}")
if(open MATCHES "\"presets\"" OR NOT open MATCHES "\"lpv\"" OR NOT open MATCHES "\"scene\"")
  message(FATAL_ERROR "open sections ${open}: expected lpv and scene open, presets closed (from the layout file)")
endif()
string(JSON savedPresets GET "${saved}" sections presets)
string(JSON savedLpv GET "${saved}" sections lpv)
expect("saved sections (presets, lpv)" "${savedPresets} ${savedLpv}" "OFF ON")
# Each section shows what an artist tunes; the developer settings sit in a node, closed unless
# the layout (lpv/developer) or the script's `section` (render/developer) opens it. The quality
# section is opened by the script too: all of it is developer settings, so none of it is drawn.
string(JSON shown GET "${stats}" editor fieldsShown)
foreach(key vct.intensity vct.gridResolution lpv.intensity lpv.nudge render.shadowMapSize render.shadowBias)
  if(NOT shown MATCHES "\"${key}\"")
    message(FATAL_ERROR "${key} is not drawn: ${shown}")
  endif()
endforeach()
foreach(key vct.nudge vct.stepMultiplier quality.minSSIM)
  if(shown MATCHES "\"${key}\"")
    message(FATAL_ERROR "${key} (a developer setting, its node closed) is drawn: ${shown}")
  endif()
endforeach()
string(JSON savedDev GET "${saved}" sections lpv/developer)
string(JSON savedRenderDev GET "${saved}" sections render/developer)
expect("saved developer nodes (lpv, render)" "${savedDev} ${savedRenderDev}" "ON ON")
