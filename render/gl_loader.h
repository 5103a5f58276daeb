// Loading GL entry points, declared without any GL header so that window-system code (osmesa.h,
// GLFW), which brings its own GL headers, can call it.
#pragma once

#include <functional>
#include <string>

namespace occsim {

// Returns the address of a GL entry point for the current context, or null. A std::function
// rather than a plain function pointer: a window system loaded at run time (GLFW through dlopen)
// only has its glfwGetProcAddress as a value, which the loader must capture.
using GlProcLoader = std::function<void*(const char* name)>;

// Loads every entry point of gl_api.h through `loader` for the current context. Returns false and
// names the first missing function in *error.
bool loadGlFunctions(const GlProcLoader& loader, std::string* error);

// "renderer, OpenGL version" of the current context.
std::string glRendererDescription();

}  // namespace occsim
