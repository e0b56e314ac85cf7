# cmake -P script behind the viewer_screenshot_pyramid test: render the pyramid headless under
# xvfb-run, then check the PNG (size, not blank) with check_png.py.
file(REMOVE ${SHOT})
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x720x24" ${VIEWER} pyramid --screenshot ${SHOT}
                        --frames 60 --width 640 --height 360 --no-ui
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "collide-viewer --screenshot failed: ${result}")
endif()
execute_process(COMMAND ${PYTHON} ${CHECK} ${SHOT} 640 360 RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the screenshot ${SHOT} fails the check")
endif()
