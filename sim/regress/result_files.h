// The error every reader of a regression result file throws: a shard's shard.json or junit.xml,
// a history entry. Its message is one line naming the file, the place and what was expected; the
// command line prints it and exits with status 2.
#pragma once

#include "occsim/culling/contract/input_error.h"

namespace occsim {

class ResultFileError : public InputError {
  public:
    using InputError::InputError;
};

}  // namespace occsim
