// Checked GL calls on the query path: in debug builds OCCSIM_GL_CHECKED(call) runs the call, asks
// glGetError() and, on an error, reports it with the call's text and aborts (a GL error there is a
// bug: a query begun twice, a deleted query object, a result asked for before it was issued). In
// release builds the macro is the bare call, so the measured figures pay nothing for it.
#pragma once

#include <string>

#include "render/gl_api.h"

namespace occsim {

// The GL error pending after `call` ran, as one line naming the call and the error (e.g.
// "glEndQuery(GL_SAMPLES_PASSED): GL_INVALID_OPERATION (0x502)"), or "" when there is none.
// Clears the error it reports. Built in every build, so a test can check the message.
std::string glErrorAfter(const char* call);

// Reports glErrorAfter(call) on stderr and aborts when it is not empty.
void checkGlCall(const char* call);

}  // namespace occsim

#ifdef NDEBUG
#define OCCSIM_GL_CHECKED(call) call
#else
#define OCCSIM_GL_CHECKED(call)       \
    do {                              \
        call;                         \
        ::occsim::checkGlCall(#call); \
    } while (0)
#endif
