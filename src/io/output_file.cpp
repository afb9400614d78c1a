#include "io/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/errors.h"

namespace liftmap {

namespace {

std::atomic<unsigned> temp_counter{0};

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path) {
  const std::filesystem::path p(path);
  // open(O_EXCL) with mode 0666 rather than mkstemp: the final file gets the permissions the umask gives, as
  // fopen would, and a name nobody else uses.
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_path_ = (p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                                     std::to_string(temp_counter++)))
                     .string();
    const int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd < 0) throw IoError(path + ": cannot open for writing: " + std::strerror(errno));
    file_ = ::fdopen(fd, "w");
    if (file_ == nullptr) {
      ::close(fd);
      std::remove(temp_path_.c_str());
      throw IoError(path + ": cannot open for writing: " + std::strerror(errno));
    }
    return;
  }
  throw IoError(path + ": cannot create a temporary file next to it");
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) {
    std::fclose(file_);
    std::remove(temp_path_.c_str());
  }
}

void OutputFile::close() {
  const bool write_error = std::ferror(file_) != 0;
  const bool close_error = std::fclose(file_) != 0;
  file_ = nullptr;
  if (write_error || close_error) {
    std::remove(temp_path_.c_str());
    throw IoError(path_ + ": write error (disk full?)");
  }
  // rename(2) replaces a symlink at path_ itself and is atomic: readers see the old file or the new one.
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temp_path_.c_str());
    throw IoError(path_ + ": cannot write: " + reason);
  }
}

}  // namespace liftmap
