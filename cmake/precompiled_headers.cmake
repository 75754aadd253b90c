# Precompiled headers: the compiler's front end (the standard library, GLM,
# nlohmann/json, oneTBB) is about half of each Release compile here, so each
# target parses these once instead of once per source file. It halves a cold
# build of the program on two cores (README: "the first image").
# -DPASSTRACE_PRECOMPILED_HEADERS=OFF builds without them.
option(PASSTRACE_PRECOMPILED_HEADERS "parse the common headers once per target" ON)

set(PASSTRACE_COMMON_HEADERS
  <algorithm> <array> <chrono> <cmath> <cstddef> <cstdint> <cstring> <filesystem> <functional> <limits>
  <map> <memory> <optional> <span> <stdexcept> <string> <string_view> <utility> <vector>
  <glm/glm.hpp>)

# passtrace_precompile(TARGET [HEADER ...]): the common headers and the
# target's own heavy ones (given as <name>).
function(passtrace_precompile target)
  if(PASSTRACE_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${PASSTRACE_COMMON_HEADERS} ${ARGN})
  endif()
endfunction()
