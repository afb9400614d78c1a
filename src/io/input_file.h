#pragma once
/// Opening an input file: a regular file or a pipe, never a directory or a device that reads forever.

#include <fstream>
#include <string>

namespace liftmap {

/// Opens `path` for reading in binary mode. Regular files and pipes (a FIFO, `<(command)`, /dev/stdin of a pipe)
/// are accepted; a directory, a character or block device (/dev/zero would be read until memory runs out) and a
/// socket are not.
/// \param what what the file should be, for the messages ("mesh file", "landmark file")
/// \throw IoError naming the file: missing or unopenable, a directory, a device or a socket
std::ifstream open_input_file(const std::string& path, const std::string& what);

}  // namespace liftmap
