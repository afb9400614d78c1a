// The overlay files: written and read back, read from texts as from disk, and the fuzz target's use of them
// (fuzz/overlay_as_fuzzed.h) on its seed, on every truncation and on single-byte changes of it: each must end in
// success, IoError or InvalidInputError (and, in the ASan build, without a sanitizer report).

#include "map/overlay_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/test_meshes.h"
#include "core/errors.h"
#include "overlay_as_fuzzed.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

/// The identity overlay of the fuzz target's octahedron with face 0 split at its centroid (vertex 6): the three
/// files in one string, NUL-separated, as the fuzz target reads them.
std::string split_octahedron_input() {
  const TexturedMesh oct = fuzz::fuzz_textured_octahedron();
  Overlay o;
  o.VA.resize(7, 3);
  o.VA.topRows(6) = oct.V;
  o.VA.row(6) = (oct.V.row(0) + oct.V.row(2) + oct.V.row(4)) / 3;
  o.F.resize(10, 3);
  o.F.topRows(3) << 0, 2, 6, 2, 4, 6, 4, 0, 6;
  o.F.bottomRows(7) = oct.F.bottomRows(7);
  o.face_a.resize(10);
  o.face_a << 0, 0, 0, 1, 2, 3, 4, 5, 6, 7;
  o.face_b = o.face_a;
  for (int v = 0; v < 6; ++v) {
    int f = 0, k = 0;
    while ((oct.F.row(f).array() != v).all()) ++f;
    while (oct.F(f, k) != v) ++k;
    std::array<double, 3> b{0, 0, 0};
    b[static_cast<size_t>(k)] = 1;
    o.on_a.push_back(SurfacePoint::in_face(FaceId(f), b));
  }
  o.on_a.push_back(SurfacePoint::in_face(FaceId(0), {1.0 / 3, 1.0 / 3, 1.0 / 3}));
  o.on_b = o.on_a;
  o.VB = o.VA;
  const fs::path dir = fs::temp_directory_path() / "liftmap_test_overlay_files";
  fs::create_directories(dir);
  const std::string obj = (dir / "overlay.obj").string();
  write_overlay(obj, o);
  std::string data;
  for (const std::string& path : {obj, overlay_table_paths(obj)[0], overlay_table_paths(obj)[1]}) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!data.empty()) data += '\0';
    data += text.str();
  }
  return data;
}

/// Runs the fuzz target's body; records a failure for anything but success or a bad-input error.
void expect_bad_input_error_at_most(const std::string& data, const std::string& what) {
  try {
    fuzz::overlay_as_fuzzed(data);
  } catch (const IoError&) {
  } catch (const InvalidInputError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": not a bad-input error: " << e.what();
  }
}

TEST(OverlayFiles, WrittenFilesReadBackFromDiskAndFromTexts) {
  const TexturedMesh oct = fuzz::fuzz_textured_octahedron();
  const std::string data = split_octahedron_input();
  const OverlayTexts texts = fuzz::overlay_texts_of(data);
  const fs::path obj = fs::temp_directory_path() / "liftmap_test_overlay_files" / "overlay.obj";
  const Overlay from_disk = read_overlay(obj.string(), oct.V, oct.F, oct.V, oct.F);
  const Overlay from_texts = read_overlay_texts(texts, obj.string(), oct.V, oct.F, oct.V, oct.F);
  ASSERT_EQ(from_disk.F.rows(), 10);
  ASSERT_EQ(from_disk.VA.rows(), 7);
  EXPECT_EQ(from_disk.F, from_texts.F);
  EXPECT_EQ(from_disk.VA, from_texts.VA);
  EXPECT_EQ(from_disk.face_b, from_texts.face_b);
  EXPECT_NEAR((from_disk.VB.row(6) - (oct.V.row(0) + oct.V.row(2) + oct.V.row(4)) / 3).norm(), 0, 1e-15);
  for (size_t i = 0; i < from_disk.on_b.size(); ++i) {
    EXPECT_EQ(from_disk.on_b[i].face, from_texts.on_b[i].face);
    EXPECT_EQ(from_disk.on_b[i].bary, from_texts.on_b[i].bary);
  }
  // The seed is a valid overlay: the fuzz target's use of it succeeds.
  EXPECT_NO_THROW(fuzz::overlay_as_fuzzed(data));
}

TEST(OverlayFiles, MissingTableIsAnIoErrorNamingIt) {
  const TexturedMesh oct = fuzz::fuzz_textured_octahedron();
  (void)split_octahedron_input();
  const fs::path dir = fs::temp_directory_path() / "liftmap_test_overlay_files";
  fs::remove(dir / "overlay_faces.txt");
  try {
    (void)read_overlay((dir / "overlay.obj").string(), oct.V, oct.F, oct.V, oct.F);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("overlay_faces.txt"), std::string::npos) << e.what();
  }
}

TEST(OverlayFiles, TruncatedAndChangedInputsAreBadInputErrorsNotCrashes) {
  const std::string data = split_octahedron_input();
  for (size_t n = 0; n < data.size(); ++n)
    expect_bad_input_error_at_most(data.substr(0, n), "first " + std::to_string(n));
  int changed = 0;
  for (size_t i = 0; i < data.size(); ++i) {
    for (const char c : {'-', '9', 'e', '.', ' ', '\n', '\0', 'x'}) {
      if (data[i] == c) continue;
      std::string d = data;
      d[i] = c;
      expect_bad_input_error_at_most(d, "byte " + std::to_string(i) + " set to " + std::to_string(c));
      ++changed;
    }
  }
  EXPECT_GT(changed, 1000);
}

/// The bytes of a file.
std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream data;
  data << in.rdbuf();
  return data.str();
}

// The fuzz target's seeds (tests/data/fuzz-seeds/overlay, copied by scripts/fuzz.sh) are valid overlays, so that
// fuzzing starts past the readers' first checks; its findings, once fixed, are bad-input errors.
TEST(OverlayFiles, FuzzSeedsAreOverlaysAndFindingsAreBadInputErrors) {
  int seeds = 0;
  for (const auto& entry : fs::directory_iterator(testing::test_data("fuzz-seeds/overlay"))) {
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(fuzz::overlay_as_fuzzed(file_bytes(entry.path())));
    ++seeds;
  }
  EXPECT_GE(seeds, 2);
  const fs::path findings = testing::test_data("fuzz-regressions/overlay");
  if (fs::is_directory(findings)) {
    for (const auto& entry : fs::directory_iterator(findings))
      expect_bad_input_error_at_most(file_bytes(entry.path()), entry.path().string());
  }
}

}  // namespace
}  // namespace liftmap
