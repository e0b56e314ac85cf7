# collide's headers refuse a GLM configured with another data layout (include/collide/math.h): the
# game's own compilation fails naming the macro, instead of handing the library misplaced data. CXX,
# SOURCE (tests/package/glm_configuration.cpp), INCLUDE (collide's include folder). The default
# configuration compiles.
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only -I${INCLUDE} ${SOURCE} RESULT_VARIABLE code
                ERROR_VARIABLE errors)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the default GLM configuration does not compile:\n${errors}")
endif()
foreach(check IN ITEMS "GLM_FORCE_QUAT_DATA_WXYZ|glm::quat stores its components in another order"
                       "GLM_FORCE_DEFAULT_ALIGNED_GENTYPES GLM_FORCE_INTRINSICS|GLM's vectors are aligned or padded")
  string(REPLACE "|" ";" check "${check}")
  list(GET check 0 macros)
  list(GET check 1 expected)
  separate_arguments(macros)
  list(TRANSFORM macros PREPEND -D)
  execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${macros} -I${INCLUDE} ${SOURCE} RESULT_VARIABLE code
                  ERROR_VARIABLE errors)
  if(code EQUAL 0)
    message(FATAL_ERROR "${macros}: compiled, but collide's headers should have refused it")
  endif()
  string(FIND "${errors}" "${expected}" at)
  if(at LESS 0)
    message(FATAL_ERROR "${macros}: refused without the message '${expected}':\n${errors}")
  endif()
endforeach()
