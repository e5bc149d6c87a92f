# Runs gi-editor under Xvfb with the Reference panel in split view: the screenshot waits until the
# path-traced reference has its 8 samples and its scores. Then checks that the screenshot exists,
# has the window's size and shows a lit scene, and that the editor reported an SSIM in (0, 1].
# The reference cache is a fresh temporary folder, so the test traces and never reads old files.
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message(FATAL_ERROR "xvfb-run not found: run scripts/install-deps.sh")
endif()
get_filename_component(cache ${OUT} DIRECTORY)
set(cache ${cache}/editor_reference_cache)
file(REMOVE_RECURSE ${cache})
file(MAKE_DIRECTORY ${cache})
file(REMOVE ${OUT})
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env GI_CACHE_DIR=${cache}
          ${XVFB_RUN} -a -s "-screen 0 1280x720x24"
          ${EDITOR} --preset ${PRESET} --frames 3 --reference split --reference-spp 8 --screenshot ${OUT}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
file(REMOVE_RECURSE ${cache})
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gi-editor exited with ${rc}")
endif()
if(NOT out MATCHES "reference 8/8 spp: SSIM ([0-9.]+)")
  message(FATAL_ERROR "gi-editor did not report the reference's SSIM")
endif()
set(ssim ${CMAKE_MATCH_1})
# The reference's own noise, from two halves of its samples (gi::relativeNoise, tested in MetricsNoise).
if(NOT out MATCHES "reference noise ([0-9.]+) %")
  message(FATAL_ERROR "gi-editor did not report the reference's noise")
endif()
set(noise ${CMAKE_MATCH_1})
if(noise LESS_EQUAL 0 OR noise GREATER_EQUAL 100)
  message(FATAL_ERROR "reference noise ${noise} % is outside (0, 100): 8 samples leave some, and less than the image")
endif()
if(ssim LESS_EQUAL 0 OR ssim GREATER 1)
  message(FATAL_ERROR "SSIM ${ssim} is outside (0, 1]")
endif()
execute_process(COMMAND ${CHECKER} ${OUT} 1280 720 RESULT_VARIABLE rc2 OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
message("${out2}${err2}")
if(NOT rc2 EQUAL 0)
  message(FATAL_ERROR "screenshot check failed")
endif()
