# A WebAssembly build (emcmake) takes Debian's header-only libraries by their headers alone: their
# CMake packages name /usr/include, whose C library headers are the host's and break emscripten's
# own. GLM, nlohmann-json and tinyobjloader's header (its implementation compiled here: Debian's
# library is built for the host) are linked into a directory of their own and used from there.
set(COLLIDE_HOST_HEADERS ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${COLLIDE_HOST_HEADERS})
foreach(entry glm nlohmann tiny_obj_loader.h)
  if(NOT EXISTS /usr/include/${entry})
    message(FATAL_ERROR "/usr/include/${entry} is missing: scripts/install-deps installs it")
  endif()
  if(NOT EXISTS ${COLLIDE_HOST_HEADERS}/${entry})
    file(CREATE_LINK /usr/include/${entry} ${COLLIDE_HOST_HEADERS}/${entry} SYMBOLIC)
  endif()
endforeach()

add_library(glm::glm INTERFACE IMPORTED GLOBAL)
set_target_properties(glm::glm PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${COLLIDE_HOST_HEADERS})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED GLOBAL)
set_target_properties(nlohmann_json::nlohmann_json PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${COLLIDE_HOST_HEADERS})
file(WRITE ${CMAKE_BINARY_DIR}/tinyobjloader_impl.cpp "#define TINYOBJLOADER_IMPLEMENTATION\n#include <tiny_obj_loader.h>\n")
add_library(collide_tinyobjloader STATIC ${CMAKE_BINARY_DIR}/tinyobjloader_impl.cpp)
target_include_directories(collide_tinyobjloader SYSTEM PUBLIC ${COLLIDE_HOST_HEADERS})
add_library(tinyobjloader::tinyobjloader ALIAS collide_tinyobjloader)
