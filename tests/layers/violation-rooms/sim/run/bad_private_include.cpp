// A deliberate violation for the test layers.include_check_fails_on_a_private_culling_include
// (never compiled): outside culling/, only its public headers (occsim/culling/...) are included.
#include "culling/cullers/chc_culler.h"
