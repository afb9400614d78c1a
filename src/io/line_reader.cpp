#include "io/line_reader.h"

#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "io/input_file.h"

namespace liftmap {

std::string read_file(const std::string& path, const std::string& what) {
  std::ifstream in = open_input_file(path, what);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError(path + ": read error");
  return ss.str();
}

LineReader::LineReader(const std::string& path, const std::string& text, bool hash_comments)
    : path_(path), text_(text), hash_comments_(hash_comments) {
  if (text_.rfind(kByteOrderMark, 0) == 0) pos_ = kByteOrderMark.size();
}

bool LineReader::next_line() {
  while (pos_ < text_.size()) {
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string_view line(text_.data() + pos_, end - pos_);
    pos_ = end + 1;
    ++line_no_;
    for (char c : line) {
      const auto u = static_cast<unsigned char>(c);
      if (u == 0 || (u < 32 && c != '\t' && c != '\r')) fail("not a text line (binary data?)");
    }
    if (const size_t hash = line.find('#'); hash_comments_ && hash != std::string_view::npos) {
      line = line.substr(0, hash);
    }
    tokens_.clear();
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) tokens_.push_back(line.substr(i, j - i));
      i = j;
    }
    if (!tokens_.empty()) return true;
  }
  return false;
}

void LineReader::fail(const std::string& what) const {
  throw IoError(path_ + ":" + std::to_string(line_no_) + ": " + what);
}

double LineReader::to_double(std::string_view s) const {
  double x = 0;
  // from_chars does not accept a leading '+'.
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || p != s.data() + s.size()) fail("'" + std::string(s) + "' is not a number");
  return x;
}

long long LineReader::to_int(std::string_view s) const {
  long long x = 0;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || p != s.data() + s.size()) fail("'" + std::string(s) + "' is not an integer");
  return x;
}

}  // namespace liftmap
