#pragma once
/// Reading text formats line by line, with the file and line named in every message (OFF, OBJ, STL, PLY headers,
/// MTL).

#include <string>
#include <string_view>
#include <vector>

namespace liftmap {

/// A UTF-8 byte-order mark: skipped before a text format's content.
inline constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

/// Removes a byte-order mark from the start of `first_line` (the first line of a file read line by line).
inline void skip_byte_order_mark(std::string& first_line) {
  if (first_line.rfind(kByteOrderMark, 0) == 0) first_line.erase(0, kByteOrderMark.size());
}

/// The bytes of a file.
/// \param what what the file should be, for the message on a directory ("mesh file", "material file")
/// \throw IoError naming the file if it is a directory or cannot be opened or read
std::string read_file(const std::string& path, const std::string& what);

/// Splits text into lines and whitespace-separated tokens, keeping line numbers for messages.
class LineReader {
 public:
  /// \param path the file name messages start with
  /// \param text the file's content; it and `path` must outlive the reader
  /// \param hash_comments whether '#' starts a comment (OFF, OBJ, STL, MTL); PLY has none
  LineReader(const std::string& path, const std::string& text, bool hash_comments = true);

  /// Advances to the next line that has content (comments after '#' removed); false at end of file.
  /// \throw IoError for a line with control characters (binary data)
  bool next_line();

  [[nodiscard]] const std::vector<std::string_view>& tokens() const { return tokens_; }
  [[nodiscard]] int line_no() const { return line_no_; }

  /// \throw IoError "path:line: what"
  [[noreturn]] void fail(const std::string& what) const;

  /// The token as a number. \throw IoError naming the line if it is not one
  double to_double(std::string_view s) const;
  /// The token as an integer. \throw IoError naming the line if it is not one
  long long to_int(std::string_view s) const;

 private:
  const std::string& path_;
  const std::string& text_;
  bool hash_comments_ = true;
  size_t pos_ = 0;
  int line_no_ = 0;
  std::vector<std::string_view> tokens_;
};

}  // namespace liftmap
