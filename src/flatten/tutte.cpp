#include "flatten/tutte.h"

#include <omp.h>
#include <Eigen/Geometry>
#include <Eigen/KLUSupport>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>

#include "core/errors.h"

namespace liftmap {

namespace {

/// The weight of edge (i, other) of length `length` in vertex i's convex combination, given its mean-value part.
double edge_weight(const TutteWeights& weights, int i, int other, double length, double mean_value) {
  if (weights.depth.empty() || weights.drift == 0) return mean_value;
  const double slope = (weights.depth[static_cast<size_t>(i)] - weights.depth[static_cast<size_t>(other)]) / length;
  const double local = weights.drift_scale.empty() ? 1.0 : weights.drift_scale[static_cast<size_t>(i)];
  return mean_value * std::exp(local * weights.drift * std::clamp(slope, -1.0, 1.0));
}

void check_weights(const TutteWeights& weights, int n) {
  if (!weights.depth.empty() && weights.depth.size() != static_cast<size_t>(n)) {
    throw InvalidInputError("tutte_embedding: weights.depth must have #V values");
  }
  if (!weights.drift_scale.empty() && weights.drift_scale.size() != static_cast<size_t>(n)) {
    throw InvalidInputError("tutte_embedding: weights.drift_scale must have #V values");
  }
  if (!std::isfinite(weights.drift)) throw InvalidInputError("tutte_embedding: weights.drift must be finite");
}

}  // namespace

Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                const Eigen::MatrixXd& B, const TutteWeights& weights) {
  return std::move(tutte_embeddings(mesh, V, boundary, B, {weights}).front());
}

std::vector<Eigen::MatrixXd> tutte_embeddings(const Mesh& mesh, const Eigen::MatrixXd& V,
                                              const std::vector<VertexId>& boundary, const Eigen::MatrixXd& B,
                                              const std::vector<TutteWeights>& weights) {
  const int n = mesh.n_vertices();
  if (V.rows() != n || V.cols() != 3) throw InvalidInputError("tutte_embedding: V must be #V by 3");
  if (B.rows() != static_cast<Eigen::Index>(boundary.size()) || B.cols() != 2) {
    throw InvalidInputError("tutte_embedding: B must be #boundary by 2");
  }
  for (const TutteWeights& w : weights) check_weights(w, n);
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
  struct Corner {
    int row, other;
    double length;  // |x_row - x_other|
    double mean_value;
  };
  std::vector<Corner> corners;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face_vertices(FaceId(f));
    for (int c = 0; c < 3; ++c) {
      const int row = unknown[static_cast<size_t>(fv[c].idx)];
      if (row < 0) continue;
      const int i = fv[c].idx, j = fv[(c + 1) % 3].idx, k = fv[(c + 2) % 3].idx;
      const Eigen::Vector3d ej = V.row(j) - V.row(i);
      const Eigen::Vector3d ek = V.row(k) - V.row(i);
      const double lj = ej.norm(), lk = ek.norm();
      if (!(lj > 0) || !(lk > 0)) {
        throw InvalidInputError("tutte_embedding: face " + std::to_string(f) + " has a zero-length edge");
      }
      const double t = std::tan(0.5 * std::atan2(ej.cross(ek).norm(), ej.dot(ek)));
      corners.push_back({i, j, lj, t / lj});
      corners.push_back({i, k, lk, t / lk});
    }
  }
  std::vector<Eigen::MatrixXd> result(weights.size(), U);
  if (m == 0) return result;
  // The Laplacian of one set of weights, solved into result[s] by SuiteSparse's KLU (sparse LU, partial pivoting).
  // Every set has the same sparsity pattern, so each thread analyses it once (KLU's ordering depends on the pattern
  // only: the embeddings are the same on any thread count).
  const auto solve_set = [&](size_t s, Eigen::KLU<Eigen::SparseMatrix<double>>& lu, bool analyze) {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(2 * corners.size());
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
    for (const Corner& c : corners) {
      const int row = unknown[static_cast<size_t>(c.row)];
      const double w = edge_weight(weights[s], c.row, c.other, c.length, c.mean_value);
      triplets.emplace_back(row, row, w);
      const int col = unknown[static_cast<size_t>(c.other)];
      if (col >= 0) {
        triplets.emplace_back(row, col, -w);
      } else {
        rhs.row(row) += w * U.row(c.other);
      }
    }
    Eigen::SparseMatrix<double> L(m, m);
    L.setFromTriplets(triplets.begin(), triplets.end());
    if (analyze) lu.analyzePattern(L);
    lu.factorize(L);
    if (lu.info() != Eigen::Success) throw PipelineError("tutte_embedding: the mean-value Laplacian is singular");
    const Eigen::MatrixXd X = lu.solve(rhs);
    if (lu.info() != Eigen::Success || !X.allFinite()) throw PipelineError("tutte_embedding: the solve failed");
    for (int v = 0; v < n; ++v) {
      const int u = unknown[static_cast<size_t>(v)];
      if (u >= 0) result[s].row(v) = X.row(u);
    }
  };
  // Two threads share the sets (a squeezed disk has about ten, each an LU factorisation: KLU's, which calls no BLAS,
  // so two can run at once); an exception on either is rethrown after both have finished.
  const int threads = weights.size() > 1 ? std::min(2, omp_get_max_threads()) : 1;
  std::array<std::exception_ptr, 2> failed;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    Eigen::KLU<Eigen::SparseMatrix<double>> lu;
    try {
      for (size_t s = static_cast<size_t>(t); s < weights.size(); s += static_cast<size_t>(nt)) {
        solve_set(s, lu, s == static_cast<size_t>(t));
      }
    } catch (...) {
      failed[static_cast<size_t>(t)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
  return result;
}

}  // namespace liftmap
