#include "flatten/subproblem_faces.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace liftmap::subproblem {

Setup make_setup(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0) {
  if (X0.rows() != problem.n_slots || X0.cols() != 2 || problem.n_slots < 2) {
    throw InvalidInputError("convex subproblem: X0 must be #slots by 2");
  }
  return make_setup(problem);
}

Setup make_setup(const ConvexSubproblem& problem) {
  Setup s;
  s.settings.h_max = problem.h == DistortionCombiner::kMax;
  s.settings.p_inf = std::isinf(problem.p);
  s.n_pos = 2 * problem.n_slots;
  s.n_var = s.n_pos - 2;
  for (int mi = 0; mi < 3; ++mi) {
    const SubproblemMesh& mesh = mi < 2 ? problem.meshes[static_cast<size_t>(mi)] : problem.ghosts;
    if (mesh.theta.size() != mesh.F.rows() || mesh.jacobian.G.rows() != mesh.F.rows()) {
      throw InvalidInputError("convex subproblem: mesh " + std::to_string(mi) + " has inconsistent sizes");
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      FaceSetup fs;
      fs.S = similarity_map(mesh.jacobian.G.row(f));
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.F(f, k);
        if (v < 0 || v >= static_cast<int>(mesh.slot.size())) {
          throw InvalidInputError("convex subproblem: face " + std::to_string(f) + " has no slot");
        }
        const int slot = mesh.slot[static_cast<size_t>(v)];
        if (slot < 0 || slot >= problem.n_slots) throw InvalidInputError("convex subproblem: slot out of range");
        for (int d = 0; d < 2; ++d) {
          fs.pos[static_cast<size_t>(2 * k + d)] = 2 * slot + d;
          fs.var[static_cast<size_t>(2 * k + d)] = slot == kFixedSlot ? -1 : 2 * slot + d - 2;
        }
      }
      fs.cs = std::cos(mesh.theta(f));
      fs.sn = std::sin(mesh.theta(f));
      fs.w = mesh.jacobian.area(f);
      fs.mesh = mi;
      s.faces.push_back(fs);
    }
  }
  s.n_faces = static_cast<int>(s.faces.size());
  return s;
}

void set_ghost_bounds(const Eigen::VectorXd& pos, Setup& s) {
  for (FaceSetup& fs : s.faces) {
    if (!fs.ghost()) continue;
    const Eigen::Vector4d a = face_coordinates(fs, pos);
    fs.bound = kGhostStretch * (std::hypot(a(0), a(1)) + std::hypot(a(2), a(3)));
  }
}

Eigen::Vector4d face_coordinates(const FaceSetup& fs, const Eigen::VectorXd& pos) {
  Vec6 u;
  for (int k = 0; k < 6; ++k) u(k) = pos(fs.pos[static_cast<size_t>(k)]);
  return fs.S * u;
}

Pattern make_pattern(const Setup& s) {
  std::vector<std::array<int, 6>> var(s.faces.size());
  for (size_t j = 0; j < s.faces.size(); ++j) var[j] = s.faces[j].var;
  return make_pattern(var, s.n_var);
}

Pattern make_pattern(const std::vector<std::array<int, 6>>& var, int n_var) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(var.size() * 21 + static_cast<size_t>(n_var));
  for (const std::array<int, 6>& fv : var) {
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        const int vr = fv[static_cast<size_t>(r)], vc = fv[static_cast<size_t>(c)];
        if (vr >= 0 && vc >= 0 && vr >= vc) trip.emplace_back(vr, vc, 0.0);
      }
    }
  }
  for (int i = 0; i < n_var; ++i) trip.emplace_back(i, i, 0.0);
  Pattern p;
  p.A.resize(n_var, n_var);
  p.A.setFromTriplets(trip.begin(), trip.end());
  p.A.makeCompressed();
  p.index.resize(var.size());
  const int* outer = p.A.outerIndexPtr();
  const int* inner = p.A.innerIndexPtr();
  for (size_t j = 0; j < var.size(); ++j) {
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        int& idx = p.index[j][static_cast<size_t>(6 * r + c)];
        idx = -1;
        const int vr = var[j][static_cast<size_t>(r)], vc = var[j][static_cast<size_t>(c)];
        if (vr < 0 || vc < 0 || vr < vc) continue;
        const int* it = std::lower_bound(inner + outer[vc], inner + outer[vc + 1], vr);
        idx = static_cast<int>(it - inner);
      }
    }
  }
  return p;
}

FacePartition partition_faces(const Setup& s, const SparseCholesky& cholesky) {
  FacePartition p;
  const std::vector<int> halves = cholesky.unknown_halves();
  for (int j = 0; j < s.n_faces; ++j) {
    int list = 2;
    if (!halves.empty()) {
      int seen = -1;  // the half of the face's unknowns so far; 2 once one is in the top or two differ
      for (const int v : s.faces[static_cast<size_t>(j)].var) {
        if (v < 0) continue;
        const int h = halves[static_cast<size_t>(v)];
        if (h < 0 || (seen >= 0 && seen != h)) {
          seen = 2;
          break;
        }
        seen = h;
      }
      if (seen >= 0) list = seen;
    }
    p.lists[static_cast<size_t>(list)].push_back(j);
  }
  return p;
}

AssemblyStructure& assembly_structure(const Setup& s, SparseCholesky& cholesky, AssemblyStructure& cache) {
  bool same = cache.var.size() == s.faces.size() && cholesky.analyzed();
  for (size_t j = 0; same && j < s.faces.size(); ++j) same = cache.var[j] == s.faces[j].var;
  if (same) return cache;
  cache.pattern = make_pattern(s);
  if (!cholesky.has_pattern_of(cache.pattern.A)) cholesky.analyze(cache.pattern.A);
  cache.parts = partition_faces(s, cholesky);
  cache.var.resize(s.faces.size());
  for (size_t j = 0; j < s.faces.size(); ++j) cache.var[j] = s.faces[j].var;
  return cache;
}

}  // namespace liftmap::subproblem
