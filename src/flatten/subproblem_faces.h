#pragma once
/// The per-face data of the convex subproblem (10), shared by its two solvers (barrier_solver.cpp,
/// primal_dual_solver.cpp): each face's corner map, rotation and area, where its corners live in the unknowns,
/// and the sparsity pattern of the Schur system in the vertex coordinates that both solvers factorise
/// (newton_system.h).

#include <omp.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "core/seconds_since.h"
#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem.h"

namespace liftmap::subproblem {

using Mat46 = Eigen::Matrix<double, 4, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// The slot whose position is fixed (the objective is invariant under translation): its two coordinates are not
/// unknowns.
constexpr int kFixedSlot = 0;
/// Below this many faces the per-face loops run serially: thread start-up and contention cost more than they save.
constexpr int kParallelFaces = 4000;

/// Constant data of one face of either mesh.
struct FaceSetup {
  Mat46 S;                 // corners (u0,v0,u1,v1,u2,v2) -> (alpha,beta,gamma,delta)
  std::array<int, 6> pos;  // indices of the corners' coordinates in the position vector
  std::array<int, 6> var;  // indices in the unknowns (-1: the fixed gauge vertex)
  double cs = 1, sn = 0;   // rotation of eq. (7b)
  double w = 0;            // area |t_j|
  double bound = 0;        // ghost faces: upper bound of Sigma_j
  int mesh = 0;            // 0, 1: the two flattenings; 2: ghost face (constraint only)
  [[nodiscard]] bool ghost() const { return mesh == 2; }
};

struct Settings {
  bool h_max = false;
  bool p_inf = false;
};

/// The sum of term(j) over the faces j = 0 .. n - 1: the terms on the threads, their sum in face order, so that the
/// result is the same at any thread count (an OpenMP reduction adds each thread's partial sum, which rounds
/// differently with the number of threads). T: double or a fixed-size Eigen array.
template <class T, class Term>
T sum_over_faces(int n, Term&& term) {
  std::vector<T> terms(static_cast<size_t>(n));
#pragma omp parallel for schedule(static) if (n > kParallelFaces)
  for (int j = 0; j < n; ++j) terms[static_cast<size_t>(j)] = term(j);
  T sum = T{};
  if constexpr (!std::is_arithmetic_v<T>) sum.setZero();
  for (const T& t : terms) sum += t;
  return sum;
}

/// The per-face data of one subproblem, built once per call.
struct Setup {
  std::vector<FaceSetup> faces;
  int n_faces = 0;
  int n_pos = 0;
  int n_var = 0;
  Settings settings;
};

/// The faces of both meshes, then the ghost faces (bound still 0: set from the start, set_ghost_bounds).
/// \throw InvalidInputError if a mesh's sizes disagree or a face has no slot.
Setup make_setup(const ConvexSubproblem& problem);

/// make_setup(problem) after checking that X0 is #slots by 2 (at least two slots).
/// \throw InvalidInputError if it is not, or as make_setup.
Setup make_setup(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0);

/// Sets each ghost face's bound of Sigma_j to kGhostStretch times its Sigma_j at the positions `pos` (2 #slots).
void set_ghost_bounds(const Eigen::VectorXd& pos, Setup& s);

/// (alpha, beta, gamma, delta) of face j at the positions `pos` (2 #slots).
Eigen::Vector4d face_coordinates(const FaceSetup& fs, const Eigen::VectorXd& pos);

/// Sparse lower-triangular pattern of the Schur system and where each face's entries go.
struct Pattern {
  Eigen::SparseMatrix<double> A;
  std::vector<std::array<int, 36>> index;  // per face, entry (r, c) of K -> value index, -1 if not stored
};
/// The lower triangle of the sum of the faces' 6 x 6 corner blocks, over the unknown coordinates.
Pattern make_pattern(const Setup& s);

/// The same for any faces: var[j] the unknowns of face j's six corner coordinates (-1: fixed), n_var unknowns. The
/// diagonal is stored even for an unknown of no face.
Pattern make_pattern(const std::vector<std::array<int, 6>>& var, int n_var);

/// The faces in three lists for sums over faces into the Schur system and vectors over the unknowns, which faces
/// sharing a vertex would race on: lists[h] holds the faces whose unknowns all lie in half h of the factorisation's
/// split (SparseCholesky::unknown_halves; no face couples the two halves), lists[2] the others (a vertex in the
/// top of the elimination tree), each list in face order. Without a split, every face is in lists[2].
struct FacePartition {
  std::array<std::vector<int>, 3> lists;
};
FacePartition partition_faces(const Setup& s, const SparseCholesky& cholesky);

/// The Newton system's assembly structure for the faces of a Setup: its pattern and face partition, which depend only
/// on the faces' unknowns (FaceSetup::var). The subproblems of one flattening (joint_flatten) share them: only their
/// rotations and ghost bounds differ.
struct AssemblyStructure {
  Pattern pattern;
  FacePartition parts;
  std::vector<std::array<int, 6>> var;  ///< the faces' unknowns it was built for
};

/// `cache`, rebuilt for the faces of s unless it was built for the same faces' unknowns; analyses `cholesky` on
/// first use (which must then keep the pattern's analysis).
AssemblyStructure& assembly_structure(const Setup& s, SparseCholesky& cholesky, AssemblyStructure& cache);

/// Runs fn(j, list) for every face j: the faces of lists[0] and lists[1] on two threads, one list each (one after
/// the other if OpenMP allows only one thread), then those of lists[2] on this one. fn may add into the entries of its
/// face's unknowns.
template <class Fn>
void for_each_face_partitioned(const FacePartition& p, Fn&& fn) {
  if (!p.lists[0].empty() || !p.lists[1].empty()) {
#pragma omp parallel for num_threads(std::min(2, omp_get_max_threads())) schedule(static, 1)
    for (int h = 0; h < 2; ++h) {
      for (const int j : p.lists[static_cast<size_t>(h)]) fn(j, h);
    }
  }
  for (const int j : p.lists[2]) fn(j, 2);
}

/// What both solvers hold of one solve: its settings, the factorisation, the per-face data (checked against the
/// start X0), the Newton system's assembly structure (the cache's, or its own), and the result being built.
class SolverBase {
 protected:
  SolverBase(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0, const SubproblemSettings& settings,
             SparseCholesky& cholesky, AssemblyStructure* cache)
      : settings_(settings),
        cholesky_(cholesky),
        n_slots_(problem.n_slots),
        s_(make_setup(problem, X0)),
        st_(s_.settings),
        nf_(s_.n_faces),
        nv_(s_.n_var),
        assembly_(&assembly_structure(s_, cholesky_, cache != nullptr ? *cache : own_)) {}

  /// The positions of X0 as one vector (2 #slots), and the ghost faces' bounds set from them.
  Eigen::VectorXd start_positions(const Eigen::MatrixXd& X0) {
    Eigen::VectorXd pos(s_.n_pos);
    for (int i = 0; i < n_slots_; ++i) pos.segment<2>(2 * i) = X0.row(i).transpose();
    set_ghost_bounds(pos, s_);
    return pos;
  }
  /// result_ with X (#slots by 2) from the position vector pos.
  SubproblemResult& result_at(const Eigen::VectorXd& pos) {
    result_.X.resize(n_slots_, 2);
    for (int i = 0; i < n_slots_; ++i) result_.X.row(i) = pos.segment<2>(2 * i).transpose();
    return result_;
  }

  const SubproblemSettings& settings_;
  SparseCholesky& cholesky_;
  int n_slots_;
  Setup s_;
  const Settings& st_;
  int nf_, nv_;
  AssemblyStructure own_;
  AssemblyStructure* assembly_;
  SubproblemResult result_;
};

/// Runs a solver class (BarrierSolver, PrimalDualSolver: constructed from the problem, the start, the settings, the
/// factorisation and the cache; solve() returns the result) and sets the result's objective (10a) at its X.
template <class Solver>
SubproblemResult solve_with(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                            const SubproblemSettings& settings, SparseCholesky& cholesky, AssemblyStructure* cache) {
  Solver solver(problem, X0, settings, cholesky, cache);
  SubproblemResult result = solver.solve();
  result.objective = subproblem_objective(problem, result.X);
  return result;
}

}  // namespace liftmap::subproblem
