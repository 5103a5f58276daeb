// A planted test source for the label check (cmake/CheckTestLabels.cmake): nothing it does
// starts a process, although its comments say popen and std::filesystem. Never compiled.
#include <filesystem>
int planted() { return 0; }
