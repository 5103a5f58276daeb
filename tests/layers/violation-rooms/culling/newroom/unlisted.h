// A deliberate violation for the test layers.include_check_fails_on_a_room_without_a_list (never
// compiled): a new folder of culling/ is a room only once the include check gives it its list.
#pragma once
