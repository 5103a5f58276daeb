// A deliberate layer violation for the layers.include_check_fails test (never compiled): the
// scenario layer must not include the run layer.
#pragma once

#include "sim/run/runner.h"
