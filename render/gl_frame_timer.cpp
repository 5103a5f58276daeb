#include "render/gl_frame_timer.h"

#include <stdexcept>

#include "render/gl_api.h"

namespace occsim {

GlFrameTimer::GlFrameTimer() {
    GLuint q = 0;
    glGenQueries(1, &q);
    query_ = q;
    checkGl("timer query set-up");
}

GlFrameTimer::~GlFrameTimer() {
    GLuint q = query_;
    glDeleteQueries(1, &q);
}

void GlFrameTimer::begin() {
    glBeginQuery(GL_TIME_ELAPSED, query_);
    running_ = true;
}

void GlFrameTimer::end() {
    glEndQuery(GL_TIME_ELAPSED);
    running_ = false;
}

double GlFrameTimer::resultMs() {
    if (running_) throw std::logic_error("GlFrameTimer::resultMs: the timer is still running");
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
    return static_cast<double>(ns) * 1e-6;
}

}  // namespace occsim
