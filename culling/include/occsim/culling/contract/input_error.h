// Bad input: a file, a flag, a plugin or an environment that a command was given and that does not
// meet what it is read as. Every error that bad input causes derives from InputError, whichever
// module finds it, so that each executable catches it once and ends with its one line on stderr
// and exit code 2. Everything else that goes wrong while running (OpenGL, writing outputs) is
// another exception, exit code 1. It lives here, at the bottom, because the registry and the
// plugin loader find bad input too and may include nothing above culling/.
#pragma once

#include <stdexcept>
#include <string>

namespace occsim {

// what() is one line: "<flag or file>[: <JSON pointer>]: <what was expected>[, got ...]".
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The same error named by the flag that gave its file: "--plugin x.so: ..." from "x.so: ...".
inline InputError givenBy(const std::string& flag, const std::exception& e) {
    return InputError(flag + " " + e.what());
}

}  // namespace occsim
