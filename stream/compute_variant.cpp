#include "stream/compute_variant.h"

#include <regex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace passtrace {

std::string computeVariant(std::string source) {
  if (std::regex_search(source, std::regex(R"(\bdiscard\s*;)")))
    throw std::invalid_argument("the kernel discards fragments, which its compute variant cannot express");
  source = std::regex_replace(source, std::regex(R"(\bgl_FragCoord\b)"), "fragCoord_");
  source = std::regex_replace(source, std::regex(R"(\bgl_HelperInvocation\b)"), "false");
  source = std::regex_replace(source, std::regex(R"(layout\s*\(\s*early_fragment_tests\s*\)\s*in\s*;)"), "");
  // After "#version": the next line is an assembled file's #line, so driver
  // logs still name the kernel's own files and lines.
  source.insert(source.find('\n') + 1, "vec4 fragCoord_;\n");

  std::vector<std::pair<std::string, std::string>> outputs;  // image unit, name
  const std::regex output(R"(layout\s*\(\s*location\s*=\s*(\d+)\s*\)\s*out\s+vec4\s+(\w+)\s*;)");
  for (std::sregex_iterator it(source.begin(), source.end(), output), end; it != end; ++it)
    outputs.emplace_back((*it)[1], (*it)[2]);
  source = std::regex_replace(source, output, "vec4 $2;");
  source = std::regex_replace(source, std::regex(R"(\bvoid\s+main\s*\(\s*\))"), "void fragmentMain_()");

  const std::string group = std::to_string(kComputeGroupSize);
  source += "\nlayout(local_size_x = " + group + ", local_size_y = " + group + ") in;\nuniform uvec2 uComputeSize_;\n";
  for (const auto& [unit, name] : outputs)
    source += "layout(rgba32f, binding = " + unit + ") uniform writeonly image2D " + name + "Image_;\n";
  source +=
      "void main() {\n"
      "  if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uComputeSize_))) return;\n"
      "  fragCoord_ = vec4(vec2(gl_GlobalInvocationID.xy) + 0.5, 0.5, 1.0);\n"
      "  fragmentMain_();\n";
  for (const auto& [unit, name] : outputs)
    source += "  imageStore(" + name + "Image_, ivec2(gl_GlobalInvocationID.xy), " + name + ");\n";
  return source + "}\n";
}

}  // namespace passtrace
