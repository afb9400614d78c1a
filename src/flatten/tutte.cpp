#include "flatten/tutte.h"

#include <Eigen/Geometry>
#include <Eigen/SparseLU>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace liftmap {

Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                const Eigen::MatrixXd& B) {
  const int n = mesh.n_vertices();
  if (V.rows() != n || V.cols() != 3) throw InvalidInputError("tutte_embedding: V must be #V by 3");
  if (B.rows() != static_cast<Eigen::Index>(boundary.size()) || B.cols() != 2) {
    throw InvalidInputError("tutte_embedding: B must be #boundary by 2");
  }
  const auto loops = mesh.boundary_loops();
  if (loops.size() != 1 || mesh.euler_characteristic() != 1) {
    throw InvalidInputError("tutte_embedding: the mesh is not a disk");
  }
  if (boundary.size() != loops[0].size()) {
    throw InvalidInputError("tutte_embedding: " + std::to_string(boundary.size()) + " boundary vertices given, the " +
                            "boundary loop has " + std::to_string(loops[0].size()));
  }

  // Unknowns: the interior vertices; boundary and isolated vertices are known.
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(n, 2);
  std::vector<int> unknown(static_cast<size_t>(n), -1);
  std::vector<char> pinned(static_cast<size_t>(n), 0);
  for (size_t i = 0; i < boundary.size(); ++i) {
    const VertexId v = boundary[i];
    if (!v.valid() || v.idx >= n || !mesh.is_boundary(v)) {
      throw InvalidInputError("tutte_embedding: vertex " + std::to_string(v.idx) + " is not a boundary vertex");
    }
    pinned[static_cast<size_t>(v.idx)] = 1;
    U.row(v.idx) = B.row(static_cast<Eigen::Index>(i));
  }
  int m = 0;
  for (int v = 0; v < n; ++v) {
    if (!pinned[static_cast<size_t>(v)] && !mesh.is_isolated(VertexId(v))) unknown[static_cast<size_t>(v)] = m++;
  }

  // Mean-value weights (Floater 2003): w_ij = (tan(a/2) + tan(b/2)) / |x_j - x_i|, with a, b the angles at i of
  // the two faces beside edge ij. Each face corner contributes tan(angle/2) / |edge| to its two edges.
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face_vertices(FaceId(f));
    for (int c = 0; c < 3; ++c) {
      const int i = fv[c].idx;
      const int row = unknown[static_cast<size_t>(i)];
      if (row < 0) continue;
      const int j = fv[(c + 1) % 3].idx;
      const int k = fv[(c + 2) % 3].idx;
      const Eigen::Vector3d ej = V.row(j) - V.row(i);
      const Eigen::Vector3d ek = V.row(k) - V.row(i);
      const double lj = ej.norm();
      const double lk = ek.norm();
      if (!(lj > 0) || !(lk > 0)) {
        throw InvalidInputError("tutte_embedding: face " + std::to_string(f) + " has a zero-length edge");
      }
      const double angle = std::atan2(ej.cross(ek).norm(), ej.dot(ek));
      const double t = std::tan(0.5 * angle);
      for (const auto& [other, len] : {std::pair{j, lj}, std::pair{k, lk}}) {
        const double w = t / len;
        triplets.emplace_back(row, row, w);
        const int col = unknown[static_cast<size_t>(other)];
        if (col >= 0) {
          triplets.emplace_back(row, col, -w);
        } else {
          rhs.row(row) += w * U.row(other);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> L(m, m);
  L.setFromTriplets(triplets.begin(), triplets.end());
  if (m == 0) return U;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(L);
  if (lu.info() != Eigen::Success) throw PipelineError("tutte_embedding: the mean-value Laplacian is singular");
  const Eigen::MatrixXd X = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !X.allFinite()) throw PipelineError("tutte_embedding: the solve failed");
  for (int v = 0; v < n; ++v) {
    const int u = unknown[static_cast<size_t>(v)];
    if (u >= 0) U.row(v) = X.row(u);
  }
  return U;
}

}  // namespace liftmap
