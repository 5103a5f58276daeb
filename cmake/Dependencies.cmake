# Every dependency comes from a Debian 12 package (scripts/setup.sh installs them) through its
# CMake config or pkg-config. Nothing is downloaded at configure time.
find_package(PkgConfig REQUIRED)
find_package(glm CONFIG REQUIRED)                 # libglm-dev
find_package(nlohmann_json 3.10 CONFIG REQUIRED)  # nlohmann-json3-dev
find_package(CLI11 CONFIG REQUIRED)               # libcli11-dev
find_package(TinyGLTF CONFIG REQUIRED)            # libtinygltf-dev
find_package(Threads REQUIRED)
find_package(SQLite3 REQUIRED)                    # libsqlite3-dev: objects.sqlite (sim/record/)
find_package(meshoptimizer CONFIG REQUIRED)       # libmeshoptimizer-dev: occluder meshes (sim/scene/)
# EGL is opened with dlopen at run time (render/egl_context.cpp); only its headers are needed here.
find_path(EGL_INCLUDE_DIR EGL/egl.h REQUIRED)               # libegl-dev
# OSMesa is optional (Mesa removed it in 25.1): AUTO uses it when installed, ON requires it, OFF
# builds without it (the no-osmesa preset). OCCSIM_HAVE_OSMESA tells the result.
if(OCCSIM_WITH_OSMESA STREQUAL "OFF")
  set(OCCSIM_HAVE_OSMESA OFF)
else()
  if(OCCSIM_WITH_OSMESA STREQUAL "ON")
    pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)   # libosmesa6-dev
  else()
    pkg_check_modules(OSMESA QUIET IMPORTED_TARGET osmesa)
  endif()
  set(OCCSIM_HAVE_OSMESA ${OSMESA_FOUND})
endif()
if(OCCSIM_HAVE_OSMESA)
  message(STATUS "occsim: headless backends: EGL and OSMesa")
else()
  message(STATUS "occsim: headless backends: EGL (no OSMesa)")
endif()
pkg_check_modules(GLFW3 REQUIRED IMPORTED_TARGET glfw3)     # libglfw3-dev: the header only (render/)

# stb (libstb-dev) ships headers and a shared library; we only use stb_image_write's header.
find_path(STB_INCLUDE_DIR stb/stb_image_write.h REQUIRED)

if(OCCSIM_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)             # libgtest-dev, libgmock-dev
endif()
if(OCCSIM_BUILD_BENCHMARKS)
  find_package(benchmark CONFIG REQUIRED)         # libbenchmark-dev
endif()
