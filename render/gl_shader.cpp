#include "render/gl_shader.h"

#include <stdexcept>
#include <vector>

namespace occsim {
namespace {

GLuint compileStage(const ShaderStage& stage, const std::string& what) {
    const GLuint shader = glCreateShader(stage.first);
    glShaderSource(shader, 1, &stage.second, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[1024] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(what + ": shader compile failed: " + log);
    }
    return shader;
}

}  // namespace

GLuint linkProgram(std::initializer_list<ShaderStage> stages, const std::string& what) {
    std::vector<GLuint> shaders;
    try {
        for (const ShaderStage& stage : stages) shaders.push_back(compileStage(stage, what));
    } catch (...) {
        for (const GLuint s : shaders) glDeleteShader(s);
        throw;
    }
    const GLuint program = glCreateProgram();
    for (const GLuint s : shaders) glAttachShader(program, s);
    glLinkProgram(program);
    for (const GLuint s : shaders) glDeleteShader(s);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[1024] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(what + ": shader link failed: " + log);
    }
    return program;
}

}  // namespace occsim
