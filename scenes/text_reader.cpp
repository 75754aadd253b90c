#include "scenes/text_reader.h"


#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "scenes/file_bytes.h"
#include "scenes/scene_error.h"
#include "scenes/scene_limits.h"

namespace passtrace {
namespace {


bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

}  // namespace

TextReader::TextReader(const std::filesystem::path& file) : file_(file) {
  data_ = readFileBytes(file, kMaxParsedFileBytes);

  // Lines end at \n, \r\n or a lone \r.
  std::size_t line = 1;
  const char* p = data_.data();
  const char* const end = p + data_.size();
  bool comment = false;
  while (p < end) {
    const char c = *p;
    if (c == '\0') throw SceneError(file, line, "NUL byte: binary data, not a text scene file");
    if (c == '\n' || c == '\r') {
      if (c == '\r' && p + 1 < end && p[1] == '\n') ++p;
      ++p;
      ++line;
      comment = false;
      continue;
    }
    if (isSpace(c) || comment) {
      ++p;
      continue;
    }
    if (c == '#' || c == '%') {
      comment = true;
      continue;
    }
    const char* begin = p;
    while (p < end && !isSpace(*p) && *p != '\0') ++p;
    tokens_.push_back({std::string_view(begin, static_cast<std::size_t>(p - begin)), line});
  }
}

std::size_t TextReader::line() const {
  if (tokens_.empty()) return 1;
  return atEnd() ? tokens_.back().line : tokens_[next_].line;
}

bool TextReader::nextOnSameLine() const {
  return next_ > 0 && !atEnd() && tokens_[next_].line == tokens_[next_ - 1].line;
}

std::string_view TextReader::word(const char* what) {
  if (atEnd()) fail(std::string("unexpected end of file: expected ") + what);
  return tokens_[next_++].text;
}

bool TextReader::isNumber(std::string_view token) {
  if (token.empty()) return false;
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);
  double x = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
  return error != std::errc::invalid_argument && end == digits.data() + digits.size();
}

float TextReader::real(const char* what) {
  const std::string_view token = word(what);
  std::string_view digits = token;
  // from_chars rejects a leading '+'.
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
  double x = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
  if (error == std::errc::result_out_of_range) failAt(tokens_[next_ - 1].line, std::string(what) + ": number out of range " + quoted(token));
  if (error != std::errc{} || end != digits.data() + digits.size())
    failAt(tokens_[next_ - 1].line, std::string("expected ") + what + " (a number), got " + quoted(token));
  if (!std::isfinite(x)) failAt(tokens_[next_ - 1].line, std::string(what) + ": non-finite number " + quoted(token));
  if (std::fabs(x) > std::numeric_limits<float>::max())
    failAt(tokens_[next_ - 1].line, std::string(what) + ": number out of range " + quoted(token));
  return static_cast<float>(x);
}

long long TextReader::integer(const char* what, long long limit) {
  const std::string_view token = word(what);
  long long x = 0;
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
  const std::size_t at = tokens_[next_ - 1].line;
  if (error == std::errc::result_out_of_range) failAt(at, std::string(what) + " out of range " + quoted(token));
  if (error != std::errc{} || end != digits.data() + digits.size())
    failAt(at, std::string("expected ") + what + " (an integer), got " + quoted(token));
  if (x < 0) failAt(at, std::string(what) + " is negative (" + std::to_string(x) + ")");
  if (x > limit) failAt(at, std::string(what) + " " + std::to_string(x) + " out of range (at most " + std::to_string(limit) + ")");
  return x;
}

std::size_t TextReader::count(const char* what, std::size_t tokensPerItem) {
  const long long n = integer(what, std::numeric_limits<long long>::max());
  const std::size_t at = tokens_[next_ - 1].line;
  const std::size_t room = remaining() / (tokensPerItem == 0 ? 1 : tokensPerItem);
  if (static_cast<unsigned long long>(n) > room)
    failAt(at, std::string(what) + " " + std::to_string(n) + " is more than the rest of the file holds (room for at most " +
                   std::to_string(room) + ")");
  return static_cast<std::size_t>(n);
}

void TextReader::expect(std::string_view token, const std::string& context) {
  if (atEnd()) fail("unexpected end of file: expected '" + std::string(token) + "' " + context);
  if (peek() != token) fail("expected '" + std::string(token) + "' " + context + ", got " + quoted(peek()));
  ++next_;
}

void TextReader::fail(const std::string& reason) const { throw SceneError(file_, line(), reason); }
void TextReader::failAt(std::size_t at, const std::string& reason) const { throw SceneError(file_, at, reason); }

std::string TextReader::quoted(std::string_view token) {
  std::string out = "'";
  for (char c : token.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out + (token.size() > 40 ? "...'" : "'");
}

}  // namespace passtrace
