# Shared by the editor tests that drive gi-editor under Xvfb (editor_script, editor_live,
# editor_layout, editor_keys, editor_compare): xvfb-run must exist, WORK starts empty,
# run_under_xvfb() runs a command on a virtual screen and fails the test when it fails, and
# expect() compares a read-back value.
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message(FATAL_ERROR "xvfb-run not found: run scripts/install-deps.sh")
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect what actual expected)
  if(NOT "${actual}" STREQUAL "${expected}")
    message(FATAL_ERROR "${what}: got '${actual}', expected '${expected}'")
  endif()
endfunction()

# run_under_xvfb(SCREEN COMMAND...): runs COMMAND under xvfb-run on a SCREEN (e.g. 1200x600x24)
# display, prints what it wrote, and fails when it exits non-zero or runs past 300 s.
function(run_under_xvfb screen)
  execute_process(
    COMMAND ${XVFB_RUN} -a -s "-screen 0 ${screen}" ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGV1} exited with ${rc}")
  endif()
endfunction()
