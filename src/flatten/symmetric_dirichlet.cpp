#include "flatten/symmetric_dirichlet.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem_faces.h"
#include "flatten/symmetric_dirichlet_face.h"

namespace liftmap {

namespace {

using Vec4 = Eigen::Vector4d;
using Mat46 = Eigen::Matrix<double, 4, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

using subproblem::kParallelFaces;  // below this many faces the per-face loops run serially

/// d(a11, a12, a21, a22) / d(u0, v0, u1, v1, u2, v2) of one face (JacobianOperator's convention).
Mat46 jacobian_map(const Eigen::Matrix<double, 1, 6>& g) {
  Mat46 D = Mat46::Zero();
  for (int k = 0; k < 3; ++k) {
    D(0, 2 * k) = g(2 * k);
    D(1, 2 * k) = g(2 * k + 1);
    D(2, 2 * k + 1) = g(2 * k);
    D(3, 2 * k + 1) = g(2 * k + 1);
  }
  return D;
}

/// One face of E: its Jacobian map, its factor (the term's weight times its area) and the rows of X of its corners.
struct Face {
  Mat46 D;
  double w = 0;
  std::array<int, 3> row{};
};

/// The faces of every term, in term order.
std::vector<Face> gather_faces(const std::vector<SymmetricDirichletTerm>& terms) {
  std::vector<Face> faces;
  for (const SymmetricDirichletTerm& t : terms) {
    for (Eigen::Index f = 0; f < t.F->rows(); ++f) {
      Face face{.D = jacobian_map(t.jacobian->G.row(f)), .w = t.weight * t.jacobian->area(f)};
      for (int k = 0; k < 3; ++k) face.row[static_cast<size_t>(k)] = (*t.slot)[static_cast<size_t>((*t.F)(f, k))];
      faces.push_back(face);
    }
  }
  return faces;
}

Vec6 corners(const Face& face, const Eigen::MatrixXd& X) {
  Vec6 x;
  for (int k = 0; k < 3; ++k) x.segment<2>(2 * k) = X.row(face.row[static_cast<size_t>(k)]).transpose();
  return x;
}

/// E(X), +inf at a flipped face; the faces' terms are summed in face order, whatever the threads.
double energy(const std::vector<Face>& faces, const Eigen::MatrixXd& X) {
  const auto nf = static_cast<Eigen::Index>(faces.size());
  Eigen::VectorXd e(nf);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Face& face = faces[static_cast<size_t>(f)];
    e(f) = face.w * symmetric_dirichlet_energy(face.D * corners(face, X));
  }
  double sum = 0;
  for (Eigen::Index f = 0; f < nf; ++f) sum += e(f);
  return sum;
}

/// The smallest t > 0 with det(j + t dj) = 0, or +inf.
double flip_root(const Vec4& j, const Vec4& dj) {
  // det(j + t dj) = c0 + c1 t + c2 t^2
  const double c0 = jacobian_determinant(j), c2 = jacobian_determinant(dj);
  const double c1 = j(0) * dj(3) + dj(0) * j(3) - j(1) * dj(2) - dj(1) * j(2);
  double root = std::numeric_limits<double>::infinity();
  if (std::abs(c2) < 1e-300) {
    if (c1 < 0) root = -c0 / c1;
  } else {
    const double disc = c1 * c1 - 4 * c2 * c0;
    if (disc >= 0) {
      const double s = std::sqrt(disc);
      for (const double r : {(-c1 - s) / (2 * c2), (-c1 + s) / (2 * c2)}) {
        if (r > 0) root = std::min(root, r);
      }
    }
  }
  return root;
}

/// The fraction of the largest flip-free step that a step may take. The joint relaxation's first steps are cut by
/// this bound, so the larger it is the fewer of them (0.9 against 0.8: camel-cow 43 -> 41, man-homer 31 -> 29,
/// fandisk-bunny 23 -> 21 relaxation steps, the same energies within 8e-5; docs/performance.md).
constexpr double kFlipMargin = 0.9;

/// kFlipMargin times the largest a such that no face flips along X + t step_x for t in [0, a] (at most
/// 1 / kFlipMargin).
double flip_free_step(const std::vector<Face>& faces, const Eigen::MatrixXd& X, const Eigen::MatrixXd& step_x) {
  const auto nf = static_cast<Eigen::Index>(faces.size());
  double a = 1 / kFlipMargin;
#pragma omp parallel for schedule(static) reduction(min : a) if (nf > kParallelFaces)
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Face& face = faces[static_cast<size_t>(f)];
    a = std::min(a, flip_root(face.D * corners(face, X), face.D * corners(face, step_x)));
  }
  return kFlipMargin * a;
}

/// The unknowns of each face's six corner coordinates (dof: per slot, its index among the free slots, or -1).
std::vector<std::array<int, 6>> face_unknowns(const std::vector<Face>& faces, const std::vector<int>& dof) {
  std::vector<std::array<int, 6>> var(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int a = 0; a < 6; ++a) {
      const int r = dof[static_cast<size_t>(faces[f].row[static_cast<size_t>(a / 2)])];
      var[f][static_cast<size_t>(a)] = r < 0 ? -1 : 2 * r + a % 2;
    }
  }
  return var;
}

/// Every face's gradient and projected Hessian of its term of E at X, in its six corner coordinates.
struct FaceDerivatives {
  std::vector<Vec6> g;
  std::vector<Mat6> h;
};

/// With `proxy`, each face's Hessian is its reweighted proxy's (symmetric_dirichlet_proxy_derivatives).
FaceDerivatives face_derivatives(const std::vector<Face>& faces, const Eigen::MatrixXd& X, bool proxy) {
  const auto nf = static_cast<Eigen::Index>(faces.size());
  FaceDerivatives d{.g = std::vector<Vec6>(faces.size()), .h = std::vector<Mat6>(faces.size())};
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Face& face = faces[static_cast<size_t>(f)];
    const FaceJacobian j = face.D * corners(face, X);
    const SymmetricDirichletDerivatives dj =
        proxy ? symmetric_dirichlet_proxy_derivatives(j) : symmetric_dirichlet_derivatives(j);
    d.g[static_cast<size_t>(f)] = face.w * face.D.transpose() * dj.gradient;
    d.h[static_cast<size_t>(f)] = face.w * face.D.transpose() * dj.hessian * face.D;
  }
  return d;
}

/// Fills p.A with the sum of the faces' projected Hessians (faces `first` to `first + var.size()`, var their unknowns,
/// p made by subproblem::make_pattern(var, ...)) plus a tiny multiple of its diagonal, which keeps the semidefinite
/// sum definite, and g with the sum of their gradients plus the Hessians times the corners' `known` step (the
/// unknowns' own rows: g + H_ok d_k). Sums run in face order: they do not depend on the threads.
void newton_system(const FaceDerivatives& d, size_t first, const std::vector<std::array<int, 6>>& var,
                   const std::vector<Vec6>* known, subproblem::Pattern& p, Eigen::VectorXd& g) {
  double* values = p.A.valuePtr();
  std::fill(values, values + p.A.nonZeros(), 0.0);
  g = Eigen::VectorXd::Zero(p.A.rows());
  for (size_t i = 0; i < var.size(); ++i) {
    const size_t f = first + i;
    const Vec6 gf = known == nullptr ? d.g[f] : Vec6(d.g[f] + d.h[f] * (*known)[i]);
    for (int a = 0; a < 6; ++a) {
      const int ra = var[i][static_cast<size_t>(a)];
      if (ra < 0) continue;
      g(ra) += gf(a);
      for (int b = 0; b < 6; ++b) {
        const int at = p.index[i][static_cast<size_t>(6 * a + b)];
        if (at >= 0) values[at] += d.h[f](a, b);
      }
    }
  }
  for (Eigen::Index i = 0; i < p.A.rows(); ++i) p.A.coeffRef(i, i) += 1e-12 * (1 + std::abs(p.A.coeff(i, i)));
}

/// A term's own unknowns (SymmetricDirichletTerm::own_solve) and the system over them.
struct OwnSolve {
  size_t first = 0;                     ///< the term's first face in gather_faces' order
  std::vector<std::array<int, 6>> var;  ///< per face of the term: its own unknown of each corner coordinate, or -1
  std::vector<int> global;              ///< own unknown -> the joint system's unknown
  subproblem::Pattern pattern;
  SparseCholesky cholesky;
};

/// Per corner coordinate of each of the term's faces: its own unknown (>= 0), a shared unknown u as -2 - u, or -1
/// (fixed). Two terms with equal signatures, faces (Jacobian maps, factors) are solved alike by solve_own_unknowns.
std::vector<std::array<int, 6>> signature(const OwnSolve& o, const std::vector<std::array<int, 6>>& var) {
  std::vector<std::array<int, 6>> sig = o.var;
  for (size_t i = 0; i < sig.size(); ++i) {
    for (size_t a = 0; a < 6; ++a) {
      const int u = var[o.first + i][a];
      if (sig[i][a] < 0 && u >= 0) sig[i][a] = -2 - u;
    }
  }
  return sig;
}

bool same_data(const std::vector<Face>& faces, const std::vector<std::array<int, 6>>& var, const OwnSolve& a,
               const OwnSolve& b) {
  if (a.var.size() != b.var.size() || a.global.size() != b.global.size()) return false;
  for (size_t i = 0; i < a.var.size(); ++i) {
    const Face& fa = faces[a.first + i];
    const Face& fb = faces[b.first + i];
    if (fa.D != fb.D || fa.w != fb.w) return false;
  }
  return signature(a, var) == signature(b, var);
}

/// The own unknowns of every term with own_solve set (the joint unknowns that only its faces touch), kept for the
/// terms whose data equal another such term's: only there can the joint factorisation's elimination order make steps
/// that should be identical differ.
std::vector<OwnSolve> own_solves(const std::vector<SymmetricDirichletTerm>& terms, const std::vector<Face>& faces,
                                 const std::vector<std::array<int, 6>>& var, int n) {
  std::vector<int> owner(static_cast<size_t>(n), -1);  // the term whose faces touch the unknown, -2 if several
  size_t first = 0;
  for (size_t t = 0; t < terms.size(); ++t) {
    const auto nf = static_cast<size_t>(terms[t].F->rows());
    for (size_t f = first; f < first + nf; ++f) {
      for (const int u : var[f]) {
        if (u < 0) continue;
        int& o = owner[static_cast<size_t>(u)];
        o = o == -1 || o == static_cast<int>(t) ? static_cast<int>(t) : -2;
      }
    }
    first += nf;
  }
  std::vector<OwnSolve> candidates;
  first = 0;
  for (size_t t = 0; t < terms.size(); ++t) {
    const auto nf = static_cast<size_t>(terms[t].F->rows());
    if (terms[t].own_solve) {
      OwnSolve o;
      o.first = first;
      std::vector<int> local(static_cast<size_t>(n), -1);
      for (int u = 0; u < n; ++u) {  // in the joint order, so that terms with the same data number alike
        if (owner[static_cast<size_t>(u)] != static_cast<int>(t)) continue;
        local[static_cast<size_t>(u)] = static_cast<int>(o.global.size());
        o.global.push_back(u);
      }
      for (size_t f = first; f < first + nf; ++f) {
        std::array<int, 6> v{};
        for (int a = 0; a < 6; ++a) {
          const int u = var[f][static_cast<size_t>(a)];
          v[static_cast<size_t>(a)] = u < 0 ? -1 : local[static_cast<size_t>(u)];
        }
        o.var.push_back(v);
      }
      if (!o.global.empty()) candidates.push_back(std::move(o));
    }
    first += nf;
  }
  std::vector<char> twin(candidates.size(), 0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = i + 1; j < candidates.size(); ++j) {
      if (same_data(faces, var, candidates[i], candidates[j])) twin[i] = twin[j] = 1;
    }
  }
  std::vector<OwnSolve> out;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!twin[i]) continue;
    OwnSolve& o = candidates[i];
    o.pattern = subproblem::make_pattern(o.var, static_cast<int>(o.global.size()));
    o.cholesky.analyze(o.pattern.A);
    out.push_back(std::move(o));
  }
  return out;
}

/// Replaces the own unknowns' part of the joint step dx by H_oo^-1 (-(g_o + H_os dx_s)), from the term's faces alone.
/// \return false if H_oo is not numerically positive definite.
bool solve_own_unknowns(const FaceDerivatives& d, const std::vector<std::array<int, 6>>& var, OwnSolve& o,
                        Eigen::VectorXd& dx) {
  std::vector<Vec6> known(o.var.size(), Vec6::Zero());  // the shared unknowns' step at each face's corners
  for (size_t i = 0; i < o.var.size(); ++i) {
    for (int a = 0; a < 6; ++a) {
      const int u = var[o.first + i][static_cast<size_t>(a)];
      if (u >= 0 && o.var[i][static_cast<size_t>(a)] < 0) known[i](a) = dx(u);
    }
  }
  Eigen::VectorXd r;
  newton_system(d, o.first, o.var, &known, o.pattern, r);
  if (!o.cholesky.factorize(o.pattern.A)) return false;
  const Eigen::VectorXd own = o.cholesky.solve(-r);
  for (size_t k = 0; k < o.global.size(); ++k) dx(o.global[k]) = own(static_cast<Eigen::Index>(k));
  return true;
}

void check_terms(const std::vector<SymmetricDirichletTerm>& terms, Eigen::Index n_slots) {
  for (const SymmetricDirichletTerm& t : terms) {
    if (t.jacobian == nullptr || t.F == nullptr || t.slot == nullptr || t.jacobian->G.rows() != t.F->rows() ||
        t.jacobian->area.size() != t.F->rows() || !(t.weight > 0)) {
      throw InvalidInputError("minimize_symmetric_dirichlet: a term's sizes disagree or its weight is not positive");
    }
    for (Eigen::Index f = 0; f < t.F->rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int v = (*t.F)(f, k);
        const bool ok = v >= 0 && static_cast<size_t>(v) < t.slot->size() && (*t.slot)[static_cast<size_t>(v)] >= 0 &&
                        (*t.slot)[static_cast<size_t>(v)] < n_slots;
        if (!ok) {
          throw InvalidInputError("minimize_symmetric_dirichlet: face " + std::to_string(f) +
                                  " has a corner without a slot");
        }
      }
    }
  }
}

}  // namespace

SymmetricDirichletResult minimize_symmetric_dirichlet(const std::vector<SymmetricDirichletTerm>& terms,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& X0,
                                                      const SymmetricDirichletOptions& options,
                                                      SparseCholesky* shared_cholesky) {
  const auto ns = static_cast<Eigen::Index>(fixed.size());
  if (X0.rows() != ns || X0.cols() != 2) throw InvalidInputError("minimize_symmetric_dirichlet: sizes disagree");
  check_terms(terms, ns);
  const std::vector<Face> faces = gather_faces(terms);
  SymmetricDirichletResult res;
  res.U = X0;
  res.energy_start = res.energy = energy(faces, X0);
  if (!std::isfinite(res.energy)) {
    throw InvalidInputError("minimize_symmetric_dirichlet: a face of the start is flipped or degenerate");
  }
  std::vector<int> dof(static_cast<size_t>(ns), -1);
  int n = 0;
  for (Eigen::Index v = 0; v < ns; ++v) {
    if (!fixed[static_cast<size_t>(v)]) dof[static_cast<size_t>(v)] = n++;
  }
  if (n == 0 || options.max_iterations <= 0) return res;
  const std::vector<std::array<int, 6>> var = face_unknowns(faces, dof);
  subproblem::Pattern pattern = subproblem::make_pattern(var, 2 * n);
  SparseCholesky own_cholesky;
  SparseCholesky& cholesky = shared_cholesky != nullptr ? *shared_cholesky : own_cholesky;
  if (!cholesky.has_pattern_of(pattern.A)) cholesky.analyze(pattern.A);
  std::vector<OwnSolve> own = own_solves(terms, faces, var, 2 * n);
  bool proxy = options.proxy_while_decrease > 0;
  for (int iter = 0; iter < options.max_iterations; ++iter) {
    const FaceDerivatives d = face_derivatives(faces, res.U, proxy);
    Eigen::VectorXd g;
    newton_system(d, 0, var, nullptr, pattern, g);
    if (!cholesky.factorize(pattern.A)) break;
    Eigen::VectorXd dx = cholesky.solve(-g);
    bool solved = true;
    for (OwnSolve& o : own) solved = solved && solve_own_unknowns(d, var, o, dx);
    if (!solved) break;
    Eigen::MatrixXd step_x = Eigen::MatrixXd::Zero(ns, 2);
    for (Eigen::Index v = 0; v < ns; ++v) {
      const int r = dof[static_cast<size_t>(v)];
      if (r >= 0) step_x.row(v) << dx(2 * r), dx(2 * r + 1);
    }
    // Flip-free, then Armijo.
    const double slope = g.dot(dx);
    if (!(slope < 0)) break;
    const double flip_limit = flip_free_step(faces, res.U, step_x);
    double step = std::min(1.0, flip_limit);
    double e = std::numeric_limits<double>::infinity();
    Eigen::MatrixXd trial;
    for (int halvings = 0; halvings < 40; ++halvings, step *= 0.5) {
      trial = res.U + step * step_x;
      e = energy(faces, trial);
      if (e <= res.energy + 1e-4 * step * slope) break;
    }
    if (!(e < res.energy)) {
      if (!proxy) break;
      proxy = false;  // no progress along the proxy's direction: projected Newton from here
      continue;
    }
    const double before = res.energy;
    res.U = std::move(trial);
    res.energy = e;
    ++res.iterations;
    if (proxy) {
      ++res.proxy_steps;
      proxy = before - e >= options.proxy_while_decrease * before;
      continue;
    }
    const bool shortened_by_flips = flip_limit < 1;
    if (options.only_full_steps_stop && shortened_by_flips) continue;
    if (before - e < options.relative_decrease * before) break;
  }
  return res;
}

SymmetricDirichletResult minimize_symmetric_dirichlet(const JacobianOperator& op, const Eigen::MatrixXi& F,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& U0,
                                                      const SymmetricDirichletOptions& options) {
  const auto nv = static_cast<Eigen::Index>(fixed.size());
  if (U0.rows() != nv || U0.cols() != 2 || op.G.rows() != F.rows() || op.area.size() != F.rows()) {
    throw InvalidInputError("minimize_symmetric_dirichlet: sizes disagree");
  }
  std::vector<int> slot(static_cast<size_t>(nv));
  for (Eigen::Index v = 0; v < nv; ++v) slot[static_cast<size_t>(v)] = static_cast<int>(v);
  return minimize_symmetric_dirichlet({SymmetricDirichletTerm{.jacobian = &op, .F = &F, .slot = &slot}}, fixed, U0,
                                      options);
}

}  // namespace liftmap
