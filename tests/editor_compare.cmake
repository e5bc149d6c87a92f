# A/B comparison under Xvfb (issue 14 item 7): hold the built-in default's image as A, make B
# brighter (toneMap.exposure 2.5), and show the split: the left half of the viewport (A) is
# darker than the right (B); showing A alone takes the brightness back out of the right half.
# The settings that differ A -> B are exactly the one changed, and a preset file's diff with the
# editor is listed. -DEDITOR, -DCHECKER, -DPRESETS and -DWORK come from tests/CMakeLists.txt.
include(${CMAKE_CURRENT_LIST_DIR}/editor_common.cmake)
file(WRITE ${WORK}/script.txt
"wait
hold
set toneMap.exposure=2.5
compare split
screenshot ${WORK}/split
compare a
screenshot ${WORK}/a
diff-file ${PRESETS}/vct_cornell.json
wait
")
run_under_xvfb(1200x600x24 ${EDITOR} --width 1100 --height 500 --script ${WORK}/script.txt --ui-stats ${WORK}/stats.json)
file(READ ${WORK}/stats.json stats)
string(JSON held GET "${stats}" editor compare held)
expect("A held" "${held}" "ON")
string(JSON view GET "${stats}" editor compare view)
expect("compare view at exit" "${view}" "a")
string(JSON ab GET "${stats}" editor compare abDiff)
string(REGEX REPLACE "[ \n]" "" ab "${ab}")
expect("settings that differ A -> B" "${ab}" "[\"toneMap.exposure\"]")
string(JSON fileDiffCount LENGTH "${stats}" editor compare fileDiff)
if(fileDiffCount LESS 1)
  message(FATAL_ERROR "no difference listed between presets/vct_cornell.json and the editor's settings")
endif()
string(JSON fileDiff GET "${stats}" editor compare fileDiff)
message("vct_cornell.json -> editor: ${fileDiff}")

function(halves file outLeft outRight)
  execute_process(COMMAND ${CHECKER} --halves ${file} RESULT_VARIABLE hrc OUTPUT_VARIABLE hout ERROR_VARIABLE herr)
  if(NOT hrc EQUAL 0 OR NOT hout MATCHES "left ([0-9.]+) right ([0-9.]+)")
    message(FATAL_ERROR "cannot read ${file}: ${hout}${herr}")
  endif()
  set(${outLeft} ${CMAKE_MATCH_1} PARENT_SCOPE)
  set(${outRight} ${CMAKE_MATCH_2} PARENT_SCOPE)
endfunction()
halves(${WORK}/split-viewport.png splitLeft splitRight)
halves(${WORK}/a-viewport.png aLeft aRight)
message("split: A half ${splitLeft}, B half ${splitRight}; A alone: ${aLeft} | ${aRight}")
# Grey levels (0..255) compared in whole levels (CMake's math is integer).
string(REGEX REPLACE "\\..*" "" splitRightI "${splitRight}")
string(REGEX REPLACE "\\..*" "" splitLeftI "${splitLeft}")
string(REGEX REPLACE "\\..*" "" aRightI "${aRight}")
math(EXPR splitGap "${splitRightI} - ${splitLeftI}")
math(EXPR aDrop "${splitRightI} - ${aRightI}")
if(splitGap LESS 10)
  message(FATAL_ERROR "the split's halves differ by ${splitGap} grey levels: A and B look alike")
endif()
if(aDrop LESS 10)
  message(FATAL_ERROR "showing A left the right half as bright as B (${aRight} vs ${splitRight})")
endif()
