# `collide run --snapshot-at K --snapshot FILE`, then `--from-snapshot FILE` for the steps left, ends in
# the state of one run of them all (the "state hash" lines equal). CLI (the program), SCENE, STEPS,
# AT, WORK (a folder for the snapshot file).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(snapshot "${WORK}/world.snapshot")
execute_process(COMMAND ${CLI} run ${SCENE} --steps ${STEPS} OUTPUT_VARIABLE whole COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CLI} run ${SCENE} --steps ${STEPS} --snapshot ${snapshot} --snapshot-at ${AT}
                OUTPUT_VARIABLE saving COMMAND_ERROR_IS_FATAL ANY)
math(EXPR rest "${STEPS} - ${AT}")
execute_process(COMMAND ${CLI} run ${SCENE} --from-snapshot ${snapshot} --steps ${rest} OUTPUT_VARIABLE resumed
                COMMAND_ERROR_IS_FATAL ANY)
string(REGEX MATCH "state hash +[0-9a-f]+" hashWhole "${whole}")
string(REGEX MATCH "state hash +[0-9a-f]+" hashSaving "${saving}")
string(REGEX MATCH "state hash +[0-9a-f]+" hashResumed "${resumed}")
if(hashWhole STREQUAL "" OR NOT hashWhole STREQUAL hashResumed OR NOT hashWhole STREQUAL hashSaving)
  message(FATAL_ERROR "${SCENE}: ${STEPS} steps '${hashWhole}', saving at ${AT} '${hashSaving}', resumed from it "
                      "'${hashResumed}'")
endif()
message(STATUS "${SCENE}: ${hashWhole} whole and resumed at step ${AT}")
