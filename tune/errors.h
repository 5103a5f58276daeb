// The tuner's errors by cause. Bad input (flags, bounds, a sample log that does not match the
// command) is a TuneInputError: one line, exit code 2, before any run. An interrupted run is
// Interrupted: the sample log stays whole, nothing else is written.
#pragma once

#include <stdexcept>
#include <string>

#include "occsim/culling/contract/input_error.h"

namespace occsim::tune {

class TuneInputError : public InputError {
  public:
    using InputError::InputError;
};

// Thrown between frames (outside every timing) when SIGINT arrived.
class Interrupted : public std::runtime_error {
  public:
    Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace occsim::tune
