// A deliberate room violation for the test
// layers.include_check_fails_on_a_culler_calling_the_registry (never compiled): a culler fills in
// its row (declaration/), it never reaches the host's registry.
#include "occsim/culling/registry/registry.h"
