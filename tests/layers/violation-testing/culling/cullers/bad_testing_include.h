// A deliberate violation for the test layers.include_check_fails_on_a_testing_include: production
// culling code must not include the CPU test devices.
#pragma once
#include "occsim/culling/testing/scripted_query_device.h"
