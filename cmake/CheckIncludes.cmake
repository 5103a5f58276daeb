# Fails when a file includes a header from a layer above its own (docs/architecture.md), or,
# inside culling/, from a room its room may not include, or a private header where it may not.
# Run as a script: cmake -DSOURCE_DIR=<repository root> -P cmake/CheckIncludes.cmake
#
# Each folder may include headers from the folders listed for it (its own layer and those below).
# Culling's public headers are included as occsim/culling/... (culling/include/occsim/culling/,
# their installed names); its private headers as culling/<room>/..., from inside culling/ only.
# render/mesh_data.h is plain CPU data (the occsim_mesh_data interface target), so the scene and
# world layers may include it without depending on OpenGL.
cmake_policy(VERSION 3.25)  # a script: IN_LIST and the other policies of today
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckIncludes.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

set(layers render sim/scenario sim/scene sim/world sim/run sim/output sim/record sim/regress sim/view sim/commands tune)
set(allowed_render occsim/culling render)
set(allowed_sim/scenario occsim/culling sim/scenario)
set(allowed_sim/scene occsim/culling render/mesh_data.h sim/scenario sim/scene)
set(allowed_sim/world occsim/culling render/mesh_data.h sim/scenario sim/scene sim/world)
set(allowed_sim/run occsim/culling render sim/scenario sim/scene sim/world sim/run)
set(allowed_sim/output occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output)
set(allowed_sim/record occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/record)
set(allowed_sim/regress occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/record sim/regress)
set(allowed_sim/view occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/view)
# The occsim executable's commands, above every sim layer.
set(allowed_sim/commands occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output sim/record sim/regress sim/view sim/commands)
set(allowed_tune occsim/culling render sim/scenario sim/scene sim/world sim/run sim/output tune)

# The rooms of culling/, each with the rooms its files may include (its own and those below). A
# file's room is its folder: culling/<room>/ (the .cpp files and private headers) or
# culling/include/occsim/culling/<room>/ (public headers); occsim/culling/plugin.h, the plugin
# header, is the room `plugin`. The registry reaches the cullers only through the declarations of
# their registration functions (registry/builtin_cullers.cpp), never by an include.
set(rooms geometry contract tree devices declaration raster cullers plugin registry testing)
set(room_geometry geometry)
set(room_contract geometry contract)
set(room_tree geometry contract tree)
set(room_devices geometry contract devices)
set(room_declaration geometry contract declaration)
set(room_raster geometry raster)
set(room_cullers geometry contract tree declaration raster cullers)
set(room_plugin geometry contract tree declaration plugin)
set(room_registry geometry contract devices declaration plugin registry)
set(room_testing geometry contract raster testing)

set(violations "")

# The room a repository path inside culling/ belongs to ("" when in none), and whether it is a
# public header.
function(culling_room path out_room out_public)
  set(public FALSE)
  if(path MATCHES "^culling/include/occsim/culling/(.*)$")
    set(rest ${CMAKE_MATCH_1})
    set(public TRUE)
  elseif(path MATCHES "^culling/(.*)$")
    set(rest ${CMAKE_MATCH_1})
  endif()
  set(room "")
  if(rest STREQUAL "plugin.h" AND public)
    set(room plugin)
  elseif(rest MATCHES "^([^/]+)/")
    set(room ${CMAKE_MATCH_1})
  endif()
  set(${out_room} "${room}" PARENT_SCOPE)
  set(${out_public} ${public} PARENT_SCOPE)
endfunction()

# The quoted includes of a file.
function(quoted_includes file out)
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]+\"[^\"]+\"")
  set(headers "")
  foreach(line ${lines})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    list(APPEND headers "${header}")
  endforeach()
  set(${out} "${headers}" PARENT_SCOPE)
endfunction()

# The layers outside culling/: public culling headers only (occsim/culling/...), never its
# private ones (culling/...), which no allowed list names.
foreach(layer ${layers})
  file(GLOB_RECURSE files "${SOURCE_DIR}/${layer}/*.h" "${SOURCE_DIR}/${layer}/*.cpp")
  foreach(file ${files})
    quoted_includes("${file}" headers)
    foreach(header ${headers})
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
      if(header MATCHES "^occsim/culling/testing/")
        set(ok FALSE)
      endif()
      if(NOT ok)
        file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
        if(header MATCHES "^culling/")
          list(APPEND violations "${relative}: includes \"${header}\", a private culling header")
        else()
          list(APPEND violations "${relative}: includes \"${header}\", above its layer ${layer}")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

# culling/, room by room.
file(GLOB_RECURSE files "${SOURCE_DIR}/culling/*.h" "${SOURCE_DIR}/culling/*.cpp")
foreach(file ${files})
  file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
  culling_room("${relative}" room public)
  if(NOT room IN_LIST rooms)
    list(APPEND violations "${relative}: in no room of culling/ (give its folder a list in cmake/CheckIncludes.cmake)")
    continue()
  endif()
  quoted_includes("${file}" headers)
  foreach(header ${headers})
    if(NOT header MATCHES "/")
      continue()  # beside the file itself: its own room
    endif()
    set(target "")
    set(private FALSE)
    if(header MATCHES "^occsim/culling/")
      culling_room("culling/include/${header}" target ignored)
    elseif(header MATCHES "^culling/")
      culling_room("${header}" target ignored)
      set(private TRUE)
    endif()
    if(target STREQUAL "")
      list(APPEND violations "${relative}: includes \"${header}\", outside the culling library")
    elseif(private AND public)
      list(APPEND violations "${relative}: a public header includes the private \"${header}\"")
    elseif(NOT target IN_LIST room_${room})
      list(JOIN room_${room} " " may)
      string(CONCAT why "${relative}: includes \"${header}\", from room ${target}, which room "
                        "${room} may not include (only ${may})")
      list(APPEND violations "${why}")
    endif()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layer violations:\n  ${text}")
endif()
message(STATUS "includes: every file includes only its own layer and the layers below, every "
               "culling file only its own room and the rooms below")
