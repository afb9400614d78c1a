#include "io/output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/errors.h"

namespace liftmap {

namespace fs = std::filesystem;

namespace {

/// Whether writing `output` (a rename onto its path) would replace the file `input` names.
bool same_file(const fs::path& output, const std::string& input) {
  std::error_code ec;
  // The rename replaces the directory entry `output`; `input` resolved through its symlinks may be that entry.
  const fs::path out_entry = fs::weakly_canonical(output.parent_path(), ec) / output.filename();
  if (ec) return false;
  const fs::path in_resolved = fs::weakly_canonical(input, ec);
  if (!ec && in_resolved == out_entry) return true;
  // A hard link: the entry itself (not a symlink's target) is the input file.
  const fs::file_status s = fs::symlink_status(output, ec);
  if (ec || !fs::is_regular_file(s)) return false;
  return fs::equivalent(output, input, ec) && !ec;
}

void check_writable(const fs::path& dir) {
  const fs::path probe = dir / (".liftmap-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw IoError(dir.string() + ": cannot write into the output folder: " + std::strerror(errno));
  }
  ::close(fd);
  std::error_code ec;
  fs::remove(probe, ec);
}

}  // namespace

void refuse_overwriting_inputs(const std::string& output, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    if (same_file(output, input)) {
      throw UsageError("the output " + output + " would overwrite the input " + input + ": choose another output path");
    }
  }
}

void prepare_output_folder(const std::string& dir, const std::vector<std::string>& outputs,
                           const std::vector<std::string>& inputs) {
  refuse_overwriting_inputs(dir, inputs);  // an input given as the folder: a usage error, not an unwritable folder
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir + ": cannot create output folder: " + ec.message());
  if (!fs::is_directory(dir, ec)) throw IoError(dir + ": the output folder is not a folder");
  for (const std::string& name : outputs) refuse_overwriting_inputs((fs::path(dir) / name).string(), inputs);
  check_writable(dir);
  for (const std::string& name : outputs) {
    const fs::path p = fs::path(dir) / name;
    fs::remove(p, ec);  // a symlink itself, not its target
    if (ec) throw IoError(p.string() + ": cannot remove the previous run's file: " + ec.message());
  }
}

}  // namespace liftmap
