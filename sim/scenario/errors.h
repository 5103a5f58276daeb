// The errors that mean "bad input": each carries one line naming the file (and, for scenario
// files, the JSON pointer) and what was expected. Commands turn them into exit code 2.
#pragma once

#include <stdexcept>
#include <string>

#include "occsim/culling/contract/input_error.h"

namespace occsim {

// One line: "<file>: <json pointer>: <what was expected>", or "<file>: <what went wrong>" for
// errors about the file as a whole (cannot open it, not JSON), which have no pointer.
class ScenarioError : public InputError {
  public:
    ScenarioError(const std::string& file, const std::string& pointer, const std::string& message)
        : InputError(file + ": " + (pointer.empty() ? "" : pointer + ": ") + message) {}
};

// A glTF file that cannot be used: one line naming the file and tinygltf's (or our) reason.
class GltfError : public InputError {
  public:
    using InputError::InputError;
};

// A Masked Occlusion Culling recording (.mocrec) that cannot be read: one line naming the file,
// the byte offset and what was expected there (sim/scene/mocrec.h).
class MocrecError : public InputError {
  public:
    using InputError::InputError;
};

}  // namespace occsim
