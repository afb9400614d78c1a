#pragma once
/// Writing the result of step 1 so that a user can inspect a cut before mapping.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cut/cut_meshes.h"

namespace liftmap {

/// Writes, into the existing folder `dir`:
///  - `cut_A.obj`, `cut_B.obj`: the cut meshes, refined positions as `v`, one `vt` per cut-mesh vertex (from
///    UV_a / UV_b, #Vc by 2; zeros if empty, e.g. before flattening) and faces `f v/vt`, so the seams show;
///  - `boundary_map.txt`: nu, one line `iA iB` per boundary pair (0-based cut-vertex indices), in
///    counter-clockwise boundary order;
///  - `cut_graph_A.obj`, `cut_graph_B.obj`: the cut tree, one OBJ polyline (`l`) per path.
/// \throw IoError if a file cannot be written.
void write_cut(const std::string& dir, const CutResult& result, const Eigen::MatrixXd& UV_a = {},
               const Eigen::MatrixXd& UV_b = {});

/// The names of the files write_cut writes.
std::vector<std::string> cut_output_names();

}  // namespace liftmap
