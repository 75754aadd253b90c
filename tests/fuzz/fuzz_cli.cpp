// libFuzzer target: the passtrace command line through parseOptions
// (apps/cli_options.h). The bytes are argv words separated by NUL or newline.
// parseOptions never exits the process: --help prints and returns -1, and
// every bad command line throws std::runtime_error (main prints it as one
// line). Any other exception escapes and is reported as a crash, and so is a
// successful parse that leaves an option outside its documented range.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

#include "tests/fuzz/cli_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::cout.setstate(std::ios::badbit);  // --help output is of no interest here
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace passtrace;
  Options options;
  std::string problem;
  try {
    if (fuzz::parseWords(fuzz::splitArguments({reinterpret_cast<const char*>(data), size}), options) == 0)
      problem = fuzz::optionsProblem(options);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) problem = "error message spans lines";
  }
  if (!problem.empty()) {
    std::fprintf(stderr, "passtrace fuzz: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
