#pragma once
/// Landmark files: corresponding points of mesh A and mesh B.
///
/// Format (text): one pair per line, `iA iB`, 0-based vertex indices into mesh A and mesh B. `#` starts a
/// comment (whole line or trailing); blank lines are ignored. A token that is a plain non-negative integer is a
/// vertex index. Other token forms are reserved for landmarks on surface points (inside faces or on edges) and
/// are rejected for now with a message saying so; a future version accepts them without changing the meaning of
/// existing files.

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// Corresponding landmarks: `a[i]` on mesh A corresponds to `b[i]` on mesh B.
struct Landmarks {
  std::vector<VertexId> a;
  std::vector<VertexId> b;
  std::vector<int> line;  ///< line of the file each pair came from (for messages)
};

/// Reads and validates a landmark file against meshes with `n_vertices_a` and `n_vertices_b` vertices.
/// \throw IoError if the file cannot be read; InvalidInputError naming the file and line for a malformed line,
///        an index out of range, a vertex used twice on one side, or fewer than 2 pairs.
/// A UTF-8 byte-order mark before the first line is skipped.
Landmarks read_landmarks(const std::string& path, int n_vertices_a, int n_vertices_b);

/// read_landmarks from a stream; `name` stands for the file in messages.
Landmarks read_landmarks(std::istream& in, const std::string& name, int n_vertices_a, int n_vertices_b);

/// Landmarks given as index pairs (e.g. a k by 2 array from Python), with the checks of read_landmarks.
/// \param pairs k pairs {vertex of A, vertex of B}
/// \param name how messages name the pairs; each message names the offending row (0-based)
/// \throw InvalidInputError naming the row for a negative or out-of-range index or a vertex used twice on one
///        side, or if there are fewer than 2 pairs.
Landmarks make_landmarks(const std::vector<std::array<long long, 2>>& pairs, const std::string& name, int n_vertices_a,
                         int n_vertices_b);

/// Writes landmarks in the format above.
/// \throw IoError if the file cannot be written.
void write_landmarks(const std::string& path, const Landmarks& landmarks);

}  // namespace liftmap
