# cmake -P script behind the viewer_screenshot_* tests: render SCENE after FRAMES steps headless under
# xvfb-run, with the camera report, then check the PNG against it with check_png.py.
file(REMOVE ${SHOT} ${SHOT}.json)
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x720x24" ${VIEWER} ${SCENE} --screenshot ${SHOT}
                        --camera-json ${SHOT}.json --frames ${FRAMES} --width 640 --height 360 --no-ui
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "collide-viewer --screenshot failed: ${result}")
endif()
execute_process(COMMAND ${PYTHON} ${CHECK} ${SHOT} 640 360 --report ${SHOT}.json RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the screenshot ${SHOT} fails the check")
endif()
