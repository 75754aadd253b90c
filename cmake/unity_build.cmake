# Unity builds of the libraries: each library's sources compiled as one
# translation unit, so the headers (the standard library, GLM, oneTBB,
# nlohmann/json, the project's own) are parsed once per library instead of
# once per file; parsing was most of each file's compile. Measured on two
# cores, a cold build of the program (fresh build directory, no ccache,
# Ninja): 2 min 28 s in batches of 8, 2 min 14 s in batches of 16, 1 min 54 s
# with one unit per library, 1 min 34 s with the -O1 cold code inside the
# unit too (cold_code.cmake); 3 min 49 s before unity builds, with Make. One
# unit per library also makes a clash between two files' internal names show
# at once, whatever files are added later.
# Files that must be units of their own are excluded where they are listed:
# the two builds of the wide BVH's traversal loop (accel/CMakeLists.txt),
# tinygltf's implementation (scenes/CMakeLists.txt). Tests and the Python
# module keep one file per unit: their helpers repeat names from file to file.
# Editing one file recompiles its whole library (about 45 s for accel/): for
# that work, configure with -DPASSTRACE_UNITY_BATCH_SIZE=8, or
# -DPASSTRACE_UNITY_BUILD=OFF (file by file, as ccache likes best).
option(PASSTRACE_UNITY_BUILD "compile each library's sources as one unit (or in batches)" ON)
set(PASSTRACE_UNITY_BATCH_SIZE 0 CACHE STRING "sources per unity batch (0: the whole library)")

# passtrace_unity(TARGET): TARGET's sources in unity batches when the option is on.
function(passtrace_unity target)
  if(PASSTRACE_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${PASSTRACE_UNITY_BATCH_SIZE})
  endif()
endfunction()
