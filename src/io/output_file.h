#pragma once
/// A file written whole or not at all: every writer of liftmap goes through it.

#include <cstdio>
#include <string>

namespace liftmap {

/// Writes `path` through a temporary file in the same folder that `close()` renames into place: until then
/// `path` keeps its previous content (or stays absent), a failed or abandoned write leaves no partial file, and
/// an existing symlink at `path` is replaced, never followed (the file it points to stays untouched).
class OutputFile {
 public:
  /// \throw IoError naming `path` if the temporary file cannot be created (missing or read-only folder)
  explicit OutputFile(const std::string& path);
  /// Removes the temporary file if `close()` was not reached (an exception while writing).
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// The stream to fprintf or fwrite to.
  [[nodiscard]] std::FILE* get() const { return file_; }
  /// Flushes and closes the temporary file and renames it to `path`.
  /// \throw IoError naming the file if anything written was lost (a full disk) or the rename fails
  void close();

 private:
  std::string path_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
};

}  // namespace liftmap
