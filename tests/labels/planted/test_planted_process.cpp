// A planted test source for the label check: it starts a process through a header of its folder.
// Never compiled.
#include "planted_helper.h"
int plantedRun() { return run("occsim --version"); }
