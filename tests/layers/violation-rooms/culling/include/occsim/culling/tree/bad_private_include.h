// A deliberate violation for the test
// layers.include_check_fails_on_a_public_header_including_a_private_one (never compiled): a public
// header is installed, the private ones it would include are not.
#pragma once
#include "culling/tree/tree_builder.h"
