// A planted helper for the label check: it starts a shell. Never compiled.
#include <cstdio>
inline int run(const char* command) { return pclose(popen(command, "r")); }
