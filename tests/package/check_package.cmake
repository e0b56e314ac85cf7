# Installs collide from BUILD_DIR into a scratch prefix, then configures, builds and runs the consumer
# project (and the programs in EXAMPLES_DIR) against it, as a user's find_package(collide) would, and
# compiles the consumer with the flags of the installed pkg-config file (CXX, the compiler).
# CONSUMER_FLAGS carries the sanitizer flags of a sanitized build, whose static library needs their
# runtime.
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} COMMAND_ERROR_IS_FATAL ANY
                OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
                        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
                        "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}" COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${WORK_DIR}/build/consumer COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK_DIR}/build/scene_consumer COMMAND_ERROR_IS_FATAL ANY)

# pkg-config: the installed collide.pc gives what a build without CMake needs to compile and link.
if(CXX)
  find_program(PKG_CONFIG pkg-config REQUIRED)
  file(GLOB_RECURSE pc_files ${prefix}/*/collide.pc)
  list(GET pc_files 0 pc_file)
  get_filename_component(pc_dir ${pc_file} DIRECTORY)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir} ${PKG_CONFIG} --cflags --libs collide
                  OUTPUT_VARIABLE pc_flags OUTPUT_STRIP_TRAILING_WHITESPACE COMMAND_ERROR_IS_FATAL ANY)
  separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
  separate_arguments(consumer_flags UNIX_COMMAND "${CONSUMER_FLAGS}")
  execute_process(COMMAND ${CXX} -std=c++20 ${consumer_flags} ${SOURCE_DIR}/consumer.cpp ${pc_flags}
                          -o ${WORK_DIR}/consumer_pkg_config COMMAND_ERROR_IS_FATAL ANY)
  execute_process(COMMAND ${WORK_DIR}/consumer_pkg_config COMMAND_ERROR_IS_FATAL ANY)
endif()

# The examples (examples/) against the same installed package: they build and run.
if(EXAMPLES_DIR)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${EXAMPLES_DIR} -B ${WORK_DIR}/examples -DCMAKE_PREFIX_PATH=${prefix}
                          -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
                          "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}" COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/examples COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
  execute_process(COMMAND ${WORK_DIR}/examples/falling_bodies COMMAND_ERROR_IS_FATAL ANY)
  execute_process(COMMAND ${WORK_DIR}/examples/job_system COMMAND_ERROR_IS_FATAL ANY)
endif()
