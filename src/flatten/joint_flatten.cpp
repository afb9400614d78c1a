#include "flatten/joint_flatten.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "core/seconds_since.h"
#include "core/total_area.h"
#include "flatten/barrier_solver.h"
#include "flatten/boundary_loop.h"
#include "flatten/flattening_checks.h"
#include "flatten/jacobian.h"
#include "flatten/joint_start_relaxation.h"
#include "flatten/primal_dual_solver.h"
#include "flatten/subproblem_faces.h"
#include "flatten/symmetric_dirichlet.h"
#include "flatten/tutte.h"

namespace liftmap {

namespace {

/// Checks that `boundary` is the disk's boundary loop, counter-clockwise, from any start.
void check_boundary(const FlatteningDisk& d, const char* name) {
  if (d.mesh == nullptr) throw InvalidInputError(std::string("joint_flatten: disk ") + name + " has no mesh");
  if (d.V.rows() != d.mesh->n_vertices() || d.V.cols() != 3) {
    throw InvalidInputError(std::string("joint_flatten: V of disk ") + name + " must be #V by 3");
  }
  const std::vector<VertexId> loop = ccw_boundary_loop(*d.mesh);
  if (loop.size() != d.boundary.size()) {
    throw InvalidInputError(std::string("joint_flatten: the boundary of disk ") + name + " has " +
                            std::to_string(loop.size()) + " vertices, " + std::to_string(d.boundary.size()) + " given");
  }
  size_t start = 0;
  while (start < loop.size() && loop[start] != d.boundary[0]) ++start;
  for (size_t i = 0; i < loop.size(); ++i) {
    if (start == loop.size() || loop[(start + i) % loop.size()] != d.boundary[i]) {
      throw InvalidInputError(std::string("joint_flatten: the boundary of disk ") + name +
                              " is not its boundary loop in counter-clockwise order");
    }
  }
}

/// Cumulative boundary arc length, as a fraction of the loop length, at each boundary vertex.
Eigen::VectorXd arc_fractions(const Eigen::MatrixXd& V, const std::vector<VertexId>& loop) {
  const auto nb = static_cast<Eigen::Index>(loop.size());
  Eigen::VectorXd s = Eigen::VectorXd::Zero(nb);
  double total = 0;
  for (Eigen::Index i = 0; i < nb; ++i) {
    const double l =
        (V.row(loop[static_cast<size_t>((i + 1) % nb)].idx) - V.row(loop[static_cast<size_t>(i)].idx)).norm();
    if (i + 1 < nb) s(i + 1) = total + l;
    total += l;
  }
  return s / total;
}

double energy_of(const SubproblemMesh& mesh, const Eigen::MatrixXd& U, const JointFlattenOptions& options,
                 double& max_distortion) {
  const Eigen::MatrixXd P = similarity_parts(mesh.jacobian, mesh.F, U);
  max_distortion = std::max(max_distortion, true_distortion(P).maxCoeff());
  return distortion_energy(face_distortion(P, options.h), mesh.jacobian.area, options.p);
}

}  // namespace

Eigen::MatrixXd mesh_positions(const ConvexSubproblem& problem, int k, const Eigen::MatrixXd& X) {
  const SubproblemMesh& mesh = problem.meshes[static_cast<size_t>(k)];
  Eigen::MatrixXd U(static_cast<Eigen::Index>(mesh.slot.size()), 2);
  for (size_t v = 0; v < mesh.slot.size(); ++v) {
    U.row(static_cast<Eigen::Index>(v)) =
        mesh.slot[v] >= 0 ? Eigen::RowVector2d(X.row(mesh.slot[v])) : Eigen::RowVector2d::Zero();
  }
  return U;
}

void set_rotations(ConvexSubproblem& problem, const Eigen::MatrixXd& X) {
  for (int k = 0; k < 3; ++k) {
    SubproblemMesh& mesh = k < 2 ? problem.meshes[static_cast<size_t>(k)] : problem.ghosts;
    if (mesh.F.rows() == 0) continue;
    Eigen::MatrixXd U(static_cast<Eigen::Index>(mesh.slot.size()), 2);
    for (size_t v = 0; v < mesh.slot.size(); ++v) {
      U.row(static_cast<Eigen::Index>(v)) =
          mesh.slot[v] >= 0 ? Eigen::RowVector2d(X.row(mesh.slot[v])) : Eigen::RowVector2d::Zero();
    }
    mesh.theta = polar_rotations(similarity_parts(mesh.jacobian, mesh.F, U));
  }
}

void place_ghost_vertices(ConvexSubproblem& problem, Eigen::MatrixXd& X) {
  SubproblemMesh& g = problem.ghosts;
  const auto n_ghost_faces = g.F.rows();
  if (n_ghost_faces == 0) return;
  for (Eigen::Index f = 0; f < n_ghost_faces; f += 2) {
    const int v = g.F(f, 0), a = g.F(f, 1), gv = g.F(f, 2), b = g.F(f + 1, 2);
    const Eigen::Vector2d pv = X.row(v).transpose();
    const Eigen::Vector2d da = X.row(a).transpose() - pv, db = X.row(b).transpose() - pv;
    // The exterior wedge at v runs counter-clockwise from da to db (the interior, on the left of the
    // counter-clockwise boundary, from db to da); its angle is 2 pi minus v's angle sum. At a convex corner
    // (exterior angle above pi, every corner of the Tutte start) its bisector is -(da^ + db^); at a reflex one (below
    // pi, e.g. along a cut path's tip) it is +(da^ + db^), where -(da^ + db^) would point into the disk.
    const Eigen::Vector2d sum = da.normalized() + db.normalized();
    const double cross = da.x() * db.y() - da.y() * db.x();
    Eigen::Vector2d out;
    if (cross < 0) {
      out = -sum.normalized();
    } else if (cross > 0) {
      out = sum.normalized();
    } else {  // straight (exterior angle pi): the normal on the exterior side
      out = Eigen::Vector2d(-da.y(), da.x()).normalized();
    }
    X.row(gv) = (pv + 0.25 * (da.norm() + db.norm()) * out).transpose();
  }
  g.V = Eigen::MatrixXd::Zero(X.rows(), 3);
  g.V.leftCols(2) = X;
  g.jacobian = jacobian_operator(g.V, g.F);
}

JointFlattenProblem make_joint_flatten_problem(const FlatteningDisk& m, const FlatteningDisk& n,
                                               const JointFlattenOptions& options) {
  check_boundary(m, "M");
  check_boundary(n, "N");
  if (m.boundary.size() != n.boundary.size()) {
    throw InvalidInputError("joint_flatten: the boundaries have " + std::to_string(m.boundary.size()) + " and " +
                            std::to_string(n.boundary.size()) + " vertices; they must correspond one to one");
  }
  if (!(options.p >= 1)) throw InvalidInputError("joint_flatten: p must be 2 or infinity");
  const int nb = static_cast<int>(m.boundary.size());
  const std::array<const FlatteningDisk*, 2> disks{&m, &n};

  JointFlattenProblem jp;
  const double am = total_area(m.V, m.mesh->faces()), an = total_area(n.V, n.mesh->faces());
  if (options.normalize_area) {
    jp.scale_m = std::sqrt(std::numbers::pi / am);
    jp.scale_n = std::sqrt(std::numbers::pi / an);
  } else {
    jp.scale_m = jp.scale_n = std::sqrt(std::numbers::pi / (0.5 * (am + an)));
  }
  ConvexSubproblem& sp = jp.subproblem;
  sp.p = options.p;
  sp.h = options.h;

  // Slots: boundary (shared, in correspondence order), interior of M, interior of N, ghost vertices.
  int next = nb;
  for (int k = 0; k < 2; ++k) {
    const FlatteningDisk& d = *disks[static_cast<size_t>(k)];
    SubproblemMesh& sm = sp.meshes[static_cast<size_t>(k)];
    sm.F = d.mesh->faces();
    sm.V = d.V * (k == 0 ? jp.scale_m : jp.scale_n);
    sm.jacobian = jacobian_operator(sm.V, sm.F);
    sm.slot.assign(static_cast<size_t>(d.mesh->n_vertices()), -1);
    for (int i = 0; i < nb; ++i) sm.slot[static_cast<size_t>(d.boundary[static_cast<size_t>(i)].idx)] = i;
    for (int v = 0; v < d.mesh->n_vertices(); ++v) {
      if (sm.slot[static_cast<size_t>(v)] < 0 && !d.mesh->is_isolated(VertexId(v)))
        sm.slot[static_cast<size_t>(v)] = next++;
    }
    jp.F[static_cast<size_t>(k)] = sm.F;
  }
  const int n_mesh_slots = next;
  sp.n_slots = n_mesh_slots + (options.ghost_faces ? nb : 0);

  // Start: corresponding boundary vertices at the same point of the unit circle, interiors by flattening_start.
  const Eigen::VectorXd s = 0.5 * (arc_fractions(m.V, m.boundary) + arc_fractions(n.V, n.boundary));
  Eigen::MatrixXd B(nb, 2);
  for (int i = 0; i < nb; ++i) {
    const double a = 2 * std::numbers::pi * s(i);
    B.row(i) << std::cos(a), std::sin(a);
  }
  jp.X0 = Eigen::MatrixXd::Zero(sp.n_slots, 2);
  for (int k = 0; k < 2; ++k) {
    const FlatteningDisk& d = *disks[static_cast<size_t>(k)];
    const SubproblemMesh& sm = sp.meshes[static_cast<size_t>(k)];
    const auto energy = [&](const Eigen::MatrixXd& U) {
      double max_distortion = 0;
      return energy_of(sm, U, options, max_distortion);
    };
    FlatteningStart start = flattening_start(*d.mesh, d.V, d.boundary, B, energy);
    jp.start[static_cast<size_t>(k)] = start.chosen;
    Eigen::MatrixXd U = std::move(start.U);
    if (start.squeezed && options.start_optimization.max_iterations > 0) {
      std::vector<char> fixed(static_cast<size_t>(d.mesh->n_vertices()), 0);
      for (int v = 0; v < d.mesh->n_vertices(); ++v) {
        fixed[static_cast<size_t>(v)] = d.mesh->is_boundary(VertexId(v)) || d.mesh->is_isolated(VertexId(v));
      }
      SymmetricDirichletResult sd =
          minimize_symmetric_dirichlet(sm.jacobian, sm.F, fixed, U, options.start_optimization);
      jp.start_steps[static_cast<size_t>(k)] = sd.iterations;
      U = std::move(sd.U);
    }
    for (size_t v = 0; v < sm.slot.size(); ++v) {
      if (sm.slot[v] >= 0) jp.X0.row(sm.slot[v]) = U.row(static_cast<Eigen::Index>(v));
    }
  }

  // Ghost faces (v, a, g), (v, g, b) for boundary vertex v with neighbours a (before) and b (after): they close
  // v's one-ring through the ghost vertex g (placed by place_ghost_vertices).
  if (options.ghost_faces) {
    SubproblemMesh& g = sp.ghosts;
    g.F.resize(2 * nb, 3);
    g.slot.resize(static_cast<size_t>(sp.n_slots));
    for (int i = 0; i < sp.n_slots; ++i) g.slot[static_cast<size_t>(i)] = i;
    for (int i = 0; i < nb; ++i) {
      const int a = (i + nb - 1) % nb, b = (i + 1) % nb, gv = n_mesh_slots + i;
      g.F.row(2 * i) << i, a, gv;
      g.F.row(2 * i + 1) << i, gv, b;
    }
    place_ghost_vertices(sp, jp.X0);
    if (options.joint_start.newton.max_iterations > 0) {
      const auto relax_start = std::chrono::steady_clock::now();
      jp.cholesky = std::make_shared<SparseCholesky>();
      SymmetricDirichletResult r = relax_joint_start(sp, jp.X0, options.joint_start, jp.cholesky.get());
      jp.joint_start = {.steps = r.iterations,
                        .energy_before = r.energy_start,
                        .energy_after = r.energy,
                        .seconds = seconds_since(relax_start)};
      jp.X0 = std::move(r.U);
      place_ghost_vertices(sp, jp.X0);
    }
  }
  set_rotations(sp, jp.X0);
  return jp;
}

namespace {

/// The last outer iteration's relative energy decrease (E_{k-1} - E_k) / E_k; needs at least two iterates.
double last_relative_gain(const std::vector<JointFlattenIteration>& iterations) {
  const double before = iterations[iterations.size() - 2].energy, last = iterations.back().energy;
  return (before - last) / last;
}

/// The last outer iteration's rotation gain (Q_{k-1}(X_k) - E_k) / E_k: how far the energy (8) at its minimiser X_k,
/// with X_k's own polar rotations, lies below the objective (10a) the subproblem reached there with the rotations it
/// was solved with; 0 if the iteration records no subproblem (the start).
double last_rotation_gain(const std::vector<JointFlattenIteration>& iterations) {
  const JointFlattenIteration& last = iterations.back();
  if (!(last.subproblem_objective > 0)) return 0;
  return (last.subproblem_objective - last.energy) / last.energy;
}

}  // namespace

double subproblem_gap(const JointFlattenOptions& options, const std::vector<JointFlattenIteration>& iterations) {
  const double finest = options.solver.relative_gap;
  if (!(options.gap_fraction > 0)) return finest;
  const double coarsest = std::max(finest, options.max_subproblem_gap);
  if (iterations.size() < 2) return coarsest;
  return std::clamp(options.gap_fraction * last_relative_gain(iterations), finest, coarsest);
}

double start_gap(const JointFlattenOptions& options, const std::vector<JointFlattenIteration>& iterations,
                 bool relaxed_start) {
  if (iterations.size() < 2) {
    if (!relaxed_start || !(options.relaxed_start_gap_fraction > 0)) return 0;
    return options.relaxed_start_gap_fraction * subproblem_gap(options, iterations);
  }
  if (!(options.start_gap_fraction > 0)) return 0;
  const double gain = last_relative_gain(iterations);
  if (!(gain > 0)) return 0;
  const double gap = options.start_gap_fraction * gain;
  const double rotations = last_rotation_gain(iterations);
  if (!(options.rotation_gain_start_fraction > 0) || !(rotations > 0)) return gap;
  return std::min(gap, std::max(options.rotation_gain_start_fraction * rotations, 0.5 * options.solver.relative_gap));
}

bool can_refine(const JointFlattenOptions& options, const SubproblemSettings& solver) {
  return options.refined_gap_fraction > 0 &&
         options.refined_gap_fraction * options.relative_tolerance < solver.relative_gap;
}

bool uses_primal_dual(const JointFlattenOptions& options) {
  return options.method == SubproblemSolver::kPrimalDual ||
         (options.method == SubproblemSolver::kAuto && std::isinf(options.p));
}

namespace {

/// Checks that the iterate X can be lifted (no flipped or degenerate face, interior angle sums 2 pi, boundary ones
/// below 2 pi) and records its statistics in `it` (energies (8), max distortion, smallest face area over the mean);
/// keeps its flattenings in res if options.keep_iterates.
/// \throw PipelineError naming the outer iteration, or the vertex and disk, if a check fails.
void record_iterate(const JointFlattenProblem& jp, const std::array<const Mesh*, 2>& meshes, const Eigen::MatrixXd& X,
                    const JointFlattenOptions& options, JointFlattenResult& res, JointFlattenIteration& it) {
  double e[2];
  for (int k = 0; k < 2; ++k) {
    const Eigen::MatrixXd U = mesh_positions(jp.subproblem, k, X);
    const Eigen::VectorXd areas = signed_double_areas(jp.F[static_cast<size_t>(k)], U);
    const double ratio = areas.minCoeff() / areas.mean();
    it.min_area_ratio = k == 0 ? ratio : std::min(it.min_area_ratio, ratio);
    if ((areas.array() <= 0).any()) {
      throw PipelineError("joint_flatten: a face is flipped or degenerate in outer iteration " +
                          std::to_string(res.iterations.size()));
    }
    const Eigen::VectorXd sums = angle_sums(*meshes[static_cast<size_t>(k)], U);
    for (int v = 0; v < meshes[static_cast<size_t>(k)]->n_vertices(); ++v) {
      const VertexId vid(v);
      if (meshes[static_cast<size_t>(k)]->is_isolated(vid)) continue;
      const bool bad = meshes[static_cast<size_t>(k)]->is_boundary(vid)
                           ? !(sums(v) < 2 * std::numbers::pi)
                           : std::abs(sums(v) - 2 * std::numbers::pi) > 1e-6;
      if (bad) {
        throw PipelineError("joint_flatten: vertex " + std::to_string(v) + " of disk " + (k == 0 ? "M" : "N") +
                            " is not locally injective (angle sum " + std::to_string(sums(v)) + ")");
      }
    }
    e[k] = energy_of(jp.subproblem.meshes[static_cast<size_t>(k)], U, options, it.max_distortion);
    if (options.keep_iterates) (k == 0 ? res.Phi_iterates : res.Psi_iterates).push_back(U / jp.scale_m);
  }
  it.energy_m = e[0];
  it.energy_n = e[1];
  it.energy = e[0] + e[1];
}

}  // namespace

JointFlattenResult joint_flatten(const FlatteningDisk& m, const FlatteningDisk& n, const JointFlattenOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  JointFlattenProblem jp = make_joint_flatten_problem(m, n, options);
  ConvexSubproblem& sp = jp.subproblem;
  JointFlattenResult res;
  res.scale_m = jp.scale_m;
  res.scale_n = jp.scale_n;
  res.start = jp.start;
  res.start_steps = jp.start_steps;
  res.joint_start = jp.joint_start;
  const std::array<const Mesh*, 2> meshes{m.mesh, n.mesh};

  Eigen::MatrixXd X = jp.X0;
  {
    JointFlattenIteration it;
    record_iterate(jp, meshes, X, options, res, it);
    it.seconds = seconds_since(start_time);
    res.iterations.push_back(it);
    if (options.on_iteration) options.on_iteration(0, it);
  }
  SparseCholesky own_cholesky;
  SparseCholesky& cholesky = jp.cholesky != nullptr ? *jp.cholesky : own_cholesky;
  subproblem::AssemblyStructure assembly;  // shared by every subproblem: only rotations and ghost bounds change
  const bool primal_dual = uses_primal_dual(options);
  for (int iter = 0; iter < options.max_iterations; ++iter) {
    const auto t0 = std::chrono::steady_clock::now();
    place_ghost_vertices(sp, X);
    set_rotations(sp, X);
    SubproblemSettings solver = options.solver;
    solver.relative_gap = subproblem_gap(options, res.iterations);
    solver.barrier.initial_gap = start_gap(options, res.iterations, res.joint_start.steps > 0);
    const auto solve = [&](const SubproblemSettings& settings) {
      return primal_dual ? solve_convex_subproblem_primal_dual(sp, X, settings, cholesky, &assembly)
                         : solve_convex_subproblem(sp, X, settings, cholesky, &assembly);
    };
    const double start_objective = subproblem_objective(sp, X);
    SubproblemResult br;
    int earlier_steps = 0;  // Newton steps of a first solve that the finer one below replaced
    try {
      br = solve(solver);
      // The start X is feasible with objective E(X) (the rotations are its polar ones). A result not below that
      // at a gap coarser than the outer tolerance says only that X is within that gap of the optimum: the gap rule
      // expected more progress than is left. Solve again, finer than the tolerance (refined_gap_fraction). (A result
      // equal to its start: a Newton direction's dual point certified the start itself, dual_gap_decrement.)
      if (br.objective >= start_objective && can_refine(options, solver)) {
        earlier_steps = br.iterations;
        solver.relative_gap = options.refined_gap_fraction * options.relative_tolerance;
        solver.barrier.initial_gap = 0.5 * solver.relative_gap;
        br = solve(solver);
      }
    } catch (const PipelineError& e) {
      // The previous iterate passed every liftability check: it is the result, with the reason it is the last.
      std::ostringstream msg;
      msg << "the convex subproblem of outer iteration " << iter + 1 << " failed (" << e.what()
          << ") from flattenings of max distortion " << res.iterations.back().max_distortion
          << "; kept the flattenings of iteration " << iter;
      res.stop_reason = msg.str();
      break;
    }
    if (br.objective > start_objective) {
      // Certified within a gap g below the tolerance, yet not below the start: the subproblem's optimum is within
      // g of E(X), so no outer iteration from X can lower the energy by the tolerance. X is converged.
      if (br.converged() && solver.relative_gap < options.relative_tolerance) {
        res.converged = true;
        res.last_subproblem_steps = earlier_steps + br.iterations;
        break;
      }
      // Otherwise (only possible if the solver stopped early, far from the central path's end) a step would break
      // monotonicity. Every iterate is strictly feasible, so the previous one is a valid (liftable) result: stop
      // there rather than fail the whole map.
      res.stop_reason = "the convex subproblem of outer iteration " + std::to_string(iter + 1) + " ended at " +
                        std::to_string(br.objective) + ", above its start's " + std::to_string(start_objective) + " (" +
                        std::to_string(br.iterations) + " Newton steps, " +
                        (br.converged() ? "certified" : "not certified") + "); kept the flattenings of iteration " +
                        std::to_string(iter);
      break;
    }
    JointFlattenIteration it;
    it.subproblem_objective = br.objective;
    it.subproblem_gap = solver.relative_gap;
    it.newton_steps = earlier_steps + br.iterations;
    it.subproblem_refined = earlier_steps > 0;
    it.subproblem_converged = br.converged();
    it.stalled_centrings = br.stalled_centrings;
    it.subproblem_status = br.status;
    try {
      record_iterate(jp, meshes, br.X, options, res, it);
    } catch (const PipelineError& e) {  // the previous iterate passed these checks: it is the result
      res.stop_reason = std::string(e.what()) + "; kept the flattenings of iteration " + std::to_string(iter);
      if (options.keep_iterates) {
        res.Phi_iterates.resize(res.iterations.size());
        res.Psi_iterates.resize(res.iterations.size());
      }
      break;
    }
    it.seconds = seconds_since(t0);
    const double previous = res.iterations.back().energy;
    if (it.energy > previous) {
      // Only an inexact subproblem solution can do this (the start is feasible with objective E(X), and E of
      // the optimum is at most its objective): keep the previous iterate, so that the energy never rises.
      res.stop_reason = "outer iteration " + std::to_string(iter + 1) + " raised the energy from " +
                        std::to_string(previous) + " to " + std::to_string(it.energy) + " (subproblem " +
                        (br.converged() ? "certified" : "not certified") + "); kept the flattenings of iteration " +
                        std::to_string(iter);
      if (options.keep_iterates) {
        res.Phi_iterates.pop_back();
        res.Psi_iterates.pop_back();
      }
      break;
    }
    res.iterations.push_back(it);
    if (options.on_iteration) options.on_iteration(res.iterations.size() - 1, it);
    X = br.X;
    if (previous - it.energy < options.relative_tolerance * previous) {
      // Converged only if the subproblem was solved (certified): a small step from one that stalled or ran out of
      // Newton steps says nothing about the optimum.
      res.converged = br.converged();
      if (!res.converged) {
        res.stop_reason = "outer iteration " + std::to_string(iter + 1) + " lowered the energy by less than the " +
                          "tolerance, but its subproblem was not solved (" + to_string(br.status) +
                          "): the flattenings may be far from the optimum";
      }
      break;
    }
  }
  res.Phi = mesh_positions(sp, 0, X) / jp.scale_m;
  res.Psi = mesh_positions(sp, 1, X) / jp.scale_m;
  return res;
}

}  // namespace liftmap
