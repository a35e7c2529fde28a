// OpenGL 3.3 core entry points for the sandbox's own drawing.
//
// Why direct calls through GL_GLEXT_PROTOTYPES and no loader: on Linux, libGL (glvnd) exports every
// OpenGL entry point up to 4.6 and dispatches each call to the vendor library of the context that
// is current, so after SDL has made a 3.3 core context current, calling glCreateShader directly is
// valid; a loader (a table of SDL_GL_GetProcAddress pointers) would add code and a startup step
// for nothing on the platforms the project ships (Debian). Dear ImGui's OpenGL3 backend keeps its
// own loader for its own calls. A Windows port would need a loader here.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
