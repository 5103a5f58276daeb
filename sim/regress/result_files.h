// The error every reader of a regression result file throws: a shard's shard.json or junit.xml,
// a history entry. Its message is one line naming the file, the place and what was expected; the
// command line prints it and exits with status 2.
#pragma once

#include <stdexcept>

namespace occsim {

class ResultFileError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace occsim
