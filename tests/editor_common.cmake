# Shared by the editor tests that drive gi-editor under Xvfb (editor_script, editor_live,
# editor_layout): xvfb-run must exist, WORK starts empty, and expect() compares a read-back value.
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
