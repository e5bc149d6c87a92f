# Runs gi-editor under Xvfb for a few frames, then checks that the screenshot exists, has the
# window's size and shows a lit scene (not a black or uniform frame). EXTRA_ARGS (optional, one
# string, space separated) goes to gi-editor as well, e.g. "--voxel-view albedo".
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message(FATAL_ERROR "xvfb-run not found: run scripts/install-deps.sh")
endif()
file(REMOVE ${OUT})
separate_arguments(extra UNIX_COMMAND "${EXTRA_ARGS}")
execute_process(
  COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x720x24" ${EDITOR} --preset ${PRESET} --frames 3 --screenshot ${OUT} ${extra}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gi-editor exited with ${rc}")
endif()
execute_process(COMMAND ${CHECKER} ${OUT} 1280 720 RESULT_VARIABLE rc2 OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
message("${out2}${err2}")
if(NOT rc2 EQUAL 0)
  message(FATAL_ERROR "screenshot check failed")
endif()
