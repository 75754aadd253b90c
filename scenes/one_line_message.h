#pragma once
// Error messages are one line ("FILE:LINE: reason" or "FILE: reason"), so a
// command-line tool can print them as they are and editors can jump to the
// line. Third-party messages (tinyobjloader's, OpenEXR's, OpenImageIO's) may
// end in or contain newlines: this folds them into one.

#include <string>
#include <string_view>

namespace passtrace {

// `message` with its trailing line breaks dropped and the others made
// spaces; `ifEmpty` when nothing is left.
inline std::string oneLineMessage(std::string message, std::string_view ifEmpty = {}) {
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message.empty() ? std::string(ifEmpty) : message;
}

}  // namespace passtrace
