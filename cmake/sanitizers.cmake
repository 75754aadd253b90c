# PASSTRACE_SANITIZE=ON builds every target (library, CLI, tests) with
# AddressSanitizer (+ LeakSanitizer) and UndefinedBehaviorSanitizer.
# scripts/sanitize.sh configures such a build in build-asan/ and runs the suite
# with the runtime options and leak suppressions it needs.
option(PASSTRACE_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)

# Per-test time limit (tests/CMakeLists.txt). Sanitized code runs about 5x
# slower: the CLI tests' brute-force references take minutes there.
set(PASSTRACE_TEST_TIMEOUT 300)

if(PASSTRACE_SANITIZE)
  # -fno-sanitize-recover=all: an undefined-behaviour report ends the process,
  # so a test cannot pass over it. -O1 builds faster than -O2 and runs about as
  # fast under ASan; it comes after the build type's flags on the command line,
  # so it wins over theirs. Line tables (-g1) and frame pointers keep stack
  # traces readable at a fraction of full debug information's compile time.
  set(PASSTRACE_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${PASSTRACE_SANITIZE_FLAGS} -O1 -g1)
  # GCC 12 warns falsely inside <regex> (std::function in _StateT) once ASan
  # instruments it; a release build still reports real ones.
  add_compile_options(-Wno-maybe-uninitialized)
  add_link_options(${PASSTRACE_SANITIZE_FLAGS})
  set(PASSTRACE_TEST_TIMEOUT 1200)
endif()
