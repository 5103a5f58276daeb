// The one source of occsim_test_pch (tests/CMakeLists.txt): the target exists to compile
// googletest's header once for every test executable, which reuse it (REUSE_FROM).
