#include "cut/write_cut.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "cut_test_util.h"

namespace liftmap {
namespace {

int count_lines(const std::string& path, const std::string& prefix) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

TEST(cut_write, WritesMeshesCorrespondenceAndGraph) {
  const auto m = test::load("hand");
  std::mt19937 rng(3);
  const auto l = test::landmark_set(m, 5, test::Pattern::kRandom, rng);
  const CutResult r = cut_meshes(m.V, m.F, m.V, m.F, l, l);
  const auto dir = std::filesystem::temp_directory_path() / "liftmap_test_write_cut";
  std::filesystem::create_directories(dir);
  write_cut(dir.string(), r);
  const std::string a = (dir / "cut_A.obj").string();
  EXPECT_EQ(count_lines(a, "v "), r.a.V.rows());
  EXPECT_EQ(count_lines(a, "vt "), r.a.cut_to_refined.size());
  EXPECT_EQ(count_lines(a, "f "), r.a.F_cut.rows());
  EXPECT_EQ(count_lines((dir / "boundary_map.txt").string(), ""), static_cast<int>(r.nu.size()));
  EXPECT_EQ(count_lines((dir / "cut_graph_B.obj").string(), "l "), 4);
  std::filesystem::remove_all(dir);
  EXPECT_THROW(write_cut((dir / "missing" / "folder").string(), r), IoError);
}

}  // namespace
}  // namespace liftmap
