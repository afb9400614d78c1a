#include "io/output_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("liftmap_output_folder_" + name);
  fs::remove_all(d);
  return d;
}

TEST(OutputFolder, CreatesTheFolderAndRemovesThePreviousRunsFilesOnly) {
  const fs::path d = fresh_dir("stale");
  fs::create_directories(d);
  std::ofstream(d / "report.json") << "{\"passed\": true}\n";
  std::ofstream(d / "notes.txt") << "the user's\n";
  std::ofstream(d.parent_path() / "liftmap_output_folder_target.txt") << "target\n";
  fs::create_symlink(d.parent_path() / "liftmap_output_folder_target.txt", d / "render.png");
  prepare_output_folder(d.string(), {"report.json", "render.png", "A_to_B.txt"}, {});
  EXPECT_FALSE(fs::exists(d / "report.json"));
  EXPECT_FALSE(fs::exists(fs::symlink_status(d / "render.png")));
  EXPECT_TRUE(fs::exists(d.parent_path() / "liftmap_output_folder_target.txt")) << "a symlink's target stays";
  EXPECT_TRUE(fs::exists(d / "notes.txt")) << "files that are not outputs stay";

  const fs::path nested = fresh_dir("nested") / "a" / "b";
  prepare_output_folder(nested.string(), {"report.json"}, {});
  EXPECT_TRUE(fs::is_directory(nested));
}

TEST(OutputFolder, RefusesAnInputThatAnOutputWouldOverwrite) {
  const fs::path d = fresh_dir("inputs");
  fs::create_directories(d);
  std::ofstream(d / "cut_A.obj") << "v 0 0 0\n";
  EXPECT_THROW(prepare_output_folder(d.string(), {"cut_A.obj"}, {(d / "cut_A.obj").string()}), UsageError);
  EXPECT_THROW(prepare_output_folder((d / "." / "").string(), {"cut_A.obj"}, {(d / "cut_A.obj").string()}), UsageError)
      << "another spelling of the same path";
  EXPECT_TRUE(fs::exists(d / "cut_A.obj")) << "refused before anything is removed";
  EXPECT_NO_THROW(refuse_overwriting_inputs((d / "other.obj").string(), {(d / "cut_A.obj").string()}));
}

TEST(OutputFolder, AFileInsteadOfAFolderIsAnIoError) {
  const fs::path d = fresh_dir("file");
  fs::create_directories(d.parent_path());
  std::ofstream(d) << "a file\n";
  EXPECT_THROW(prepare_output_folder(d.string(), {"report.json"}, {}), IoError);
}

}  // namespace
}  // namespace liftmap
