# The compare section's matrix cells under Xvfb (issue 15 item 6): the smoke matrix's results
# (matrix.smoke writes them first) loaded, two cells picked and shown side by side, then split,
# with their figures. -DEDITOR, -DMATRIX (the results folder) and -DWORK come from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)
file(WRITE ${WORK}/script.txt
"wait
section scene closed
section presets closed
section render closed
matrix-load ${MATRIX}
matrix-pick 0 5
matrix-view side
wait
screenshot ${WORK}/side
matrix-view split
wait
screenshot ${WORK}/split
")
run_under_xvfb(1200x700x24 ${EDITOR} --width 1100 --height 650 --script ${WORK}/script.txt --ui-stats ${WORK}/stats.json)
file(READ ${WORK}/stats.json stats)
string(JSON cells GET "${stats}" editor matrix cells)
expect("cells loaded from the smoke matrix" "${cells}" "14")
string(JSON shown GET "${stats}" editor matrix imagesShown)
expect("both cells' images shown" "${shown}" "ON")
string(JSON view GET "${stats}" editor matrix view)
expect("view at exit" "${view}" "split")
string(JSON a GET "${stats}" editor matrix pick 0)
string(JSON b GET "${stats}" editor matrix pick 1)
if("${a}" STREQUAL "${b}")
  message(FATAL_ERROR "the two picks are the same cell: ${a}")
endif()
message("compared ${a} with ${b}")
