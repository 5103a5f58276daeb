// Loading GL entry points, declared without any GL header so that window-system code (osmesa.h,
// GLFW), which brings its own GL headers, can call it.
#pragma once

#include <string>

namespace occsim {

using GlProcLoader = void* (*)(const char* name);

// Loads every entry point of gl_api.h through `loader` for the current context. Returns false and
// names the first missing function in *error.
bool loadGlFunctions(GlProcLoader loader, std::string* error);

// "renderer, OpenGL version" of the current context.
std::string glRendererDescription();

}  // namespace occsim
