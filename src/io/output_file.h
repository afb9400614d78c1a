#pragma once
/// A file opened for writing whose errors are never lost: every writer of liftmap goes through it.

#include <cstdio>
#include <string>

namespace liftmap {

/// Opens `path` for writing; `close()` reports write errors (a full disk) that fprintf alone would hide.
class OutputFile {
 public:
  /// \throw IoError if the file cannot be opened
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// The stream to fprintf to.
  [[nodiscard]] std::FILE* get() const { return file_; }
  /// Flushes and closes.
  /// \throw IoError naming the file if anything written was lost
  void close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace liftmap
