#include "io/text_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace liftmap {
namespace {

/// What TextLine writes for `values`, read back through a temporary file.
std::string written(const std::vector<double>& values) {
  std::FILE* f = std::tmpfile();
  TextLine line;
  for (const double x : values) line.add(x);
  line.write_to(f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += static_cast<char>(c);
  std::fclose(f);
  return text;
}

// Every double reads back (strtod, as the readers parse) as exactly itself, in no more characters than %.17g.
TEST(io_text_line, DoublesReadBackExactly) {
  std::vector<double> values = {0.0,
                                -0.0,
                                0.1,
                                1.0 / 3,
                                -2.5e-310,  // subnormal
                                std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::max(),
                                -std::numeric_limits<double>::infinity(),
                                1e22,
                                123456789012345680.0};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 2000; ++i) values.push_back(u(rng) * std::pow(10.0, static_cast<int>(rng() % 40) - 20));
  const std::string text = written(values);
  ASSERT_EQ(text.back(), '\n');
  std::istringstream in(text);
  std::string token;
  for (const double x : values) {
    ASSERT_TRUE(in >> token);
    const double back = std::strtod(token.c_str(), nullptr);
    EXPECT_EQ(back, x) << token;
    EXPECT_EQ(std::signbit(back), std::signbit(x)) << token;
    char printf_text[40];
    std::snprintf(printf_text, sizeof printf_text, "%.17g", x);
    EXPECT_LE(token.size(), std::string(printf_text).size()) << token << " against " << printf_text;
  }
  EXPECT_FALSE(in >> token) << "more tokens than values";
}

TEST(io_text_line, WordsIntegersAndNonFiniteAsPrintfWritesThem) {
  std::FILE* f = std::tmpfile();
  TextLine line;
  line.add("f").add(1).add(-2147483647 - 1).add(12345678901LL).write_to(f);
  line.add(std::numeric_limits<double>::quiet_NaN()).add(std::numeric_limits<double>::infinity()).write_to(f);
  std::rewind(f);
  char buffer[128] = {};
  const size_t n = std::fread(buffer, 1, sizeof buffer - 1, f);
  std::fclose(f);
  EXPECT_EQ(std::string(buffer, n), "f 1 -2147483648 12345678901\nnan inf\n");
}

}  // namespace
}  // namespace liftmap
