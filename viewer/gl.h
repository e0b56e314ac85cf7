// OpenGL 3.3 core through libGL's own entry points: Mesa's libGL exports every 3.3 function, so
// the viewer needs no loader (GLAD/GLEW) and GLFW must not include another GL header.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
