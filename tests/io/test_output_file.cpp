#include "io/output_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

std::string content(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("liftmap_output_file_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(OutputFile, ThePathKeepsItsOldContentUntilClose) {
  const fs::path d = fresh_dir("close");
  const fs::path p = d / "a.txt";
  std::ofstream(p) << "old\n";
  {
    OutputFile f(p.string());
    std::fprintf(f.get(), "new\n");
    EXPECT_EQ(content(p), "old\n") << "written to a temporary file, renamed into place by close()";
    f.close();
  }
  EXPECT_EQ(content(p), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1) << "no temporary file left";
}

TEST(OutputFile, AnAbandonedWriteLeavesNoFile) {
  const fs::path d = fresh_dir("abandoned");
  {
    OutputFile f((d / "a.txt").string());
    std::fprintf(f.get(), "partial");
  }  // an exception while writing: close() never reached
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(OutputFile, ASymlinkIsReplacedNotFollowed) {
  const fs::path d = fresh_dir("symlink");
  std::ofstream(d / "target.txt") << "target\n";
  fs::create_symlink(d / "target.txt", d / "report.json");
  OutputFile f((d / "report.json").string());
  std::fprintf(f.get(), "{}\n");
  f.close();
  EXPECT_EQ(content(d / "target.txt"), "target\n");
  EXPECT_FALSE(fs::is_symlink(d / "report.json"));
  EXPECT_EQ(content(d / "report.json"), "{}\n");
}

TEST(OutputFile, AMissingFolderIsAnIoErrorNamingThePath) {
  try {
    OutputFile f("/nonexistent_liftmap_folder/a.txt");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_liftmap_folder/a.txt: cannot open for writing"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace liftmap
