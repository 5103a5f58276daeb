// GLSL programs from their stages' sources: the one place that compiles, links and turns the
// driver's log into an error (std::runtime_error naming what was built). Needs a current context.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>

#include "render/gl_api.h"

namespace occsim {

// One stage: its type (GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER) and source.
using ShaderStage = std::pair<GLenum, const char*>;

// The linked program of these stages. Throws std::runtime_error "<what>: shader compile failed:
// <log>" or "<what>: shader link failed: <log>", deleting what it made first.
GLuint linkProgram(std::initializer_list<ShaderStage> stages, const std::string& what);

}  // namespace occsim
