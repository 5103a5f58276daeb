// GLFW loaded at run time: dlopen("libglfw.so.3") and every function occsim calls looked up by
// name, so that the occsim executable does not link libglfw and the headless commands never load
// it (only `occsim view` does). Internal to render/: only the GLFW window code includes this.
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

// X(name) for every GLFW function we call; the header supplies their types (decltype of the
// declaration needs no definition, so nothing here references the library's symbols).
#define OCCSIM_GLFW_FUNCTIONS(X)      \
    X(glfwInit)                       \
    X(glfwTerminate)                  \
    X(glfwGetError)                   \
    X(glfwWindowHint)                 \
    X(glfwCreateWindow)               \
    X(glfwDestroyWindow)              \
    X(glfwMakeContextCurrent)         \
    X(glfwGetProcAddress)             \
    X(glfwSwapBuffers)                \
    X(glfwSwapInterval)               \
    X(glfwPollEvents)                 \
    X(glfwWaitEventsTimeout)          \
    X(glfwWindowShouldClose)          \
    X(glfwSetWindowShouldClose)       \
    X(glfwSetWindowTitle)             \
    X(glfwSetWindowSize)              \
    X(glfwGetFramebufferSize)         \
    X(glfwSetWindowUserPointer)       \
    X(glfwGetWindowUserPointer)       \
    X(glfwSetKeyCallback)             \
    X(glfwSetMouseButtonCallback)     \
    X(glfwSetCursorPosCallback)       \
    X(glfwSetScrollCallback)          \
    X(glfwSetFramebufferSizeCallback) \
    X(glfwSetWindowCloseCallback)

namespace occsim {

struct GlfwLibrary {
#define OCCSIM_GLFW_MEMBER(name) decltype(&::name) name = nullptr;
    OCCSIM_GLFW_FUNCTIONS(OCCSIM_GLFW_MEMBER)
#undef OCCSIM_GLFW_MEMBER
};

// The library, loaded on first use and kept for the life of the process. Throws
// WindowUnavailable (render/glfw_context.h) naming the library when it or a function is missing.
const GlfwLibrary& glfwLibrary();

}  // namespace occsim
