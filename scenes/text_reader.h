#pragma once
// A whitespace tokenizer with line tracking for line-oriented ASCII scene
// formats (NFF, AFF). The whole file is read up front; tokens remember their
// line so every error can say "FILE:LINE: reason". A token starting with '#'
// or '%' begins a comment that runs to the end of its line.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace passtrace {

class TextReader {
 public:
  // Throws SceneError when the file cannot be opened, is not a regular file,
  // is larger than 1 GiB or contains a NUL byte.
  explicit TextReader(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  bool atEnd() const { return next_ >= tokens_.size(); }
  std::size_t remaining() const { return tokens_.size() - next_; }

  // The next token without consuming it ("" at the end).
  std::string_view peek() const { return atEnd() ? std::string_view{} : tokens_[next_].text; }
  // The line of the next token, or of the last one at the end of the file.
  std::size_t line() const;
  // True when the next token sits on the line of the token consumed last.
  bool nextOnSameLine() const;
  // The line of the token consumed last (1 before any).
  std::size_t lastLine() const { return next_ == 0 ? 1 : tokens_[next_ - 1].line; }

  // Consumes a token; `what` names it in the error at the end of the file.
  std::string_view word(const char* what);
  // A finite number that fits a float.
  float real(const char* what);
  // An integer in [0, limit].
  long long integer(const char* what, long long limit);
  // An element count whose elements take at least `tokensPerItem` tokens
  // each: more than the rest of the file holds is refused before anything is
  // allocated for it.
  std::size_t count(const char* what, std::size_t tokensPerItem);
  // Consumes the given token or fails naming what was found.
  void expect(std::string_view token, const std::string& context);

  [[noreturn]] void fail(const std::string& reason) const;
  [[noreturn]] void failAt(std::size_t line, const std::string& reason) const;

  static bool isNumber(std::string_view token);
  // A token fit for an error message: short and printable, in quotes.
  static std::string quoted(std::string_view token);

 private:
  struct Token {
    std::string_view text;
    std::size_t line;
  };
  std::filesystem::path file_;
  std::string data_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

}  // namespace passtrace
