#include "io/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "core/errors.h"
#include "io/landmarks.h"
#include "io/line_reader.h"
#include "io/read_mesh.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

/// The message of the IoError that f throws ("" and a test failure if it throws none).
template <typename F>
std::string io_error(F f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no IoError";
  return "";
}

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("liftmap_input_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

// A device reads forever (/dev/zero) or is not a file: an error at once, not a reader that fills the memory. Before,
// `liftmap check zero.off` (a link to /dev/zero) ran until it was killed.
TEST_F(InputFile, DevicesAndDirectoriesAreErrorsNamingTheFile) {
  ASSERT_TRUE(fs::exists("/dev/zero"));
  EXPECT_EQ(io_error([] { read_file("/dev/zero", "mesh file"); }),
            "/dev/zero: is a device or socket, not a mesh file (a regular file or a pipe)");
  const std::string link = path("zero.off");
  fs::create_symlink("/dev/zero", link);
  EXPECT_EQ(io_error([&] { read_mesh(link); }),
            link + ": is a device or socket, not a mesh file (a regular file or a pipe)");
  EXPECT_EQ(io_error([&] { read_landmarks(link, 10, 10); }),
            link + ": is a device or socket, not a landmark file (a regular file or a pipe)");
  const std::string folder = path("folder.off");
  fs::create_directory(folder);
  EXPECT_EQ(io_error([&] { read_mesh(folder); }), folder + ": is a directory, not a mesh file");
  EXPECT_EQ(io_error([&] { open_input_file(path("missing.txt"), "landmark file"); }),
            path("missing.txt") + ": cannot open landmark file: No such file or directory");
}

// Pipes are inputs: `liftmap map <(generate A) ...` reads a FIFO.
TEST_F(InputFile, RegularFilesAndPipesAreRead) {
  const std::string regular = path("lm.txt");
  std::ofstream(regular) << "0 1\n2 3\n";
  EXPECT_EQ(read_file(regular, "landmark file"), "0 1\n2 3\n");
  const std::string fifo = path("fifo.txt");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo) << "4 5\n6 7\n"; });
  const Landmarks lm = read_landmarks(fifo, 10, 10);
  writer.join();
  ASSERT_EQ(lm.a.size(), 2U);
  EXPECT_EQ(lm.b[1].vertex.idx, 7);
}

}  // namespace
}  // namespace liftmap
