# Configures, builds and runs tests/package/subproject, which takes collide's source tree SOURCE_DIR
# as a subproject (MODE: add_subdirectory or fetchcontent), in WORK_DIR with GENERATOR. Unity
# batches keep the library's build short; the consumer only has to link and run.
file(REMOVE_RECURSE ${WORK_DIR})
# The add_subdirectory game builds everything, collide included, without exceptions or RTTI, as
# many engines do (collide with COLLIDE_EXCEPTIONS=OFF); the FetchContent one with both.
if(MODE STREQUAL "fetchcontent")
  set(fetch ON)
  set(flags "")
  set(exceptions ON)
else()
  set(fetch OFF)
  set(flags "-fno-rtti -fno-exceptions")
  set(exceptions OFF)
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/subproject -B ${WORK_DIR} -G ${GENERATOR}
                        -DCOLLIDE_SOURCE_DIR=${SOURCE_DIR} -DUSE_FETCHCONTENT=${fetch} -DCMAKE_UNITY_BUILD=ON
                        "-DCMAKE_CXX_FLAGS=${flags}" -DCOLLIDE_EXCEPTIONS=${exceptions}
                COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} -j2 COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${WORK_DIR}/consumer COMMAND_ERROR_IS_FATAL ANY)
