// Replays the inputs the fuzzers of fuzz/ found (tests/data/fuzz-regressions/<reader>/), as the fuzz target
// reads them: each must end in success, IoError or InvalidInputError (and, in the ASan build, without a
// sanitizer report).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "read_as_fuzzed.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryFoundInputIsABadInputErrorNotACrash) {
  const fs::path root = testing::test_data("fuzz-regressions");
  int replayed = 0;
  for (const char* reader : {"off", "obj", "ply", "stl", "landmarks", "surface_landmarks", "vertex_map", "obj_uv"}) {
    const fs::path dir = root / reader;
    if (!fs::is_directory(dir)) continue;
    const std::string name = std::string(reader).size() == 3 ? std::string(".") + reader : std::string(reader);
    for (const auto& entry : fs::directory_iterator(dir)) {
      SCOPED_TRACE(entry.path().string());
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream data;
      data << in.rdbuf();
      try {
        fuzz::read_as_fuzzed(name, data.str());
      } catch (const IoError&) {
      } catch (const InvalidInputError&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << "not a bad-input error: " << e.what();
      }
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0) << "no regression inputs in " << root;
}

TEST(FuzzRegressions, PlyPropertyBeforeAnyElementIsNamed) {
  // CGAL's PLY reader indexed its empty list of elements (undefined behaviour, found by fuzz_ply).
  std::ifstream in(testing::test_data("fuzz-regressions/ply/property_before_element_text.ply"), std::ios::binary);
  std::ostringstream data;
  data << in.rdbuf();
  try {
    fuzz::read_as_fuzzed(".ply", data.str());
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "fuzz.ply:3: 'property' before any 'element'");
  }
}

TEST(FuzzRegressions, PlyHeadersThatCgalWouldMisreadAreNamed) {
  // A vertex coordinate of an integer type was read through a null pointer (found by fuzz_ply); a 32-bit list
  // count could size a buffer of gigabytes.
  const std::pair<const char*, const char*> cases[] = {
      {"integer_coordinate_text.ply", "fuzz.ply:6: vertex coordinate 'z' has type 'ushort'; float or double is needed"},
      {"list_coordinate.ply", "fuzz.ply:4: vertex coordinate 'x' is a list; float or double is needed"},
      {"list_count_uint.ply", "fuzz.ply:8: list count type 'uint' is not supported (uchar or ushort)"},
      // A signed count of -3 became 2^64 - 3 in CGAL's reader, whose vector threw length_error (fuzz_ply).
      {"list_count_char_text.ply", "fuzz.ply:8: list count type 'char' is not supported (uchar or ushort)"},
      // "end_header" inside the format line ended liftmap's header check but not CGAL's reader (fuzz_ply).
      {"end_header_inside_a_line_text.ply", "fuzz.ply:3: 'property' before any 'element'"},
      // "end_header#": a comment for liftmap's line reader, not the end of the header for CGAL's (fuzz_ply).
      {"end_header_with_hash_text.ply", "fuzz.ply:3: unknown PLY header keyword 'end_header#'"},
  };
  for (const auto& [file, message] : cases) {
    std::ifstream in(testing::test_data(std::string("fuzz-regressions/ply/") + file), std::ios::binary);
    std::ostringstream data;
    data << in.rdbuf();
    try {
      fuzz::read_as_fuzzed(".ply", data.str());
      ADD_FAILURE() << file << ": no error";
    } catch (const IoError& e) {
      EXPECT_STREQ(e.what(), message);
    }
  }
}

}  // namespace
}  // namespace liftmap
