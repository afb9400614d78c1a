#include "map/map_meshes.h"

#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <thread>

#include "check/check_mesh.h"
#include "core/errors.h"
#include "core/seconds_since.h"
#include "core/thread_count_scope.h"
#include "core/total_area.h"
#include "flatten/distortion.h"
#include "flatten/flattening_checks.h"
#include "flatten/jacobian.h"
#include "io/landmarks.h"
#include "map/map_overlay.h"

namespace liftmap {

namespace {

using Clock = std::chrono::steady_clock;

/// The longest stretch without a progress line inside a convex subproblem.
constexpr double kProgressSeconds = 3;

// Barycentric coordinates of p in the triangle (a, b, c) of R^3, p assumed in (or very near) its plane.
std::array<double, 3> barycentric_3d(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  std::array<double, 3> w{(c - b).cross(p - b).dot(n) / nn, (a - c).cross(p - c).dot(n) / nn, 0.0};
  w[2] = 1.0 - w[0] - w[1];
  return w;
}

Eigen::Vector3d row3(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }

/// Everything needed to translate between one input mesh and its cut disk.
struct SideTranslator {
  const Eigen::MatrixXd* V_input = nullptr;
  const Eigen::MatrixXi* F_input = nullptr;
  const CutSide* side = nullptr;                   // points into the owning MapIndex
  std::vector<int> refined_to_cut;                 // a cut copy of each refined vertex
  std::vector<std::vector<int>> refined_of_input;  // refined (= disk) faces inside each input face

  SideTranslator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const CutSide& s)
      : V_input(&V), F_input(&F), side(&s) {
    refined_to_cut.assign(static_cast<size_t>(s.V.rows()), -1);
    for (Eigen::Index c = s.cut_to_refined.size() - 1; c >= 0; --c) {
      refined_to_cut[static_cast<size_t>(s.cut_to_refined(c))] = static_cast<int>(c);
    }
    refined_of_input.resize(static_cast<size_t>(F.rows()));
    for (Eigen::Index f = 0; f < s.face_to_input.size(); ++f) {
      refined_of_input[static_cast<size_t>(s.face_to_input(f))].push_back(static_cast<int>(f));
    }
  }

  /// A point of the disk (any kind) as a face point of the input mesh.
  [[nodiscard]] SurfacePoint to_input(const Mesh& disk, const SurfacePoint& p) const {
    const SurfacePoint q = as_face_point(disk, p);
    const int fc = q.face.idx;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += q.bary[static_cast<size_t>(k)] * row3(side->V, side->F(fc, k));
    const int fi = side->face_to_input(fc);
    const Eigen::MatrixXi& F = *F_input;
    // Through the refined corners' own input coordinates: exact combinatorics, no rounding of 3D positions.
    std::array<double, 3> w{0, 0, 0};
    bool exact = true;
    for (int k = 0; k < 3 && exact; ++k) {
      const auto c = reexpress_in_face(side->on_input[static_cast<size_t>(side->F(fc, k))], F, fi, &exact);
      for (size_t j = 0; j < 3; ++j) w[j] += q.bary[static_cast<size_t>(k)] * c[j];
    }
    if (!exact) w = barycentric_3d(x, row3(*V_input, F(fi, 0)), row3(*V_input, F(fi, 1)), row3(*V_input, F(fi, 2)));
    return SurfacePoint::in_face(FaceId(fi), clamp_barycentric(w));
  }

  /// A face point of the input mesh as a face point of the disk.
  [[nodiscard]] SurfacePoint to_disk(const SurfacePoint& p) const {
    const Eigen::MatrixXi& F = *F_input;
    const int fi = p.face.idx;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * row3(*V_input, F(fi, k));
    int best = -1;
    std::array<double, 3> best_w{};
    double best_min = -std::numeric_limits<double>::infinity();
    for (int fc : refined_of_input[static_cast<size_t>(fi)]) {
      const auto w = barycentric_3d(x, row3(side->V, side->F(fc, 0)), row3(side->V, side->F(fc, 1)),
                                    row3(side->V, side->F(fc, 2)));
      const double m = std::min({w[0], w[1], w[2]});
      if (m > best_min) {
        best_min = m;
        best = fc;
        best_w = w;
      }
    }
    if (best < 0 || best_min < -1e-9) {
      throw PipelineError("map: point of input face " + std::to_string(fi) + " is in none of its refined faces");
    }
    return SurfacePoint::in_face(FaceId(best), clamp_barycentric(best_w));
  }

  /// Position in R^3 of a face point of the input mesh.
  [[nodiscard]] Eigen::Vector3d position(const SurfacePoint& p) const {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += p.bary[static_cast<size_t>(k)] * row3(*V_input, (*F_input)(p.face.idx, k));
    return x;
  }
};

Eigen::Matrix2d jacobian_matrix(const Eigen::MatrixXd& P, int f) {
  const double alpha = P(f, 0), beta = P(f, 1), gamma = P(f, 2), delta = P(f, 3);
  Eigen::Matrix2d A;
  A << alpha + gamma, delta - beta, beta + delta, alpha - gamma;
  return A;
}

/// Per-sample distortion max(Sigma, 1/sigma) of the map from one disk to the other, J = A_target^-1 A_source.
void sample_map_distortion(const Mesh& source, const Eigen::MatrixXd& P_source, const Eigen::VectorXd& area_source,
                           const Mesh& target, const Eigen::MatrixXd& P_target, int n,
                           const std::function<SurfacePoint(const SurfacePoint&)>& map, Eigen::VectorXd& values,
                           Eigen::VectorXd& weights) {
  const int nf = source.n_faces();
  const int per_face = n * n;
  values.resize(static_cast<Eigen::Index>(nf) * per_face);
  weights.resize(values.size());
  const std::vector<std::array<double, 3>> samples = sub_triangle_centroids(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (int f = 0; f < nf; ++f) {
    const Eigen::Matrix2d A = jacobian_matrix(P_source, f);
    for (int s = 0; s < per_face; ++s) {
      const SurfacePoint y =
          as_face_point(target, map(SurfacePoint::in_face(FaceId(f), samples[static_cast<size_t>(s)])));
      const Eigen::Matrix2d J = jacobian_matrix(P_target, y.face.idx).inverse() * A;
      const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix2d>(J).singularValues();
      const auto k = static_cast<Eigen::Index>(f) * per_face + s;
      values(k) = std::max(sv(0), 1.0 / sv(1));
      weights(k) = area_source(f) / per_face;
    }
  }
}

}  // namespace

DistortionStats weighted_stats(const Eigen::VectorXd& values, const Eigen::VectorXd& weights) {
  DistortionStats s;
  if (values.size() == 0) return s;
  std::vector<int> order(static_cast<size_t>(values.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values(a) < values(b); });
  const double total = weights.sum();
  s.mean = values.dot(weights) / total;
  s.max = values.maxCoeff();
  double acc = 0;
  bool have_median = false;
  for (int i : order) {
    acc += weights(i);
    if (!have_median && acc >= 0.5 * total) {
      s.median = values(i);
      have_median = true;
    }
    if (acc >= 0.95 * total) {
      s.p95 = values(i);
      break;
    }
  }
  return s;
}

std::vector<std::array<double, 3>> sub_triangle_centroids(int n) {
  std::vector<std::array<double, 3>> samples;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j + i < n; ++j) {
      samples.push_back({(i + 1.0 / 3) / n, (j + 1.0 / 3) / n, 1.0 - (i + j + 2.0 / 3) / n});
      if (i + j + 1 < n) samples.push_back({(i + 2.0 / 3) / n, (j + 2.0 / 3) / n, 1.0 - (i + j + 4.0 / 3) / n});
    }
  }
  return samples;
}

struct MapIndex {
  Eigen::MatrixXd VA, VB;
  Eigen::MatrixXi FA, FB;
  CutSide cut_a, cut_b;
  Mesh input_a, input_b;
  std::unique_ptr<SideTranslator> a, b;
};

namespace {

using Progress = std::function<void(const std::string&, const std::string&)>;

/// Runs a stage whose input the pipeline made (cut disks, flattenings) from checked inputs: an InvalidInputError
/// it throws (a precondition of a stage's function, e.g. a degenerate face of a cut disk) is a failure of the
/// pipeline on valid input, so it becomes a PipelineError (exit 5) naming the stage, not a bad-input error (exit 4).
template <typename Stage>
void on_checked_input(const char* stage, Stage&& run) {
  try {
    run();
  } catch (const InvalidInputError& e) {
    throw PipelineError(std::string(stage) + ": " + e.what() + " (on valid input)");
  }
}

/// Step 1: both meshes cut to disks along the same tree (paper §3.1); the disks' connectivity and positions.
void cut_stage(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
               const Eigen::MatrixXi& FB, const std::vector<SurfacePoint>& landmarks_a,
               const std::vector<SurfacePoint>& landmarks_b, const MapOptions& options, const Progress& progress,
               MapResult& r) {
  const auto t0 = Clock::now();
  progress("cut",
           "cutting both meshes to disks along a tree through " + std::to_string(landmarks_a.size()) + " landmarks");
  r.cut = cut_meshes(VA, FA, VB, FB, landmarks_a, landmarks_b, options.cut);
  r.seconds.cut = seconds_since(t0);
  r.disk_a = Mesh(r.cut.a.F_cut, static_cast<int>(r.cut.a.cut_to_refined.size()));
  r.disk_b = Mesh(r.cut.b.F_cut, static_cast<int>(r.cut.b.cut_to_refined.size()));
  r.disk_va = r.cut.a.V(r.cut.a.cut_to_refined, Eigen::all);
  r.disk_vb = r.cut.b.V(r.cut.b.cut_to_refined, Eigen::all);
  std::ostringstream s;
  s << "done in " << r.seconds.cut << " s: disks of " << r.disk_a.n_faces() << " and " << r.disk_b.n_faces()
    << " faces, " << r.cut.nu.size() << " boundary vertices each";
  progress("cut", s.str());
}

/// Step 2: the joint flattening (Algorithm 2), with a progress line after every outer iteration and every few
/// seconds inside a long subproblem.
void flatten_stage(const MapOptions& options, const Progress& progress, MapResult& r) {
  const auto t0 = Clock::now();
  FlatteningDisk m{&r.disk_a, r.disk_va, {}};
  FlatteningDisk n{&r.disk_b, r.disk_vb, {}};
  for (const auto& pair : r.cut.nu) {
    m.boundary.emplace_back(pair[0]);
    n.boundary.emplace_back(pair[1]);
  }
  progress("flatten", "start (Tutte, drifted where it squeezes) and convex subproblems (10)");
  JointFlattenOptions flatten_options = options.flatten;
  // Inside a long subproblem, a line every few seconds: its Newton steps so far, barrier parameter, objective.
  auto last_line = Clock::now();
  size_t outer = 1;
  int steps = 0;
  flatten_options.solver.on_step = [&](const SubproblemStep& step) {
    if (options.flatten.solver.on_step) options.flatten.solver.on_step(step);
    ++steps;
    if (seconds_since(last_line) < kProgressSeconds) return;
    last_line = Clock::now();
    std::ostringstream s;
    s << "iteration " << outer << ": " << steps << " Newton steps so far, t " << step.t << ", objective "
      << step.objective;
    progress("flatten", s.str());
  };
  flatten_options.on_iteration = [&](size_t i, const JointFlattenIteration& it) {
    outer = i + 1;
    steps = 0;
    last_line = Clock::now();
    if (options.flatten.on_iteration) options.flatten.on_iteration(i, it);
    std::ostringstream s;
    s << (i == 0 ? "start" : "iteration " + std::to_string(i)) << ": energy " << it.energy << ", max distortion "
      << it.max_distortion << ", smallest face " << it.min_area_ratio << " of the mean";
    if (i > 0) {
      s << " (" << it.seconds << " s, " << it.newton_steps << " Newton steps"
        << (it.subproblem_converged ? "" : ", subproblem gap not certified")
        << (it.subproblem_refined ? ", solved again to a finer gap" : "") << ")";
    }
    progress("flatten", s.str());
  };
  r.flattening = joint_flatten(m, n, flatten_options);
  r.seconds.flatten = seconds_since(t0);
  if (!r.flattening.stop_reason.empty()) progress("flatten", "stopped early: " + r.flattening.stop_reason);
  if (r.flattening.last_subproblem_steps > 0) {
    progress("flatten",
             "converged: a last subproblem, certified to a gap below the tolerance, found no lower energy (" +
                 std::to_string(r.flattening.last_subproblem_steps) + " Newton steps)");
  }
  r.scale_a = r.flattening.scale_m;
  r.scale_b = r.flattening.scale_n;
}

/// Step 3: the lifted bijection (§3.4), and the maps expressed on the input meshes (each input vertex's image as
/// a face point of the other input mesh).
void lift_stage(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                const Eigen::MatrixXi& FB, const MapOptions& options, const Progress& progress, MapResult& r) {
  const auto n_cut_a = static_cast<int>(r.cut.a.cut_to_refined.size());
  const auto n_cut_b = static_cast<int>(r.cut.b.cut_to_refined.size());
  const auto t0 = Clock::now();
  progress("lift", "lifting the flattenings into the bijection");
  Eigen::MatrixXi nu(static_cast<Eigen::Index>(r.cut.nu.size()), 2);
  for (size_t i = 0; i < r.cut.nu.size(); ++i) nu.row(static_cast<Eigen::Index>(i)) << r.cut.nu[i][0], r.cut.nu[i][1];
  r.bijection =
      std::make_shared<LiftedBijection>(r.disk_a, r.flattening.Phi, r.disk_b, r.flattening.Psi, nu, options.lift);
  auto index = std::make_shared<MapIndex>();
  index->VA = VA;
  index->FA = FA;
  index->VB = VB;
  index->FB = FB;
  index->input_a = Mesh(FA, static_cast<int>(VA.rows()));
  index->input_b = Mesh(FB, static_cast<int>(VB.rows()));
  index->cut_a = r.cut.a;
  index->cut_b = r.cut.b;
  index->a = std::make_unique<SideTranslator>(index->VA, index->FA, index->cut_a);
  index->b = std::make_unique<SideTranslator>(index->VB, index->FB, index->cut_b);
  r.index = index;
  const SideTranslator& ta = *index->a;
  const SideTranslator& tb = *index->b;
  r.cut_a_to_b.resize(static_cast<size_t>(n_cut_a));
  r.cut_b_to_a.resize(static_cast<size_t>(n_cut_b));
  for (int c = 0; c < n_cut_a; ++c)
    r.cut_a_to_b[static_cast<size_t>(c)] = as_face_point(r.disk_b, r.bijection->f()[VertexId(c)]);
  for (int c = 0; c < n_cut_b; ++c)
    r.cut_b_to_a[static_cast<size_t>(c)] = as_face_point(r.disk_a, r.bijection->g()[VertexId(c)]);
  // Input vertex i is refined vertex i (refinement only appends vertices).
  auto input_map = [](const Eigen::MatrixXd& V, const SideTranslator& from, const SideTranslator& to,
                      const Mesh& disk_to, const std::vector<SurfacePoint>& cut_map, const char* name) {
    std::vector<SurfacePoint> out(static_cast<size_t>(V.rows()));
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      if (from.side->V.row(v) != V.row(v)) {
        throw PipelineError(std::string("map: refined vertex ") + std::to_string(v) + " of mesh " + name +
                            " is not input vertex " + std::to_string(v));
      }
      const int c = from.refined_to_cut[static_cast<size_t>(v)];
      out[static_cast<size_t>(v)] = to.to_input(disk_to, cut_map[static_cast<size_t>(c)]);
    }
    return out;
  };
  r.a_to_b = input_map(VA, ta, tb, r.disk_b, r.cut_a_to_b, "A");
  r.b_to_a = input_map(VB, tb, ta, r.disk_a, r.cut_b_to_a, "B");
  r.seconds.lift = seconds_since(t0);
  progress("lift", "done in " + std::to_string(r.seconds.lift) + " s");
}

/// The common refinement of A and B under the map (overlay_of_map).
void overlay_stage(const Progress& progress, MapResult& r) {
  const auto t0 = Clock::now();
  progress("overlay", "intersecting the two flattenings");
  r.overlay = overlay_of_map(r, &r.overlay_agreement);
  r.seconds.overlay = seconds_since(t0);
  progress("overlay", "done in " + std::to_string(r.seconds.overlay) + " s: " + std::to_string(r.overlay.F.rows()) +
                          " triangles, " + std::to_string(r.overlay.VA.rows()) + " vertices");
}

}  // namespace

namespace {

/// The overlay's checks (check_overlay) and the agreement of the map with it at every overlay vertex.
void verify_overlay(const MapResult& r, MapVerification& ver) {
  const MapIndex& index = *r.index;
  ver.overlay = check_overlay(r.overlay, index.VA, index.FA, index.VB, index.FB);
  ver.overlay_vertex_error = r.overlay_agreement;
  const OverlayCheck& c = ver.overlay;
  auto require = [&](bool ok, const std::string& what) {
    if (!ok) ver.failures.push_back(what);
  };
  require(std::max(c.area_error_a, c.area_error_b) < 1e-12,
          "overlay area error " + figure(std::max(c.area_error_a, c.area_error_b)) + " >= 1e-12");
  require(c.uncovered_faces_a + c.uncovered_faces_b == 0,
          "the overlay leaves " + std::to_string(c.uncovered_faces_a + c.uncovered_faces_b) + " input faces uncovered");
  require(c.flipped_a + c.flipped_b == 0,
          "the overlay has " + std::to_string(c.flipped_a + c.flipped_b) + " flipped triangles");
  require(ver.overlay_vertex_error < 1e-12, "overlay vertex error " + figure(ver.overlay_vertex_error) + " >= 1e-12");
}

}  // namespace

MapVerification verify_map(const MapResult& r, const std::vector<SurfacePoint>& landmarks_a,
                           const std::vector<SurfacePoint>& landmarks_b) {
  const MapIndex& index = *r.index;
  const Eigen::MatrixXd& VA = index.VA;
  const Eigen::MatrixXd& VB = index.VB;
  const Eigen::MatrixXi& FA = index.FA;
  const Eigen::MatrixXi& FB = index.FB;
  const SideTranslator& ta = *index.a;
  const SideTranslator& tb = *index.b;
  const auto n_cut_a = static_cast<int>(r.cut.a.cut_to_refined.size());
  const auto n_cut_b = static_cast<int>(r.cut.b.cut_to_refined.size());
  MapVerification ver;
  const Eigen::MatrixXd& Phi = r.flattening.Phi;
  const Eigen::MatrixXd& Psi = r.flattening.Psi;
  {
    const Eigen::VectorXd da = signed_double_areas(r.cut.a.F_cut, Phi);
    const Eigen::VectorXd db = signed_double_areas(r.cut.b.F_cut, Psi);
    ver.min_orientation = std::min(da.minCoeff() / da.mean(), db.minCoeff() / db.mean());
    const Eigen::VectorXd sa = angle_sums(r.disk_a, Phi), sb = angle_sums(r.disk_b, Psi);
    for (const auto& pair : r.cut.nu) {
      ver.max_boundary_angle_sum = std::max({ver.max_boundary_angle_sum, sa(pair[0]), sb(pair[1])});
    }
  }
  const double diameter = (Phi.colwise().maxCoeff() - Phi.colwise().minCoeff()).norm();
  for (int c = 0; c < n_cut_a; ++c) {
    const Eigen::RowVectorXd z = interpolate(r.disk_b, Psi, r.bijection->f()[VertexId(c)]);
    ver.lifting_residual = std::max(ver.lifting_residual, (z - Phi.row(c)).norm() / diameter);
  }
  for (int c = 0; c < n_cut_b; ++c) {
    const Eigen::RowVectorXd z = interpolate(r.disk_a, Phi, r.bijection->g()[VertexId(c)]);
    ver.lifting_residual = std::max(ver.lifting_residual, (z - Psi.row(c)).norm() / diameter);
  }
  const double sqrt_area_a = std::sqrt(total_area(VA, FA)), sqrt_area_b = std::sqrt(total_area(VB, FB));
  double round_trip = 0;  // the largest of order-independent values: the same on any number of threads
#pragma omp parallel for schedule(dynamic, 256) reduction(max : round_trip)
  for (Eigen::Index v = 0; v < VA.rows(); ++v) {
    const SurfacePoint back = evaluate_map(r, Side::kB, r.a_to_b[static_cast<size_t>(v)]);
    round_trip = std::max(round_trip, (ta.position(back) - row3(VA, static_cast<int>(v))).norm() / sqrt_area_a);
  }
#pragma omp parallel for schedule(dynamic, 256) reduction(max : round_trip)
  for (Eigen::Index v = 0; v < VB.rows(); ++v) {
    const SurfacePoint back = evaluate_map(r, Side::kA, r.b_to_a[static_cast<size_t>(v)]);
    round_trip = std::max(round_trip, (tb.position(back) - row3(VB, static_cast<int>(v))).norm() / sqrt_area_b);
  }
  ver.round_trip_error = round_trip;
  // A vertex landmark's image is the input map's; any other is evaluated (it is a refined vertex, so exactly).
  const auto image = [&](Side side, const SurfacePoint& x) {
    const std::vector<SurfacePoint>& input_map = side == Side::kA ? r.a_to_b : r.b_to_a;
    return x.kind == SurfacePoint::Kind::kVertex ? input_map[static_cast<size_t>(x.vertex.idx)]
                                                 : evaluate_map(r, side, x);
  };
  for (size_t i = 0; i < landmarks_a.size(); ++i) {
    const Eigen::Vector3d pa = ta.position(as_face_point(index.input_a, landmarks_a[i]));
    const Eigen::Vector3d pb = tb.position(as_face_point(index.input_b, landmarks_b[i]));
    ver.landmark_error =
        std::max(ver.landmark_error, (tb.position(image(Side::kA, landmarks_a[i])) - pb).norm() / sqrt_area_b);
    ver.landmark_error =
        std::max(ver.landmark_error, (ta.position(image(Side::kB, landmarks_b[i])) - pa).norm() / sqrt_area_a);
  }
  auto require = [&](bool ok, const std::string& what) {
    if (!ok) ver.failures.push_back(what);
  };
  require(ver.min_orientation > 0,
          "a flattened face is flipped or degenerate (min orientation " + figure(ver.min_orientation) + ")");
  require(ver.max_boundary_angle_sum < 2 * M_PI,
          "a boundary angle sum reaches 2 pi (" + figure(ver.max_boundary_angle_sum) + ")");
  require(ver.lifting_residual < 1e-9, "lifting residual " + figure(ver.lifting_residual) + " >= 1e-9");
  require(ver.round_trip_error < 1e-9, "round trip error " + figure(ver.round_trip_error) + " >= 1e-9");
  require(ver.landmark_error < 1e-12, "landmark error " + figure(ver.landmark_error) + " >= 1e-12");
  if (r.overlay.F.rows() > 0) verify_overlay(r, ver);
  ver.passed = ver.failures.empty();

  return ver;
}

void map_distortion(MapResult& r, int samples_per_edge) {
  const Eigen::MatrixXd& Phi = r.flattening.Phi;
  const Eigen::MatrixXd& Psi = r.flattening.Psi;
  const JacobianOperator op_a = jacobian_operator(r.disk_va * r.scale_a, r.cut.a.F_cut);
  const JacobianOperator op_b = jacobian_operator(r.disk_vb * r.scale_b, r.cut.b.F_cut);
  const Eigen::MatrixXd P_a = similarity_parts(op_a, r.cut.a.F_cut, Phi * r.scale_a);
  const Eigen::MatrixXd P_b = similarity_parts(op_b, r.cut.b.F_cut, Psi * r.scale_a);
  r.distortion_phi = weighted_stats(true_distortion(P_a), op_a.area);
  r.distortion_psi = weighted_stats(true_distortion(P_b), op_b.area);
  const int n_samples = std::max(1, samples_per_edge);
  const LiftedBijection& bij = *r.bijection;
  Eigen::VectorXd g_values, g_weights;
  sample_map_distortion(
      r.disk_a, P_a, op_a.area, r.disk_b, P_b, n_samples, [&](const SurfacePoint& x) { return bij.evaluate_f(x); },
      r.f_samples, r.f_weights);
  sample_map_distortion(
      r.disk_b, P_b, op_b.area, r.disk_a, P_a, n_samples, [&](const SurfacePoint& y) { return bij.evaluate_g(y); },
      g_values, g_weights);
  r.distortion_f = weighted_stats(r.f_samples, r.f_weights);
  r.distortion_g = weighted_stats(g_values, g_weights);
}

MapResult map_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<VertexId>& landmarks_a,
                     const std::vector<VertexId>& landmarks_b, const MapOptions& options) {
  return map_meshes(VA, FA, VB, FB, vertex_points(landmarks_a), vertex_points(landmarks_b), options);
}

MapResult map_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<SurfacePoint>& landmarks_a,
                     const std::vector<SurfacePoint>& landmarks_b, const MapOptions& options) {
  const auto t_start = Clock::now();
  const Progress progress = [&](const std::string& stage, const std::string& message) {
    if (options.progress) options.progress(stage, message);
  };
  require_mappable(check_mesh(VA, FA), options.name_a);
  require_mappable(check_mesh(VB, FB), options.name_b);
  if (landmarks_a.size() != landmarks_b.size() || landmarks_a.size() < 2) {
    throw InvalidInputError("map: need at least 2 corresponding landmarks on each mesh");
  }
  require_landmarks_apart(landmarks_a, VA, FA, "map: " + options.name_a);
  require_landmarks_apart(landmarks_b, VB, FB, "map: " + options.name_b);
  if (options.flatten.p != 2 && !std::isinf(options.flatten.p)) {
    throw InvalidInputError("map: p must be 2 or infinity, not " + figure(options.flatten.p));
  }
  const ThreadCountScope threads(options.threads);
  MapResult r;
  cut_stage(VA, FA, VB, FB, landmarks_a, landmarks_b, options, progress, r);
  // From here on every input has been checked: a complaint about the data is about data the pipeline made.
  on_checked_input("flatten", [&] { flatten_stage(options, progress, r); });
  on_checked_input("lift", [&] { lift_stage(VA, FA, VB, FB, options, progress, r); });
  if (options.overlay) on_checked_input("overlay", [&] { overlay_stage(progress, r); });
  const auto t0 = Clock::now();
  r.verification = verify_map(r, landmarks_a, landmarks_b);
  map_distortion(r, options.distortion_samples_per_edge);
  r.seconds.verify = seconds_since(t0);
  r.seconds.total = seconds_since(t_start);
  progress("verify", r.verification.passed ? "passed" : "FAILED: " + r.verification.failures.front());
  return r;
}

namespace {

/// The index of `value` in `accepted`. \throw UsageError naming the option and the accepted values otherwise.
size_t choice(const std::string& option, const std::string& value, const std::vector<std::string>& accepted) {
  for (size_t i = 0; i < accepted.size(); ++i) {
    if (value == accepted[i]) return i;
  }
  std::string list;
  for (const std::string& a : accepted) list += (list.empty() ? "" : ", ") + a;
  throw UsageError(option + ": '" + value + "' is not one of " + list);
}

}  // namespace

void set_map_choices(MapOptions& options, const MapChoiceNames& names) {
  options.flatten.p = choice("p", names.p, {"2", "inf"}) == 1 ? std::numeric_limits<double>::infinity() : 2.0;
  options.flatten.h = choice("h", names.h, {"eq3", "eq2"}) == 1 ? DistortionCombiner::kMax : DistortionCombiner::kNorm;
  constexpr std::array kSolvers = {SubproblemSolver::kAuto, SubproblemSolver::kBarrier, SubproblemSolver::kPrimalDual};
  options.flatten.method = kSolvers[choice("solver", names.solver, {"auto", "barrier", "primal-dual"})];
  options.cut.tree =
      choice("tree", names.tree, {"mst", "path"}) == 1 ? CutOptions::Tree::kPath : CutOptions::Tree::kMinimumSpanning;
}

int MapOptionLimits::max_threads() { return 4 * static_cast<int>(std::max(1U, std::thread::hardware_concurrency())); }

SurfacePoint evaluate_map(const MapResult& map, Side side, const SurfacePoint& x) {
  const MapIndex& index = *map.index;
  const bool from_a = side == Side::kA;
  const SideTranslator& from = from_a ? *index.a : *index.b;
  const SideTranslator& to = from_a ? *index.b : *index.a;
  const SurfacePoint on_disk = from.to_disk(as_face_point(from_a ? index.input_a : index.input_b, x));
  const SurfacePoint image = from_a ? map.bijection->evaluate_f(on_disk) : map.bijection->evaluate_g(on_disk);
  return to.to_input(from_a ? map.disk_b : map.disk_a, image);
}

SurfacePoint disk_to_input(const MapResult& map, Side side, const SurfacePoint& x) {
  const bool a = side == Side::kA;
  return (a ? *map.index->a : *map.index->b).to_input(a ? map.disk_a : map.disk_b, x);
}

}  // namespace liftmap
