#include "flatten/primal_dual_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "flatten/subproblem_faces.h"

namespace liftmap {

namespace {

using namespace subproblem;  // NOLINT(google-build-using-namespace): the shared per-face data

// Local variables of one face: x_loc = (alpha, beta, gamma, delta, c, r, s, e, T). (alpha..delta) = S u are linear
// in the corner positions u; c, r, s, e are the face's auxiliaries; T is the epigraph variable of its mesh.
// p = inf: the epigraph of E_j is T itself, e is unused. Unused auxiliaries get a unit curvature and stay 0.
constexpr int kC = 4;
constexpr int kR = 5;
constexpr int kS = 6;
constexpr int kE = 7;
constexpr int kT = 8;
constexpr int kLocal = 9;
constexpr int kAux = 4;       // auxiliaries per face (c, r, s, e)
constexpr int kMaxCones = 4;  // cones per face
constexpr int kRows = 3 * kMaxCones;
constexpr int kMRows = kRows + kAux;  // rows of a face's scaled constraint matrix W^-1 A (cones, objective, unit rows)
using VecL = Eigen::Matrix<double, kLocal, 1>;
using MatL = Eigen::Matrix<double, kLocal, kLocal>;
using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;
using Mat64 = Eigen::Matrix<double, 6, 4>;
using Cols3 = Eigen::Matrix<double, 6, 3>;
using VecR = Eigen::Matrix<double, kRows, 1>;

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Fraction of the way to the boundary of the cones that a step goes at most (CVXOPT's value).
constexpr double kStepFraction = 0.99;
/// Steps below this length, twice in a row, end the method (precision limit).
constexpr double kShortStep = 1e-3;
/// Iterations over which the method must make progress: halve the gap, or move the objective by a tenth of the
/// requested gap. Near the limit of double precision, short steps alternate with longer ones that go nowhere.
constexpr int kProgressWindow = 5;
/// Largest dual residual |A^T z - c|_inf of a solution (CVXOPT's default feasibility tolerance).
constexpr double kDualTolerance = 1e-7;

/// One cone of a face: s = A x_loc(var) + b, dimension 1 (s >= 0) or 3 (s0 >= |(s1, s2)|).
struct Cone {
  int dim = 3;
  int n = 0;                 // variables it depends on
  std::array<int, 4> var{};  // their local indices
  Eigen::Matrix<double, 3, 4> A = Eigen::Matrix<double, 3, 4>::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

struct FaceCones {
  std::array<Cone, kMaxCones> cone;
  int n = 0;
};

/// The cones of face fs (see primal_dual_solver.h), built on the fly (a few dozen stores).
void face_cones(const FaceSetup& fs, const Settings& st, FaceCones& fc) {
  fc = FaceCones{};
  const int ke = st.p_inf ? kT : kE;
  auto add = [&](int dim, std::initializer_list<int> vars) -> Cone& {
    Cone& k = fc.cone[static_cast<size_t>(fc.n++)];
    k.dim = dim;
    for (const int v : vars) k.var[static_cast<size_t>(k.n++)] = v;
    return k;
  };
  {  // c >= |(gamma, delta)|, variables (c, gamma, delta)
    Cone& k = add(3, {kC, 2, 3});
    k.A(0, 0) = k.A(1, 1) = k.A(2, 2) = 1;
  }
  if (fs.ghost()) {
    Cone& k1 = add(3, {kC, 0, 1});  // bound - c >= |(alpha, beta)|
    k1.A(0, 0) = -1;
    k1.A(1, 1) = k1.A(2, 2) = 1;
    k1.b(0) = fs.bound;
    Cone& k2 = add(1, {0, 1, kC});  // m = l - c >= 0
    k2.A(0, 0) = fs.cs;
    k2.A(0, 1) = fs.sn;
    k2.A(0, 2) = -1;
    return;
  }
  // The variable that bounds |(alpha, beta)| + c: r for eq. 3, the epigraph variable for eq. 2.
  const int top = st.h_max ? ke : kR;
  Cone& k1 = add(3, {top, kC, 0, 1});  // top - c >= |(alpha, beta)|
  k1.A(0, 0) = 1;
  k1.A(0, 1) = -1;
  k1.A(1, 2) = k1.A(2, 3) = 1;
  // The variable that bounds 1 / m: s for eq. 3, the epigraph variable for eq. 2. Rotated cone inv m >= 1 as
  // (inv + m, inv - m, 2), m = alpha cos + beta sin - c.
  const int inv = st.h_max ? ke : kS;
  Cone& k2 = add(3, {inv, 0, 1, kC});
  k2.A.row(0) << 1, fs.cs, fs.sn, -1;
  k2.A.row(1) << 1, -fs.cs, -fs.sn, 1;
  k2.b(2) = 2;
  if (!st.h_max) {
    Cone& k3 = add(3, {ke, kR, kS});  // e >= |(r, s)|
    k3.A(0, 0) = k3.A(1, 1) = k3.A(2, 2) = 1;
  }
}

template <int N>
using VecN = Eigen::Matrix<double, N, 1>;

template <class V>
double soc_det(const Eigen::MatrixBase<V>& x) {
  const double r = x.tail(x.size() - 1).norm();
  return (x(0) - r) * (x(0) + r);
}

template <class V>
bool in_cone(const Eigen::MatrixBase<V>& x) {
  if (x.size() == 1) return x(0) > 0;
  return x(0) > 0 && x(0) > x.tail(x.size() - 1).norm();
}

/// Nesterov-Todd scaling of a second-order cone (dimension N, or any with N = Eigen::Dynamic):
/// W = beta (2 v v^T - J), W z = W^-1 s = lambda; wbar is the normalised scaling point (det 1), v its square root in
/// the Jordan algebra, and W^-2 = (2 J wbar (J wbar)^T - J) / beta^2.
template <int N>
struct Scaling {
  VecN<N> v, wbar;
  double beta = 1;
};

template <int N>
Scaling<N> nt_scaling(const VecN<N>& s, const VecN<N>& z) {
  const double sn = std::sqrt(soc_det(s)), zn = std::sqrt(soc_det(z));
  const VecN<N> sb = s / sn;
  VecN<N> zb = z / zn;
  const double gamma = std::sqrt((1 + sb.dot(zb)) / 2);
  zb.tail(zb.size() - 1) *= -1;  // J zbar
  Scaling<N> w;
  w.wbar = (sb + zb) / (2 * gamma);
  w.v = w.wbar;
  w.v(0) += 1;
  w.v /= std::sqrt(2 * (w.wbar(0) + 1));
  w.beta = std::sqrt(sn / zn);
  return w;
}

/// W x and W^-1 x for the scaling w.
template <int N>
VecN<N> apply_w(const Scaling<N>& w, const VecN<N>& x) {
  VecN<N> y = 2 * w.v.dot(x) * w.v;
  y(0) -= x(0);
  y.tail(y.size() - 1) += x.tail(x.size() - 1);
  return w.beta * y;
}
template <int N>
VecN<N> apply_winv(const Scaling<N>& w, const VecN<N>& x) {
  // J v . x, then 2 (J v)(J v . x) - J x
  const double jvx = w.v(0) * x(0) - w.v.tail(w.v.size() - 1).dot(x.tail(x.size() - 1));
  VecN<N> y(x.size());
  y(0) = 2 * jvx * w.v(0) - x(0);
  y.tail(y.size() - 1) = -2 * jvx * w.v.tail(w.v.size() - 1) + x.tail(x.size() - 1);
  return y / w.beta;
}

/// u with lambda o u = d (Jordan product of the second-order cone), lambda in its interior.
template <int N>
VecN<N> jordan_div(const VecN<N>& lambda, const VecN<N>& d) {
  const Eigen::Index n = lambda.size() - 1;
  const double det = soc_det(lambda);
  VecN<N> u(lambda.size());
  u(0) = (lambda(0) * d(0) - lambda.tail(n).dot(d.tail(n))) / det;
  u.tail(n) = (d.tail(n) - u(0) * lambda.tail(n)) / lambda(0);
  return u;
}

/// x o y (Jordan product of the second-order cone).
template <int N>
VecN<N> jordan_prod(const VecN<N>& x, const VecN<N>& y) {
  const Eigen::Index n = x.size() - 1;
  VecN<N> p(x.size());
  p(0) = x.dot(y);
  p.tail(n) = x(0) * y.tail(n) + y(0) * x.tail(n);
  return p;
}

/// The largest a >= 0 with x + a d in the (closed) second-order cone, x in its interior; +infinity if the whole ray
/// is inside.
template <int N>
double max_step(const VecN<N>& x, const VecN<N>& d) {
  const Eigen::Index n = x.size() - 1;
  const double c = soc_det(x);
  const double b = x(0) * d(0) - x.tail(n).dot(d.tail(n));
  const double a = soc_det(d);
  // det(x + a d) = c + 2 b t + a t^2 with c > 0: the first positive root, where the ray leaves the cone.
  if (a == 0) return b < 0 ? -c / (2 * b) : kInf;
  const double disc = b * b - a * c;
  if (disc < 0) return kInf;  // det stays positive: the ray stays in the cone's interior
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double t = kInf;
  for (const double r : {q / a, q != 0 ? c / q : kInf}) {
    if (r > 0) t = std::min(t, r);
  }
  return t;
}
/// The same for the half-line x >= 0.
double max_step_linear(double x, double d) { return d < 0 ? -x / d : kInf; }

/// The iterate: positions, auxiliaries (4 per face), epigraph variables; the dual variables of every cone.
struct Iterate {
  Eigen::VectorXd pos;
  Eigen::Matrix<double, kAux, Eigen::Dynamic> y;
  std::array<double, 2> T{};
  Eigen::Matrix<double, kRows, Eigen::Dynamic> z;  // duals of the faces' cones (cone k: rows 3k..3k+dim-1)
  std::array<Eigen::VectorXd, 2> z_obj;            // p = 2: duals of the objective cones
};

VecL local_x(const FaceSetup& fs, const Iterate& it, int j) {
  VecL x;
  x.head<4>() = face_coordinates(fs, it.pos);
  x.segment<kAux>(kC) = it.y.col(j);
  x(kT) = fs.ghost() ? 0.0 : it.T[static_cast<size_t>(fs.mesh)];
  return x;
}

Eigen::Vector3d cone_value(const Cone& k, const VecL& x) {
  Eigen::Vector4d xv = Eigen::Vector4d::Zero();
  for (int i = 0; i < k.n; ++i) xv(i) = x(k.var[static_cast<size_t>(i)]);
  return k.A * xv + k.b;
}

/// The objective cone of mesh m (p = 2): (T_m, sqrt(w_j) e_j over the mesh's faces).
struct ObjectiveCone {
  std::vector<int> faces;
  Eigen::VectorXd sqrt_w;
};

/// Per-face pieces of one iteration's Newton system, the auxiliaries eliminated (see the per-face loop).
struct FaceSystem {
  Mat6 K;                               // Schur complement in the corner coordinates
  Mat4 R;                               // H_yy = R^T R
  Mat4 Cq;                              // R^-T H_yq: H_yq = R^T Cq
  Vec6 hxT;                             // coupling corners -> T (p = inf)
  Vec4 hyT;                             // coupling auxiliaries -> T (p = inf)
  double h_tt = 0;                      // (p = inf)
  std::array<Scaling<3>, kMaxCones> w;  // scalings of the face's cones (dimension 1: beta = sqrt(s / z) only)
  VecR lambda;                          // their scaled points
};

}  // namespace

BarrierResult solve_convex_subproblem_primal_dual(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                                  const BarrierOptions& options, SparseCholesky& cholesky,
                                                  subproblem::AssemblyStructure* cache) {
  if (X0.rows() != problem.n_slots || X0.cols() != 2 || problem.n_slots < 2) {
    throw InvalidInputError("convex subproblem: X0 must be #slots by 2");
  }
  Setup s = make_setup(problem);
  const Settings& st = s.settings;
  const int nf = s.n_faces;
  const int nv = s.n_var;
  Iterate it;
  it.pos.resize(s.n_pos);
  for (int i = 0; i < problem.n_slots; ++i) it.pos.segment<2>(2 * i) = X0.row(i).transpose();
  set_ghost_bounds(it.pos, s);
  AssemblyStructure own;
  AssemblyStructure& assembly = assembly_structure(s, cholesky, cache != nullptr ? *cache : own);
  Pattern& pattern = assembly.pattern;
  const FacePartition& parts = assembly.parts;

  // Strictly feasible start: every cone's slack well inside (each auxiliary 1.5 times its lower bound).
  it.y.setZero(kAux, nf);
  std::array<double, 2> e_max{0, 0};
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const Eigen::Vector4d a = face_coordinates(fs, it.pos);
    const double cn = std::hypot(a(2), a(3)), n = std::hypot(a(0), a(1));
    const double l = a(0) * fs.cs + a(1) * fs.sn;
    if (!(l - cn > 0)) {
      throw InvalidInputError("convex subproblem: the start is not strictly feasible (sigma_tilde <= 0 on face " +
                              std::to_string(j) + ")");
    }
    const double c = cn + 0.5 * (l - cn), m = l - c;
    it.y(0, j) = c;
    if (fs.ghost()) continue;
    double e = 0;
    if (st.h_max) {
      e = std::max(c + 1.5 * n, 1.5 / m);
    } else {
      it.y(1, j) = c + 1.5 * n;
      it.y(2, j) = 1.5 / m;
      e = 1.5 * std::hypot(it.y(1, j), it.y(2, j));
    }
    it.y(3, j) = st.p_inf ? 0.0 : e;
    e_max[static_cast<size_t>(fs.mesh)] = std::max(e_max[static_cast<size_t>(fs.mesh)], e);
  }
  std::array<ObjectiveCone, 2> obj;
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!fs.ghost()) obj[static_cast<size_t>(fs.mesh)].faces.push_back(j);
  }
  for (size_t m = 0; m < 2; ++m) {
    ObjectiveCone& oc = obj[m];
    oc.sqrt_w.resize(static_cast<Eigen::Index>(oc.faces.size()));
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      oc.sqrt_w(static_cast<Eigen::Index>(i)) = std::sqrt(s.faces[static_cast<size_t>(oc.faces[i])].w);
    }
    if (st.p_inf) {
      it.T[m] = 1.5 * e_max[m];
    } else {
      double sum = 0;
      for (size_t i = 0; i < oc.faces.size(); ++i) {
        const double e = it.y(3, oc.faces[i]);
        sum += s.faces[static_cast<size_t>(oc.faces[i])].w * e * e;
      }
      it.T[m] = 1.5 * std::sqrt(sum);
    }
  }
  // The cones of every face (their rows depend only on the rotation and the ghost bound).
  std::vector<FaceCones> cones(static_cast<size_t>(nf));
  for (int j = 0; j < nf; ++j) face_cones(s.faces[static_cast<size_t>(j)], st, cones[static_cast<size_t>(j)]);
  auto objective_slack = [&](const Iterate& x, size_t m) {
    const ObjectiveCone& oc = obj[m];
    Eigen::VectorXd so(oc.faces.size() + 1);
    so(0) = x.T[m];
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      so(static_cast<Eigen::Index>(i) + 1) = oc.sqrt_w(static_cast<Eigen::Index>(i)) * x.y(3, oc.faces[i]);
    }
    return so;
  };
  // The slacks of every cone at x; false if some cone is not strictly satisfied.
  auto slacks = [&](const Iterate& x, Eigen::Matrix<double, kRows, Eigen::Dynamic>& S,
                    std::array<Eigen::VectorXd, 2>& S_obj) {
    S.setZero(kRows, nf);
    int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      const VecL xl = local_x(fs, x, j);
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        const Eigen::Vector3d v = cone_value(cone, xl);
        S.col(j).segment(3 * k, cone.dim) = v.head(cone.dim);
        if (!(cone.dim == 1 ? v(0) > 0 : in_cone(v))) ok = 0;
      }
    }
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        S_obj[m] = objective_slack(x, m);
        if (!in_cone(S_obj[m])) ok = 0;
      }
    }
    return ok == 1;
  };
  Eigen::Matrix<double, kRows, Eigen::Dynamic> S;
  std::array<Eigen::VectorXd, 2> S_obj;
  if (!slacks(it, S, S_obj)) throw PipelineError("convex subproblem: the primal-dual start is not strictly feasible");

  double nu = st.p_inf ? 0.0 : 2.0;
  for (const FaceCones& fc : cones) nu += fc.n;

  // Dual start: z = mu0 s^-1 on every cone (s o z = mu0 e: perfectly centred), with mu0 the least-squares fit of
  // the dual equation A^T z = c in the directions of the objective (the T_m).
  auto inverse = [](const Eigen::Ref<const Eigen::VectorXd>& x) {
    if (x.size() == 1) return Eigen::VectorXd(Eigen::VectorXd::Constant(1, 1 / x(0)));
    Eigen::VectorXd y = x / soc_det(x);
    y.tail(x.size() - 1) *= -1;
    return y;
  };
  it.z.setZero(kRows, nf);
  for (int j = 0; j < nf; ++j) {
    const FaceCones& fc = cones[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      const int d = fc.cone[static_cast<size_t>(k)].dim;
      it.z.col(j).segment(3 * k, d) = inverse(S.col(j).segment(3 * k, d));
    }
  }
  if (!st.p_inf) {
    for (size_t m = 0; m < 2; ++m) it.z_obj[m] = inverse(S_obj[m]);
  }
  // A^T z in the T_m (the dual equation there reads (A^T z)_T = 1).
  auto dual_t = [&](const Iterate& x) {
    std::array<double, 2> g{0, 0};
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) g[m] = x.z_obj[m](0);
      return g;
    }
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      if (fs.ghost()) continue;
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        for (int i = 0; i < cone.n; ++i) {
          if (cone.var[static_cast<size_t>(i)] != kT) continue;
          g[static_cast<size_t>(fs.mesh)] += cone.A.col(i).head(cone.dim).dot(x.z.col(j).segment(3 * k, cone.dim));
        }
      }
    }
    return g;
  };
  {
    const auto g = dual_t(it);
    const double mu0 = (g[0] + g[1]) / (g[0] * g[0] + g[1] * g[1]);
    it.z *= mu0;
    for (auto& zo : it.z_obj) zo *= mu0;
  }

  BarrierResult result;
  std::vector<FaceSystem> sys(static_cast<size_t>(nf));
  std::array<Scaling<Eigen::Dynamic>, 2> w_obj;
  std::array<Eigen::VectorXd, 2> lambda_obj;
  double last_shift = 0;

  // Applies P^-1 (the Hessian without the global coupling) to the NC columns (Rx; Ry), Ry 4 nf rows.
  auto apply_pinv = [&]<int NC>(const Eigen::MatrixXd& Rx, const Eigen::MatrixXd& Ry, Eigen::MatrixXd& Dx,
                                Eigen::MatrixXd& Dy) {
    using Corner = Eigen::Matrix<double, 6, NC>;
    using Aux = Eigen::Matrix<double, kAux, NC>;
    std::vector<Corner> corner_rows(static_cast<size_t>(nf));
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      // B H_yy^-1 r = S^T H_qy H_yy^-1 r = S^T Cq^T R^-T r
      const Aux t =
          fsys.R.transpose().template triangularView<Eigen::Lower>().solve(Ry.template block<kAux, NC>(kAux * j, 0));
      corner_rows[static_cast<size_t>(j)].noalias() =
          s.faces[static_cast<size_t>(j)].S.transpose() * (fsys.Cq.transpose() * t);
    }
    Eigen::MatrixXd Rt = Rx;
    subtract_corner_rows<NC>(s, parts, corner_rows, Rt);
    Dx = cholesky.solve(Rt);
    Dy.resize(kAux * nf, NC);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const Corner dxl = gather_corners<NC>(fs, Dx);
      // H_yy^-1 (r - H_yq S dx) = R^-1 (R^-T r - Cq S dx)
      const Aux t =
          fsys.R.transpose().template triangularView<Eigen::Lower>().solve(Ry.template block<kAux, NC>(kAux * j, 0));
      Dy.template block<kAux, NC>(kAux * j, 0) =
          fsys.R.template triangularView<Eigen::Upper>().solve(t - fsys.Cq * (fs.S * dxl));
    }
  };

  // Rank-one vectors u_m and coupling factors kappa_m of the objective cones (p = 2): their Hessian part is
  // diag(w_j / beta^2) on the e_j + u_m u_m^T, coupled to T_m by kappa_m u_m, with h_TT on T_m.
  std::array<Eigen::VectorXd, 2> u_obj;
  std::array<double, 2> kappa{0, 0}, h_tt{0, 0};

  struct Direction {
    Eigen::VectorXd dx, dy;
    std::array<double, 2> dT{};
  };
  // The coupling columns of the T_m (p = inf: H's blocks between T_m and the positions and auxiliaries; p = 2: u_m),
  // P^-1 applied to them (solved together with the predictor's right-hand side), and the 2 x 2 systems built from them.
  Eigen::MatrixXd Cx, Cy, Dcx, Dcy;
  Eigen::Matrix2d G, Minv, GM, Sc;
  auto coupling_columns = [&] {
    Cx.setZero(nv, 2);
    Cy.setZero(kAux * nf, 2);
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      if (fs.ghost()) continue;
      if (st.p_inf) {
        Cy.block<kAux, 1>(kAux * j, fs.mesh) = sys[static_cast<size_t>(j)].hyT;
        for (int r = 0; r < 6; ++r) {
          const int v = fs.var[static_cast<size_t>(r)];
          if (v >= 0) Cx(v, fs.mesh) += sys[static_cast<size_t>(j)].hxT(r);
        }
      }
    }
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        const ObjectiveCone& oc = obj[m];
        for (size_t i = 0; i < oc.faces.size(); ++i) {
          Cy(kAux * oc.faces[i] + 3, static_cast<Eigen::Index>(m)) = u_obj[m](static_cast<Eigen::Index>(i));
        }
      }
    }
  };
  // Once Dcx, Dcy = P^-1 (Cx, Cy) are known.
  auto finish_coupling = [&] {
    G = Cx.transpose() * Dcx + Cy.transpose() * Dcy;
    G = 0.5 * (G + G.transpose());
    if (st.p_inf) {
      // Bordered system [[P, Q], [Q^T, h_tt]]: its Schur complement on the two epigraph variables.
      Sc = -G;
      Sc(0, 0) += h_tt[0];
      Sc(1, 1) += h_tt[1];
    } else {
      // H = [[P + U U^T, U K], [K U^T, diag(h_tt)]], U = [u_0 u_1], K = diag(kappa): Woodbury for P + U U^T
      // (M = I + U^T P^-1 U >= I), then the 2 x 2 Schur complement in (dT_0, dT_1).
      Minv = (Eigen::Matrix2d::Identity() + G).inverse();
      GM = G * Minv;  // U^T A^-1 U, A = P + U U^T
      for (int a = 0; a < 2; ++a) {
        for (int b = 0; b < 2; ++b) {
          Sc(a, b) = (a == b ? h_tt[static_cast<size_t>(a)] : 0.0) -
                     kappa[static_cast<size_t>(a)] * kappa[static_cast<size_t>(b)] * GM(a, b);
        }
      }
    }
  };

  // Solves H dx = r for the right-hand side r = (rx, ry, r_t) (positions, auxiliaries, T_m), given P^-1 (rx, ry).
  auto finish_solve = [&](Eigen::VectorXd pinv_rx, Eigen::VectorXd pinv_ry, const std::array<double, 2>& r_t) {
    Direction d;
    d.dx = std::move(pinv_rx);
    d.dy = std::move(pinv_ry);
    const Eigen::Vector2d ctd = Cx.transpose() * d.dx + Cy.transpose() * d.dy;  // C^T P^-1 r
    if (st.p_inf) {
      const Eigen::Vector2d sol = Sc.ldlt().solve(Eigen::Vector2d(r_t[0], r_t[1]) - ctd);
      d.dT = {sol(0), sol(1)};
      d.dx -= Dcx * sol;
      d.dy -= Dcy * sol;
    } else {
      const Eigen::Vector2d k(kappa[0], kappa[1]);
      const Eigen::Vector2d uta = ctd - GM * ctd;  // U^T A^-1 r
      const Eigen::Vector2d sol = Sc.ldlt().solve(Eigen::Vector2d(r_t[0], r_t[1]) - k.cwiseProduct(uta));
      d.dT = {sol(0), sol(1)};
      const Eigen::Vector2d coef = Minv * (ctd + k.cwiseProduct(sol));
      d.dx -= Dcx * coef;
      d.dy -= Dcy * coef;
    }
    if (!d.dx.allFinite() || !d.dy.allFinite() || !std::isfinite(d.dT[0]) || !std::isfinite(d.dT[1])) {
      throw PipelineError("convex subproblem: the primal-dual step is not finite");
    }
    return d;
  };
  auto solve = [&](const Eigen::VectorXd& rx, const Eigen::VectorXd& ry, const std::array<double, 2>& r_t) {
    Eigen::MatrixXd Dx, Dy;
    apply_pinv.template operator()<1>(rx, ry, Dx, Dy);
    return finish_solve(Dx.col(0), Dy.col(0), r_t);
  };

  // Local direction of face j.
  auto local_dx = [&](const FaceSetup& fs, const Direction& d, int j) {
    Vec6 du;
    for (int r = 0; r < 6; ++r) {
      const int v = fs.var[static_cast<size_t>(r)];
      du(r) = v >= 0 ? d.dx(v) : 0.0;
    }
    VecL x;
    x.head<4>() = fs.S * du;
    x.segment<kAux>(kC) = d.dy.segment<kAux>(kAux * j);
    x(kT) = fs.ghost() ? 0.0 : d.dT[static_cast<size_t>(fs.mesh)];
    return x;
  };

  // The objective cone m's part A_obj d of a direction d (p = 2): (dT_m, sqrt(w_j) de_j over the mesh's faces).
  auto objective_direction = [&](const Direction& d, size_t m) {
    const ObjectiveCone& oc = obj[m];
    Eigen::VectorXd dso(oc.faces.size() + 1);
    dso(0) = d.dT[m];
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      dso(static_cast<Eigen::Index>(i) + 1) = oc.sqrt_w(static_cast<Eigen::Index>(i)) * d.dy(kAux * oc.faces[i] + 3);
    }
    return dso;
  };

  // Scaled directions of one solve, per cone.
  struct Scaled {
    Eigen::Matrix<double, kRows, Eigen::Dynamic> ds, dz;
    std::array<Eigen::VectorXd, 2> ds_obj, dz_obj;
  };
  // The scaled directions of a solve d: ds~ = W^-1 A dx and dz~ = W dz = U - ds~ per cone (U = lambda \ xi - lambda,
  // the right-hand side of W dz + W^-1 ds); returns the largest step that keeps s and z in their cones.
  auto step_of = [&](const Direction& d, const Eigen::Matrix<double, kRows, Eigen::Dynamic>& U,
                     const std::array<Eigen::VectorXd, 2>& U_obj, Scaled& sc) {
    sc.ds.setZero(kRows, nf);
    sc.dz.setZero(kRows, nf);
    double amax = kInf;
#pragma omp parallel for schedule(static) reduction(min : amax) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      const VecL dl = local_dx(fs, d, j);
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        const Eigen::Vector3d dsk = cone_value(cone, dl) - cone.b;
        const int dim = cone.dim;
        if (dim == 1) {
          const double lam = fsys.lambda(3 * k);
          const double dst = dsk(0) / fsys.w[static_cast<size_t>(k)].beta;
          const double dzt = U(3 * k, j) - dst;
          sc.ds(3 * k, j) = dst;
          sc.dz(3 * k, j) = dzt;
          amax = std::min({amax, max_step_linear(lam, dst), max_step_linear(lam, dzt)});
        } else {
          const Eigen::Vector3d lam = fsys.lambda.segment<3>(3 * k);
          const Eigen::Vector3d dst = apply_winv(fsys.w[static_cast<size_t>(k)], dsk);
          const Eigen::Vector3d dzt = U.col(j).segment<3>(3 * k) - dst;
          sc.ds.col(j).segment<3>(3 * k) = dst;
          sc.dz.col(j).segment<3>(3 * k) = dzt;
          amax = std::min({amax, max_step(lam, dst), max_step(lam, dzt)});
        }
      }
    }
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        const Eigen::VectorXd dso = objective_direction(d, m);
        sc.ds_obj[m] = apply_winv(w_obj[m], dso);
        sc.dz_obj[m] = U_obj[m] - sc.ds_obj[m];
        amax = std::min({amax, max_step(lambda_obj[m], sc.ds_obj[m]), max_step(lambda_obj[m], sc.dz_obj[m])});
      }
    }
    return amax;
  };

  // Auxiliary a (0..3: c, r, s, e) of face j appears in no cone: its row of the Newton system is a unit row.
  auto unused_auxiliary = [&](int j, int a) {
    if (a == 0) return false;
    if (s.faces[static_cast<size_t>(j)].ghost()) return true;
    return a == 3 ? st.p_inf : st.h_max;
  };

  // A^T applied to per-cone vectors Z (faces) and Z_obj (objective cones): (rx, ry, r_t) on the positions, the
  // auxiliaries and the T_m. Unused auxiliaries (which appear in no cone) get 0. If z_max is given, it also gets the
  // largest entry of |A|^T |Z| over the positions and auxiliaries (the size of the terms that A^T Z sums), from the
  // same pass over the faces.
  auto adjoint = [&](const Eigen::Matrix<double, kRows, Eigen::Dynamic>& Z, const std::array<Eigen::VectorXd, 2>& Z_obj,
                     Eigen::VectorXd& rx, Eigen::VectorXd& ry, std::array<double, 2>& r_t, double* z_max = nullptr) {
    const bool magnitude = z_max != nullptr;
    rx.setZero(nv);
    ry.setZero(kAux * nf);
    r_t = {0, 0};
    Eigen::VectorXd mx, my;
    if (magnitude) {
      mx.setZero(nv);
      my.setZero(kAux * nf);
    }
    std::vector<VecL> g(static_cast<size_t>(nf)), gm(magnitude ? static_cast<size_t>(nf) : 0);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      VecL gl = VecL::Zero(), gml = VecL::Zero();
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        const auto zk = Z.col(j).segment(3 * k, cone.dim);
        const Eigen::Vector4d gk = cone.A.topRows(cone.dim).transpose() * zk;
        for (int a = 0; a < cone.n; ++a) gl(cone.var[static_cast<size_t>(a)]) += gk(a);
        if (magnitude) {
          const Eigen::Vector4d gmk = cone.A.topRows(cone.dim).cwiseAbs().transpose() * zk.cwiseAbs();
          for (int a = 0; a < cone.n; ++a) gml(cone.var[static_cast<size_t>(a)]) += gmk(a);
        }
      }
      g[static_cast<size_t>(j)] = gl;
      if (magnitude) gm[static_cast<size_t>(j)] = gml;
    }
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const VecL& gl = g[static_cast<size_t>(j)];
      const Vec6 gu = fs.S.transpose() * gl.head<4>();
      for (int r = 0; r < 6; ++r) {
        const int v = fs.var[static_cast<size_t>(r)];
        if (v >= 0) rx(v) += gu(r);
      }
      ry.segment<kAux>(kAux * j) = gl.segment<kAux>(kC);
      if (!fs.ghost()) r_t[static_cast<size_t>(fs.mesh)] += gl(kT);
      if (magnitude) {
        const VecL& gml = gm[static_cast<size_t>(j)];
        const Vec6 gmu = fs.S.cwiseAbs().transpose() * gml.head<4>();
        for (int r = 0; r < 6; ++r) {
          const int v = fs.var[static_cast<size_t>(r)];
          if (v >= 0) mx(v) += gmu(r);
        }
        my.segment<kAux>(kAux * j) = gml.segment<kAux>(kC);
      }
    }
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        const ObjectiveCone& oc = obj[m];
        r_t[m] += Z_obj[m](0);
        for (size_t i = 0; i < oc.faces.size(); ++i) {
          const double wz = oc.sqrt_w(static_cast<Eigen::Index>(i)) * Z_obj[m](static_cast<Eigen::Index>(i) + 1);
          ry(kAux * oc.faces[i] + 3) += wz;
          if (magnitude) my(kAux * oc.faces[i] + 3) += std::abs(wz);
        }
      }
    }
    auto zero_unused = [&](Eigen::VectorXd& y) {
      for (int j = 0; j < nf; ++j) {
        for (int a = 1; a < kAux; ++a) {
          if (unused_auxiliary(j, a)) y(kAux * j + a) = 0;
        }
      }
    };
    zero_unused(ry);
    if (magnitude) {
      zero_unused(my);
      *z_max = std::max(mx.lpNorm<Eigen::Infinity>(), my.lpNorm<Eigen::Infinity>());
    }
  };

  // H d = A^T W^-2 A d, formed cone by cone from the scalings (W^-1 applied twice), plus the unit rows of the unused
  // auxiliaries: the Newton matrix that the factorised Schur system, the Woodbury correction and the bordered 2 x 2
  // solve represent, without their cancellations.
  auto apply_newton_matrix = [&](const Direction& d, Eigen::VectorXd& hx, Eigen::VectorXd& hy,
                                 std::array<double, 2>& h_t) {
    Eigen::Matrix<double, kRows, Eigen::Dynamic> V = Eigen::Matrix<double, kRows, Eigen::Dynamic>::Zero(kRows, nf);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      const VecL dl = local_dx(fs, d, j);
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        const Scaling<3>& w = fsys.w[static_cast<size_t>(k)];
        const Eigen::Vector3d dsk = cone_value(cone, dl) - cone.b;
        if (cone.dim == 1) {
          V(3 * k, j) = dsk(0) / (w.beta * w.beta);
        } else {
          V.col(j).segment<3>(3 * k) = apply_winv<3>(w, apply_winv<3>(w, dsk));
        }
      }
    }
    std::array<Eigen::VectorXd, 2> V_obj;
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        const Eigen::VectorXd dso = objective_direction(d, m);
        V_obj[m] = apply_winv(w_obj[m], apply_winv(w_obj[m], dso));
      }
    }
    adjoint(V, V_obj, hx, hy, h_t);
    for (int j = 0; j < nf; ++j) {
      for (int a = 1; a < kAux; ++a) {
        if (unused_auxiliary(j, a)) hy(kAux * j + a) = d.dy(kAux * j + a);
      }
    }
  };
  // Iterative refinement of a solve of H d = r: d += solve(r - H d) while the residual, computed from the cones
  // (apply_newton_matrix), is above `enough` and shrinks at least by half, at most options.max_refinements times.
  // The factorised system loses precision to the elimination of nearly active cones (W^-2 with eigenvalues
  // ~ wbar_0^2 and ~ 1 / wbar_0^2), to the Woodbury correction and to CHOLMOD's diagonal shifts; without refinement
  // the dual residual grew from 1e-9 to 1e-4 in the last iterations and the method stalled at relative gaps of 1e-5,
  // at a level set by the BLAS kernel's rounding. The residual of the Newton equation becomes the dual residual after
  // a full step, so `enough` is a hundredth of the dual tolerance: most solves, early in a subproblem, need no
  // refinement and cost one product with H.
  auto refine = [&](Direction d, const Eigen::VectorXd& rx, const Eigen::VectorXd& ry, const std::array<double, 2>& r_t,
                    double enough) {
    auto residual = [&](const Direction& x, Eigen::VectorXd& ex, Eigen::VectorXd& ey, std::array<double, 2>& e_t) {
      apply_newton_matrix(x, ex, ey, e_t);
      ex = rx - ex;
      ey = ry - ey;
      e_t = {r_t[0] - e_t[0], r_t[1] - e_t[1]};
      return std::max({ex.lpNorm<Eigen::Infinity>(), ey.lpNorm<Eigen::Infinity>(), std::abs(e_t[0]), std::abs(e_t[1])});
    };
    Eigen::VectorXd ex, ey;
    std::array<double, 2> e_t{};
    double norm = residual(d, ex, ey, e_t);
    for (int k = 0; k < options.max_refinements && norm > enough; ++k) {
      const Direction c = solve(ex, ey, e_t);
      Direction next = d;
      next.dx += c.dx;
      next.dy += c.dy;
      next.dT = {d.dT[0] + c.dT[0], d.dT[1] + c.dT[1]};
      Eigen::VectorXd nx, ny;
      std::array<double, 2> n_t{};
      const double next_norm = residual(next, nx, ny, n_t);
      if (!(next_norm < norm)) break;
      const bool slow = next_norm > 0.5 * norm;
      d = std::move(next);
      norm = next_norm;
      ex = std::move(nx);
      ey = std::move(ny);
      e_t = n_t;
      if (slow) break;
    }
    return d;
  };

  // The scalings of every cone at (S, z) and the Newton system's per-face pieces; returns the gap s^T z.
  auto build_system = [&] {
    int elimination_ok = 1;
    // Scalings of the objective cones (p = 2): their Hessian part is diag(w_j / beta^2) on the e_j (which joins the
    // faces' eliminations below) + u_m u_m^T, coupled to T_m by kappa_m u_m, with h_TT on T_m.
    double gap = 0;
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        w_obj[m] = nt_scaling(S_obj[m], it.z_obj[m]);
        lambda_obj[m] = apply_w(w_obj[m], it.z_obj[m]);
        gap += S_obj[m].dot(it.z_obj[m]);
        const Scaling<Eigen::Dynamic>& w = w_obj[m];
        const ObjectiveCone& oc = obj[m];
        // W^-2 = (2 a a^T - J) / beta^2, a = J wbar, on (T, sqrt(w) e): e-block (I + 2 wb wb^T) / beta^2 (wb the tail
        // of wbar), T-e -2 wbar_0 wb / beta^2, T-T (2 wbar_0^2 - 1) / beta^2.
        u_obj[m].resize(static_cast<Eigen::Index>(oc.faces.size()));
        for (size_t i = 0; i < oc.faces.size(); ++i) {
          const auto ii = static_cast<Eigen::Index>(i);
          u_obj[m](ii) = std::sqrt(2.0) / w.beta * oc.sqrt_w(ii) * w.wbar(ii + 1);
        }
        kappa[m] = -std::sqrt(2.0) * w.wbar(0) / w.beta;
        h_tt[m] = (2 * w.wbar(0) * w.wbar(0) - 1) / (w.beta * w.beta);
      }
    }
    // Per face: the scalings and lambda of its cones, and its Hessian block A^T W^-2 A with the auxiliaries
    // eliminated. The block is the Gram matrix of M = W^-1 A (rows: the cones' scaled rows, plus the objective cone's
    // diagonal on e, plus unit rows for unused auxiliaries), and the elimination uses the QR factorisation
    // M_y = Q R of its auxiliaries' columns: the Schur complement is (Q_2^T M_q)^T (Q_2^T M_q), positive
    // semidefinite in floating point too. Formed as H_qq - H_qy H_yy^-1 H_yq instead, it lost all precision on
    // camel-cow's slivers (W^-2 has eigenvalues ~ wbar_0^2 and ~ 1 / wbar_0^2) and CHOLMOD needed diagonal shifts of
    // 100%.
#pragma omp parallel for schedule(static) reduction(+ : gap) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      FaceSystem& fsys = sys[static_cast<size_t>(j)];
      Eigen::Matrix<double, kMRows, kLocal> M = Eigen::Matrix<double, kMRows, kLocal>::Zero();
      int row = 0;
      fsys.lambda.setZero();
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        const int dim = cone.dim;
        const auto sk = S.col(j).segment(3 * k, dim);
        const auto zk = it.z.col(j).segment(3 * k, dim);
        Scaling<3>& w = fsys.w[static_cast<size_t>(k)];
        Eigen::Matrix<double, 3, 4> Mk = Eigen::Matrix<double, 3, 4>::Zero();
        if (dim == 1) {
          w.beta = std::sqrt(sk(0) / zk(0));
          fsys.lambda(3 * k) = std::sqrt(sk(0) * zk(0));
          Mk.row(0) = cone.A.row(0) / w.beta;
        } else {
          w = nt_scaling<3>(sk, zk);
          fsys.lambda.segment<3>(3 * k) = apply_w<3>(w, zk);
          Eigen::Vector3d jv = w.v;  // W^-1 = (2 Jv (Jv)^T - J) / beta
          jv.tail<2>() *= -1;
          Mk = 2 * jv * (jv.transpose() * cone.A);
          Mk.row(0) -= cone.A.row(0);
          Mk.bottomRows<2>() += cone.A.bottomRows<2>();
          Mk /= w.beta;
        }
        gap += sk.dot(zk);
        for (int r = 0; r < dim; ++r, ++row) {
          for (int a = 0; a < cone.n; ++a) M(row, cone.var[static_cast<size_t>(a)]) += Mk(r, a);
        }
      }
      if (!st.p_inf && !fs.ghost()) {
        M(row++, kE) =
            s.faces[static_cast<size_t>(j)].w > 0 ? std::sqrt(fs.w) / w_obj[static_cast<size_t>(fs.mesh)].beta : 0.0;
      }
      for (int a = kC; a < kT; ++a) {  // unused auxiliaries: a unit row (zero right-hand side, zero step)
        if (M.col(a).isZero()) M(row++, a) = 1;
      }
      const Eigen::Matrix<double, kMRows, kAux> My = M.middleCols<kAux>(kC);
      Eigen::Matrix<double, kMRows, 5> Mk;  // the kept columns: (alpha, beta, gamma, delta, T)
      Mk.leftCols<4>() = M.leftCols<4>();
      Mk.col(4) = M.col(kT);
      const Eigen::HouseholderQR<Eigen::Matrix<double, kMRows, kAux>> qr(My);
      const Eigen::Matrix<double, kMRows, 5> QtM = qr.householderQ().transpose() * Mk;
      fsys.R = qr.matrixQR().topRows<kAux>().triangularView<Eigen::Upper>();
      if (!(fsys.R.diagonal().cwiseAbs().minCoeff() > 0)) elimination_ok = 0;
      fsys.Cq = QtM.topLeftCorner<kAux, 4>();
      const Eigen::Matrix<double, kMRows - kAux, 4> Zq = QtM.bottomLeftCorner<kMRows - kAux, 4>();
      fsys.K = fs.S.transpose() * (Zq.transpose() * Zq) * fs.S;
      fsys.hxT = fs.S.transpose() * (M.leftCols<4>().transpose() * M.col(kT));
      fsys.hyT = My.transpose() * M.col(kT);
      fsys.h_tt = M.col(kT).squaredNorm();
    }
    if (elimination_ok == 0) throw PipelineError("convex subproblem: an auxiliary block is singular");
    if (st.p_inf) {
      h_tt = {0, 0};
      for (int j = 0; j < nf; ++j) {
        const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
        if (!fs.ghost()) h_tt[static_cast<size_t>(fs.mesh)] += sys[static_cast<size_t>(j)].h_tt;
      }
    }
    return gap;
  };

  // Assembles the Schur system in the vertex coordinates and factorises it (with a relative diagonal shift if rounding
  // made it indefinite); false if no shift made it factorise.
  auto factor_system = [&] {
    // p = inf: the T couplings were taken before the elimination; they are the plain blocks of H (the bordered solve
    // eliminates through P^-1, which includes the auxiliaries).
    double* values = pattern.A.valuePtr();
    std::fill(values, values + pattern.A.nonZeros(), 0.0);
    for (int j = 0; j < nf; ++j) {
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const auto& idx = pattern.index[static_cast<size_t>(j)];
      for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) {
          const int i = idx[static_cast<size_t>(6 * r + c)];
          if (i >= 0) values[i] += fsys.K(r, c);
        }
      }
    }
    return factorize_with_shift(cholesky, pattern.A, last_shift);
  };

  int short_steps = 0;
  // The dual-feasible iterate with the smallest gap: what a stop at the precision limit returns.
  double best_gap = kInf;
  Eigen::VectorXd best_pos = it.pos;
  std::vector<std::pair<double, double>> history;  // (gap, objective) at the start of every iteration
  for (int iter = 0; iter < options.max_newton_steps; ++iter) {
    const auto step_start = std::chrono::steady_clock::now();
    BarrierStep trace;
    const double gap = build_system();
    const double mu = gap / nu;
    const double f0 = it.T[0] + it.T[1];
    // Dual residual A^T z - c (0 at a dual feasible point).
    Eigen::VectorXd res_x, res_y;
    std::array<double, 2> res_t{};
    // Relative to the dual variables' size: the residual in a vertex's coordinates is a sum of terms of the size of
    // its faces' z, up to ~1e6 on slivers, and cancels to ~1e-10 of them at best.
    double z_max = 0;
    adjoint(it.z, it.z_obj, res_x, res_y, res_t, &z_max);
    res_t[0] -= 1;
    res_t[1] -= 1;
    const double dres = std::max({res_x.lpNorm<Eigen::Infinity>(), res_y.lpNorm<Eigen::Infinity>(), std::abs(res_t[0]),
                                  std::abs(res_t[1])}) /
                        std::max(1.0, z_max);
    const double refined_enough = 1e-2 * kDualTolerance * std::max(1.0, z_max);
    if (dres <= kDualTolerance && gap < best_gap) {  // a certificate: f0 - optimum <= gap
      best_gap = gap;
      best_pos = it.pos;
    }
    trace.centring = iter;
    trace.t = 1 / mu;
    trace.objective = f0;
    if (gap <= options.relative_gap * f0 && dres <= kDualTolerance) {
      result.converged = true;
      break;
    }
    // No progress over the window: stop at this strictly feasible iterate, uncertified (precision limit).
    history.push_back({gap, f0});
    if (history.size() > kProgressWindow) {
      const auto [gap_then, f0_then] = history[history.size() - 1 - kProgressWindow];
      if (gap > 0.5 * gap_then && std::abs(f0 - f0_then) <= 0.1 * options.relative_gap * f0) {
        result.stalled_centrings = 1;
        break;
      }
    }

    const auto factor_start = std::chrono::steady_clock::now();
    trace.seconds_derivatives = std::chrono::duration<double>(factor_start - step_start).count();
    if (!factor_system()) {
      result.stalled_centrings = 1;
      break;
    }
    trace.seconds_factorization =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - factor_start).count();

    // Right-hand side A^T W^-1 u + (A^T z - c), u = lambda \ xi - lambda per cone (xi = 0: the predictor). In exact
    // arithmetic A^T W^-1 lambda = A^T z, and the right-hand side is A^T W^-1 (lambda \ xi) - c; written out, the
    // step also corrects whatever dual residual rounding left.
    auto rhs = [&](const Eigen::Matrix<double, kRows, Eigen::Dynamic>& Xi, const std::array<Eigen::VectorXd, 2>& Xi_obj,
                   Eigen::VectorXd& rx, Eigen::VectorXd& ry, std::array<double, 2>& r_t,
                   Eigen::Matrix<double, kRows, Eigen::Dynamic>& U, std::array<Eigen::VectorXd, 2>& U_obj) {
      U.setZero(kRows, nf);
      Eigen::Matrix<double, kRows, Eigen::Dynamic> V = Eigen::Matrix<double, kRows, Eigen::Dynamic>::Zero(kRows, nf);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
      for (int j = 0; j < nf; ++j) {
        const FaceCones& fc = cones[static_cast<size_t>(j)];
        const FaceSystem& fsys = sys[static_cast<size_t>(j)];
        for (int k = 0; k < fc.n; ++k) {
          const int dim = fc.cone[static_cast<size_t>(k)].dim;
          if (dim == 1) {
            const double lam = fsys.lambda(3 * k);
            const double u = Xi(3 * k, j) / lam - lam;
            U(3 * k, j) = u;
            V(3 * k, j) = u / fsys.w[static_cast<size_t>(k)].beta;
          } else {
            const Eigen::Vector3d lam = fsys.lambda.segment<3>(3 * k);
            const Eigen::Vector3d u = jordan_div<3>(lam, Xi.col(j).segment<3>(3 * k)) - lam;
            U.col(j).segment<3>(3 * k) = u;
            V.col(j).segment<3>(3 * k) = apply_winv(fsys.w[static_cast<size_t>(k)], u);
          }
        }
      }
      std::array<Eigen::VectorXd, 2> V_obj;
      if (!st.p_inf) {
        for (size_t m = 0; m < 2; ++m) {
          U_obj[m] = jordan_div(lambda_obj[m], Xi_obj[m]) - lambda_obj[m];
          V_obj[m] = apply_winv(w_obj[m], U_obj[m]);
        }
      }
      adjoint(V, V_obj, rx, ry, r_t);
      rx += res_x;
      ry += res_y;
      r_t[0] += res_t[0];
      r_t[1] += res_t[1];
    };
    // Predictor (affine scaling direction).
    Eigen::Matrix<double, kRows, Eigen::Dynamic> Xi = Eigen::Matrix<double, kRows, Eigen::Dynamic>::Zero(kRows, nf);
    std::array<Eigen::VectorXd, 2> Xi_obj;
    for (size_t m = 0; m < 2 && !st.p_inf; ++m) Xi_obj[m] = Eigen::VectorXd::Zero(lambda_obj[m].size());
    Eigen::VectorXd rx, ry;
    std::array<double, 2> r_t{};
    Eigen::Matrix<double, kRows, Eigen::Dynamic> U;
    std::array<Eigen::VectorXd, 2> U_obj;
    rhs(Xi, Xi_obj, rx, ry, r_t, U, U_obj);
    // One solve with P for the coupling columns and the predictor's right-hand side.
    coupling_columns();
    Direction d_aff;
    {
      Eigen::MatrixXd Rx(nv, 3), Ry(kAux * nf, 3), Dx, Dy;
      Rx << Cx, rx;
      Ry << Cy, ry;
      apply_pinv.template operator()<3>(Rx, Ry, Dx, Dy);
      Dcx = Dx.leftCols<2>();
      Dcy = Dy.leftCols<2>();
      finish_coupling();
      d_aff = refine(finish_solve(Dx.col(2), Dy.col(2), r_t), rx, ry, r_t, refined_enough);
    }
    Scaled sc_aff;
    const double a_aff = std::min(1.0, step_of(d_aff, U, U_obj, sc_aff));
    const double sigma = std::pow(1 - a_aff, 3);
    // Corrector: xi = sigma mu e - ds~_a o dz~_a.
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceCones& fc = cones[static_cast<size_t>(j)];
      for (int k = 0; k < fc.n; ++k) {
        const int dim = fc.cone[static_cast<size_t>(k)].dim;
        if (dim == 1) {
          Xi(3 * k, j) = sigma * mu - sc_aff.ds(3 * k, j) * sc_aff.dz(3 * k, j);
        } else {
          Xi.col(j).segment<3>(3 * k) =
              -jordan_prod<3>(sc_aff.ds.col(j).segment<3>(3 * k), sc_aff.dz.col(j).segment<3>(3 * k));
          Xi(3 * k, j) += sigma * mu;
        }
      }
    }
    if (!st.p_inf) {
      for (size_t m = 0; m < 2; ++m) {
        Xi_obj[m] = -jordan_prod(sc_aff.ds_obj[m], sc_aff.dz_obj[m]);
        Xi_obj[m](0) += sigma * mu;
      }
    }
    rhs(Xi, Xi_obj, rx, ry, r_t, U, U_obj);
    Direction d = refine(solve(rx, ry, r_t), rx, ry, r_t, refined_enough);
    Scaled sc;
    double step = std::min(1.0, kStepFraction * step_of(d, U, U_obj, sc));

    // Take the step; the slacks are recomputed from the primal variables (exact primal feasibility), and the step
    // is shortened if rounding put a nearly active cone outside.
    const auto search_start = std::chrono::steady_clock::now();
    Iterate next;
    for (int halvings = 0;; ++halvings, step *= 0.5) {
      if (halvings == 30) {
        step = 0;
        break;
      }
      next.pos = it.pos;
      next.pos.tail(nv) += step * d.dx;
      next.y = it.y;
      for (int j = 0; j < nf; ++j) next.y.col(j) += step * d.dy.segment<kAux>(kAux * j);
      next.T = {it.T[0] + step * d.dT[0], it.T[1] + step * d.dT[1]};
      // Dual step: z + step dz, dz = W^-1 dz~ per cone.
      next.z = it.z;
      int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf > kParallelFaces)
      for (int j = 0; j < nf; ++j) {
        const FaceCones& fc = cones[static_cast<size_t>(j)];
        const FaceSystem& fsys = sys[static_cast<size_t>(j)];
        for (int k = 0; k < fc.n; ++k) {
          const int dim = fc.cone[static_cast<size_t>(k)].dim;
          const Scaling<3>& w = fsys.w[static_cast<size_t>(k)];
          if (dim == 1) {
            next.z(3 * k, j) += step * sc.dz(3 * k, j) / w.beta;
          } else {
            next.z.col(j).segment<3>(3 * k) += step * apply_winv<3>(w, sc.dz.col(j).segment<3>(3 * k));
          }
          if (!in_cone(next.z.col(j).segment(3 * k, dim))) ok = 0;
        }
      }
      if (!st.p_inf) {
        for (size_t m = 0; m < 2; ++m) {
          next.z_obj[m] = it.z_obj[m] + step * apply_winv(w_obj[m], sc.dz_obj[m]);
          if (!in_cone(next.z_obj[m])) ok = 0;
        }
      }
      Eigen::Matrix<double, kRows, Eigen::Dynamic> S_next;
      std::array<Eigen::VectorXd, 2> s_obj_next;
      if (ok == 1 && slacks(next, S_next, s_obj_next)) {
        S = std::move(S_next);
        S_obj = std::move(s_obj_next);
        break;
      }
    }
    trace.seconds_line_search = std::chrono::duration<double>(std::chrono::steady_clock::now() - search_start).count();
    ++result.newton_steps;
    trace.step = step;
    trace.lambda2 = dres;
    trace.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count();
    // Steps this short twice in a row: the directions have reached the limit of double precision.
    short_steps = step < kShortStep ? short_steps + 1 : 0;
    if (step == 0 || short_steps == 2) {
      if (step > 0) it = std::move(next);
      if (options.on_step) options.on_step(trace);
      result.stalled_centrings = 1;
      break;
    }
    it = std::move(next);
    trace.objective = it.T[0] + it.T[1];
    if (options.on_step) options.on_step(trace);
  }
  // Converged: the current iterate is the best certified one. Otherwise the best certified one, whose gap is the
  // honest bound (+infinity if no iterate was dual feasible).
  result.gap_bound = best_gap;
  const Eigen::VectorXd& pos = std::isfinite(best_gap) ? best_pos : it.pos;
  result.X.resize(problem.n_slots, 2);
  for (int i = 0; i < problem.n_slots; ++i) result.X.row(i) = pos.segment<2>(2 * i).transpose();
  result.objective = subproblem_objective(problem, result.X);
  return result;
}

}  // namespace liftmap
