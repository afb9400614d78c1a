#include "io/landmarks.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "common/test_meshes.h"
#include "core/errors.h"

namespace liftmap {
namespace {

TEST(Landmarks, ReadsPairsWithCommentsAndLineNumbers) {
  const Landmarks lm = read_landmarks(testing::test_data("good/landmarks.txt"), 6, 6);
  ASSERT_EQ(lm.a.size(), 3U);
  EXPECT_EQ(lm.a[0].idx, 4);
  EXPECT_EQ(lm.b[2].idx, 1);
  EXPECT_EQ(lm.line[0], 2);
  EXPECT_EQ(lm.line[2], 4);
}

TEST(Landmarks, AByteOrderMarkIsSkipped) {
  // It used to give "'\xEF\xBB\xBF117' is not a vertex index", the mark invisible in the message.
  std::istringstream in(
      "\xEF\xBB\xBF"
      "117 3\n5 4\n");
  const Landmarks lm = read_landmarks(in, "bom.txt", 200, 200);
  ASSERT_EQ(lm.a.size(), 2U);
  EXPECT_EQ(lm.a[0].idx, 117);
}

TEST(Landmarks, WriteReadRoundTrip) {
  Landmarks lm;
  for (int i = 0; i < 20; ++i) {
    lm.a.emplace_back(3 * i);
    lm.b.emplace_back(100 - i);
  }
  const std::string path = (std::filesystem::temp_directory_path() / "liftmap_test_landmarks.txt").string();
  write_landmarks(path, lm);
  const Landmarks back = read_landmarks(path, 100, 101);
  EXPECT_EQ(back.a, lm.a);
  EXPECT_EQ(back.b, lm.b);
  std::filesystem::remove(path);
}

TEST(Landmarks, RejectsBadFilesWithTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"bad/lm_out_of_range.txt", "lm_out_of_range.txt:2: vertex 9 is out of range for mesh B"},
      {"bad/lm_duplicate_a.txt", ":2: vertex 0 of mesh A is already a landmark (line 1)"},
      {"bad/lm_three_fields.txt", ":2: expected two vertex indices"},
      {"bad/lm_one_pair.txt", "at least 2 are needed"},
      {"bad/lm_surface_point.txt", "not supported yet"},
  };
  for (const auto& [file, message] : cases) {
    try {
      read_landmarks(testing::test_data(file), 6, 6);
      ADD_FAILURE() << file << " was accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_landmarks("/nonexistent/landmarks.txt", 6, 6), IoError);
}

}  // namespace
}  // namespace liftmap
