# Fails when a file includes a header from a layer above its own (docs/architecture.md).
# Run as a script: cmake -DSOURCE_DIR=<repository root> -P cmake/CheckIncludes.cmake
#
# Each folder may include headers from the folders listed for it (its own layer and those below).
# Culling headers are included as occsim/culling/... (their installed names).
# render/mesh_data.h is plain CPU data (the occsim_mesh_data interface target), so the scene and
# world layers may include it without depending on OpenGL.
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckIncludes.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

set(layers culling render sim/scenario sim/scene sim/world sim/run sim/output sim/regress sim/view sim/commands tune)
set(allowed_culling occsim/culling)
set(allowed_render occsim/culling render)
set(allowed_sim/scenario occsim/culling sim/scenario)
set(allowed_sim/scene occsim/culling render/mesh_data.h sim/scenario sim/scene)
set(allowed_sim/world occsim/culling render/mesh_data.h sim/scenario sim/scene sim/world)
set(allowed_sim/run occsim/culling render sim/scenario sim/scene sim/world sim/run)
set(allowed_sim/output occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output)
set(allowed_sim/regress occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/regress)
set(allowed_sim/view occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/view)
# The occsim executable's commands, above every sim layer.
set(allowed_sim/commands occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/regress sim/view sim/commands)
set(allowed_tune occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output tune)

set(violations "")
foreach(layer ${layers})
  file(GLOB_RECURSE files "${SOURCE_DIR}/${layer}/*.h" "${SOURCE_DIR}/${layer}/*.cpp")
  foreach(file ${files})
    file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"[^\"]+\"")
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
      set(ok FALSE)
      foreach(prefix ${allowed_${layer}})
        string(FIND "${header}" "${prefix}" at)
        if(at EQUAL 0)
          set(ok TRUE)
        endif()
      endforeach()
      # Includes relative to the file itself (no folder) stay within its layer.
      if(NOT header MATCHES "/")
        set(ok TRUE)
      endif()
      # The CPU test devices are a library of their own, for tests: production code never
      # includes them.
      string(FIND "${header}" "occsim/culling/testing/" testing_at)
      string(FIND "${file}" "${SOURCE_DIR}/culling/testing/" in_testing)
      if(testing_at EQUAL 0 AND NOT in_testing EQUAL 0)
        set(ok FALSE)
      endif()
      if(NOT ok)
        file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
        list(APPEND violations "${relative}: includes \"${header}\", above its layer ${layer}")
      endif()
    endforeach()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layer violations:\n  ${text}")
endif()
message(STATUS "includes: every file includes only its own layer and the layers below")
