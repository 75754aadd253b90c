#include "scenes/assimp_index_watch.h"

#include <array>
#include <string_view>

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

namespace passtrace {

struct AssimpIndexWatch::Listener : Assimp::LogStream {
  std::string finding;

  void write(const char* message) override {
    // Assimp 5.2's wording; tests/unit/assimp_index_test.cpp fails if it changes.
    static constexpr std::array<std::string_view, 2> kOutOfRange = {"Vertex index overflow",
                                                                    "polygon vertex index out of range"};
    const std::string_view text(message);
    if (!finding.empty()) return;
    for (std::string_view needle : kOutOfRange)
      if (text.find(needle) != std::string_view::npos) {
        std::string_view reason = text;
        if (const std::size_t colon = reason.find(": "); colon != std::string_view::npos) reason.remove_prefix(colon + 2);
        while (!reason.empty() && (reason.back() == '\n' || reason.back() == ')')) reason.remove_suffix(1);
        finding = std::string(reason);
      }
  }
};

AssimpIndexWatch::AssimpIndexWatch() : listener_(std::make_unique<Listener>()) {
  if (Assimp::DefaultLogger::isNullLogger()) {
    Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    ownsLogger_ = true;
  }
  Assimp::DefaultLogger::get()->attachStream(listener_.get(), Assimp::Logger::Warn | Assimp::Logger::Err);
}

AssimpIndexWatch::~AssimpIndexWatch() {
  Assimp::DefaultLogger::get()->detachStream(listener_.get(), Assimp::Logger::Warn | Assimp::Logger::Err);
  if (ownsLogger_) Assimp::DefaultLogger::kill();
}

const std::string& AssimpIndexWatch::finding() const { return listener_->finding; }

}  // namespace passtrace
