# Code that runs once per run (the command line, the JSON report, the catalog,
# scene export, glTF's JSON) and the tests' own code is compiled at -O1 in
# optimised builds: at -O3 it was 40% of a cold build of the program on two
# cores (tinygltf and CLI11 alone 57 s of compiler time; 24 s at -O1) and a
# third of each test file's, for no time a run or the suite can measure.
# Everything that traces, builds or loads geometry keeps the build type's flags.
# -O1 comes after them on the command line, so it wins.
set(PASSTRACE_COLD_OPTIONS $<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-O1>)

# passtrace_cold_sources(FILE ...): these sources of the current folder's targets.
# Not in a unity build (cmake/unity_build.cmake): a file with options of its
# own is compiled apart from its library's unit, parsing every header again,
# which costs more than -O1 saves (the stream library's three cold files:
# 26 s of compiler time apart at -O1, 16 s inside the unit at -O3).
function(passtrace_cold_sources)
  if(NOT PASSTRACE_UNITY_BUILD)
    set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS "${PASSTRACE_COLD_OPTIONS}")
  endif()
endfunction()
