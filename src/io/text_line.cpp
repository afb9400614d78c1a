#include "io/text_line.h"

#include <array>
#include <charconv>

namespace liftmap {

void TextLine::separate() {
  if (!text_.empty()) text_ += ' ';
}

TextLine& TextLine::add(double x) {
  separate();
  std::array<char, 32> buffer{};  // the shortest round-trip form of a double takes at most 24 characters
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x).ptr;
  text_.append(buffer.data(), end);
  return *this;
}

TextLine& TextLine::add(long long x) {
  separate();
  std::array<char, 24> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x).ptr;
  text_.append(buffer.data(), end);
  return *this;
}

TextLine& TextLine::add(int x) { return add(static_cast<long long>(x)); }

TextLine& TextLine::add(std::string_view word) {
  separate();
  text_ += word;
  return *this;
}

void TextLine::write_to(std::FILE* f) {
  text_ += '\n';
  std::fwrite(text_.data(), 1, text_.size(), f);
  text_.clear();
}

}  // namespace liftmap
