# The Auto-tune panel under Xvfb (issue 15 item 5): the built-in default (VCT) searched for LPV
# settings in 3 renders at 48x36, each a gi-render process, while the editor keeps drawing; the
# panel shows the best render's image; Apply makes the winner the preset's (technique lpv).
# -DEDITOR, -DCHECKER and -DWORK come from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)
file(WRITE ${WORK}/script.txt
"wait
tune lpv 100000 3 48x36
tune-wait
section scene closed
section presets closed
section render closed
wait
screenshot ${WORK}/tune
tune-apply
wait
")
run_under_xvfb(1200x700x24 ${EDITOR} --width 1100 --height 650 --script ${WORK}/script.txt --ui-stats ${WORK}/stats.json)
file(READ ${WORK}/stats.json stats)
string(JSON state GET "${stats}" editor tune state)
expect("auto-tune state" "${state}" "finished")
string(JSON renders GET "${stats}" editor tune renders)
expect("renders spent" "${renders}" "3")
string(JSON within GET "${stats}" editor tune best withinBudget)
expect("best within the budget" "${within}" "ON")
string(JSON shown GET "${stats}" editor tune imageShown)
expect("the best render's image shown" "${shown}" "ON")
string(JSON ssim GET "${stats}" editor tune best ssim)
string(JSON settings GET "${stats}" editor tune best settings)
string(JSON technique GET "${stats}" editor preset technique)
expect("technique after Apply" "${technique}" "lpv")
string(JSON historyCount LENGTH "${stats}" editor history)
if(historyCount LESS 2)
  message(FATAL_ERROR "Apply left no undoable step in the history")
endif()
# The UI frames while the search ran (not asserted: speed is measured, not tested).
string(JSON frames LENGTH "${stats}" uiFrameMs)
message("auto-tune: best SSIM ${ssim} with ${settings}; ${frames} UI frames drawn")
execute_process(COMMAND ${CHECKER} --halves ${WORK}/tune-window.png RESULT_VARIABLE hrc OUTPUT_VARIABLE hout ERROR_VARIABLE herr)
if(NOT hrc EQUAL 0)
  message(FATAL_ERROR "cannot read the screenshot: ${hout}${herr}")
endif()
