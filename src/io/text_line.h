#pragma once
/// One line of a text output file, built from numbers without printf: a double as the shortest decimal text that
/// reads back as exactly the same double (std::to_chars), which is also shorter than %.17g's 17 digits (0.5, not
/// 0.50000000000000000); nan and inf as printf writes them.

#include <cstdio>
#include <string>
#include <string_view>

namespace liftmap {

/// Tokens separated by single spaces, written with a newline by write_to(), which starts the next line.
class TextLine {
 public:
  TextLine& add(double x);
  TextLine& add(int x);
  TextLine& add(long long x);
  TextLine& add(std::string_view word);
  /// Writes the line and '\n' to `f` and clears it (errors surface at OutputFile::close, as with fprintf).
  void write_to(std::FILE* f);

 private:
  void separate();
  std::string text_;
};

}  // namespace liftmap
