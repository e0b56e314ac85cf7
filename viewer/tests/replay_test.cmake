# cmake -P script behind the viewer_replay_* tests: `collide run SCENE --record` for FRAMES steps, then
# the viewer headless twice under xvfb-run: stepping live to step FRAMES, and replaying the recording
# at its frame of step FRAMES. The recording gives the run's poses back bit for bit, so the two
# images must be the same, byte for byte (Mesa's software renderer draws the same pixels every time).
# Without the joints' lines: the library draws them from the world's state, which setTransform keeps
# from the centre of mass, the body origin back to within a rounding (a pixel's shade).
# CLI (the collide command), VIEWER, XVFB_RUN, SCENE, FRAMES, WORK (a folder).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CLI} run ${SCENE} --steps ${FRAMES} --record ${WORK}/recording.json
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
foreach(mode IN ITEMS live replay)
  set(extra)
  if(mode STREQUAL "replay")
    set(extra --replay ${WORK}/recording.json)
  endif()
  execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x720x24" ${VIEWER} ${SCENE} ${extra}
                          --screenshot ${WORK}/${mode}.png --frames ${FRAMES} --width 480 --height 270 --no-ui --no-joints
                  OUTPUT_QUIET RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "collide-viewer ${mode} --screenshot failed: ${result}")
  endif()
endforeach()
file(SHA256 ${WORK}/live.png live)
file(SHA256 ${WORK}/replay.png replayed)
if(NOT live STREQUAL replayed)
  message(FATAL_ERROR "${SCENE}: the replayed frame of step ${FRAMES} is not the live one (${WORK}/live.png, replay.png)")
endif()
# The first frame differs from the last: the replay did not just show the scene as built.
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x720x24" ${VIEWER} ${SCENE} --replay ${WORK}/recording.json
                        --screenshot ${WORK}/first.png --frames 0 --width 480 --height 270 --no-ui --no-joints
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
file(SHA256 ${WORK}/first.png first)
if(first STREQUAL replayed)
  message(FATAL_ERROR "${SCENE}: the replay's first and last frames are the same image")
endif()
