#include "stream/glsl_sources.h"

#include <algorithm>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace passtrace {
namespace {

const GlslFile* findFile(const std::string& name) {
  for (const GlslFile& f : embeddedGlslFiles())
    if (name == f.name) return &f;
  return nullptr;
}

// Appends `name` to `out`, expanding includes depth first. `stack` holds the
// files being expanded (a cycle check); each file is included at most once.
void expand(const std::string& name, AssembledGlsl& out, std::vector<std::string>& stack) {
  if (std::find(stack.begin(), stack.end(), name) != stack.end())
    throw std::runtime_error("GLSL include cycle through " + name);
  if (std::find(out.files.begin(), out.files.end(), name) != out.files.end()) return;
  const GlslFile* file = findFile(name);
  if (!file) throw std::runtime_error("GLSL file not embedded: " + name);
  stack.push_back(name);
  const int number = static_cast<int>(out.files.size());
  out.files.push_back(name);

  static const std::regex includeLine(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  std::istringstream in(file->text);
  std::string line;
  int lineNo = 0;
  out.source += "#line 1 " + std::to_string(number) + "\n";
  while (std::getline(in, line)) {
    ++lineNo;
    std::smatch m;
    if (std::regex_match(line, m, includeLine)) {
      expand(m[1], out, stack);
      out.source += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(number) + "\n";
    } else {
      out.source += line + "\n";
    }
  }
  stack.pop_back();
}

}  // namespace

AssembledGlsl assembleGlsl(const std::string& name, const std::vector<std::string>& defines) {
  AssembledGlsl out;
  out.source = "#version 450 core\n";
  for (const std::string& d : defines) out.source += "#define " + d + "\n";
  std::vector<std::string> stack;
  expand(name, out, stack);
  return out;
}

std::string AssembledGlsl::translateLog(std::string_view log) const {
  // Mesa writes "0:12(5): error: ...", NVIDIA "0(12) : error ...".
  static const std::regex location(R"((\d+):(\d+)\((\d+)\)|(\d+)\((\d+)\))");
  std::string text(log), result;
  auto begin = std::sregex_iterator(text.begin(), text.end(), location);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const bool mesa = m[1].matched;
    const size_t fileNumber = std::stoul(mesa ? m[1].str() : m[4].str());
    result += text.substr(last, m.position() - last);
    if (fileNumber < files.size())
      result += files[fileNumber] + ":" + (mesa ? m[2].str() : m[5].str());
    else
      result += m.str();
    last = m.position() + m.length();
  }
  return result + text.substr(last);
}

}  // namespace passtrace
