# Precompiled headers: the compiler's front end (the standard library, GLM,
# nlohmann/json, oneTBB) is about half of each Release compile here, so each
# target parses these once instead of once per source file: it halved a
# file-by-file build. The libraries are unity builds now (unity_build.cmake),
# so it serves the tests, the Python module, and the libraries built with
# -DPASSTRACE_UNITY_BUILD=OFF.
# -DPASSTRACE_PRECOMPILED_HEADERS=OFF builds without them.
option(PASSTRACE_PRECOMPILED_HEADERS "parse the common headers once per target" ON)

set(PASSTRACE_COMMON_HEADERS
  <algorithm> <array> <chrono> <cmath> <cstddef> <cstdint> <cstring> <filesystem> <functional> <limits>
  <map> <memory> <optional> <span> <stdexcept> <string> <string_view> <utility> <vector>
  <glm/glm.hpp>)

# passtrace_precompile(TARGET [HEADER ...]): the common headers and the
# target's own heavy ones (given as <name>). Not for a target built as one
# unit (passtrace_unity(), called first): it parses its headers once anyway,
# and the precompiled header only added its own compile (a cold build of the
# program took 2 min 7 s with them, 1 min 54 s without).
function(passtrace_precompile target)
  get_target_property(unity ${target} UNITY_BUILD)
  if(PASSTRACE_PRECOMPILED_HEADERS AND NOT unity)
    target_precompile_headers(${target} PRIVATE ${PASSTRACE_COMMON_HEADERS} ${ARGN})
  endif()
endfunction()
