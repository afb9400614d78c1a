#include "io/input_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/errors.h"

namespace liftmap {

std::ifstream open_input_file(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  if (!ec) {
    if (fs::is_directory(st)) throw IoError(path + ": is a directory, not a " + what);
    if (fs::is_character_file(st) || fs::is_block_file(st) || fs::is_socket(st)) {
      throw IoError(path + ": is a device or socket, not a " + what + " (a regular file or a pipe)");
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open " + what + ": " + std::strerror(errno));
  return in;
}

}  // namespace liftmap
