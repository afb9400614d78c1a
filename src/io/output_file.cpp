#include "io/output_file.h"

#include "core/errors.h"

namespace liftmap {

OutputFile::OutputFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (file_ == nullptr) throw IoError(path + ": cannot open for writing");
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) std::fclose(file_);
}

void OutputFile::close() {
  const bool write_error = std::ferror(file_) != 0;
  const bool close_error = std::fclose(file_) != 0;
  file_ = nullptr;
  if (write_error || close_error) throw IoError(path_ + ": write error (disk full?)");
}

}  // namespace liftmap
