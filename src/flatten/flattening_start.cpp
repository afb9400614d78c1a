#include "flatten/flattening_start.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/edge_graph_distance.h"
#include "core/errors.h"
#include "flatten/flattening_checks.h"
#include "flatten/tutte.h"

namespace liftmap {

namespace {

/// Smallest face area over the mean (signed areas: <= 0 if a face is flipped or degenerate).
double min_area_ratio(const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  if (F.rows() == 0) return 1;
  const Eigen::VectorXd a = signed_double_areas(F, U);
  return a.minCoeff() / (a.sum() / static_cast<double>(a.size()));
}

/// Per face, its share of the planar area over its share of the surface's (<= 0: flipped or degenerate).
Eigen::VectorXd relative_areas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  const Eigen::VectorXd a2 = signed_double_areas(F, U);
  Eigen::VectorXd a3(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d e1 = V.row(F(f, 1)) - V.row(F(f, 0)), e2 = V.row(F(f, 2)) - V.row(F(f, 0));
    a3(f) = e1.cross(e2).norm();
  }
  return (a2.array() / a3.array()) * (a3.sum() / a2.sum());
}

/// Per vertex, how much the faces around it are squeezed: c_v in [0, 1] rises from 0 where every face's relative
/// area is above 1e-2 to 1 where one is below 1e-5 (or flipped or degenerate).
std::vector<double> squeeze(const Mesh& mesh, const Eigen::MatrixXi& F, const Eigen::VectorXd& relative) {
  std::vector<double> c(static_cast<size_t>(mesh.n_vertices()), 0.0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double shrink = relative(f) > 0 ? -std::log10(relative(f)) : 300.0;
    const double cf = std::clamp((shrink - 2) / 3, 0.0, 1.0);
    for (int k = 0; k < 3; ++k) c[static_cast<size_t>(F(f, k))] = std::max(c[static_cast<size_t>(F(f, k))], cf);
  }
  return c;
}

}  // namespace

FlatteningStart flattening_start(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& boundary,
                                 const Eigen::MatrixXd& B, const std::function<double(const Eigen::MatrixXd&)>& energy,
                                 const FlatteningStartOptions& options) {
  const std::vector<double> depth = edge_graph_distances(mesh, V, boundary);
  const Eigen::MatrixXi F = mesh.faces();
  FlatteningStart best;
  best.chosen.energy = std::numeric_limits<double>::infinity();
  const auto consider = [&](Eigen::MatrixXd U, double drift, bool local) {
    FlatteningStartCandidate c{.drift = drift,
                               .local = local,
                               .energy = std::numeric_limits<double>::infinity(),
                               .min_area_ratio = min_area_ratio(F, U)};
    if (c.min_area_ratio > 0) c.energy = energy(U);
    best.candidates.push_back(c);
    if (c.energy < best.chosen.energy || best.U.size() == 0) {
      best.chosen = c;
      best.U = std::move(U);
    }
  };
  Eigen::MatrixXd plain = tutte_embedding(mesh, V, boundary, B);
  const Eigen::VectorXd relative = relative_areas(V, F, plain);
  const std::vector<double> local = squeeze(mesh, F, relative);
  consider(std::move(plain), 0, false);
  if (relative.minCoeff() >= options.min_relative_area) return best;
  best.squeezed = true;
  std::vector<TutteWeights> tried;
  for (const double d : options.drifts) {
    tried.push_back({.depth = depth, .drift = d, .drift_scale = local});
    tried.push_back({.depth = depth, .drift = d, .drift_scale = {}});
  }
  std::vector<Eigen::MatrixXd> embeddings = tutte_embeddings(mesh, V, boundary, B, tried);
  for (size_t i = 0; i < tried.size(); ++i) {
    consider(std::move(embeddings[i]), tried[i].drift, !tried[i].drift_scale.empty());
  }
  if (!(best.chosen.min_area_ratio > 0)) {
    throw PipelineError("flattening_start: every embedding tried has a flipped or degenerate face (smallest area " +
                        std::to_string(best.chosen.min_area_ratio) + " of the mean)");
  }
  return best;
}

}  // namespace liftmap
