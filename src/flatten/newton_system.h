#pragma once
/// The Newton (KKT) system that both solvers of the convex subproblem (10) solve at every iteration
/// (barrier_solver.cpp, primal_dual_solver.cpp). Its unknowns are the positions' free coordinates x (#unknowns of
/// the Setup), the auxiliaries y (A per face, A = Face::kAux) and the two epigraph variables t = (T_0, T_1):
///
///     H = [[P + U U^T,  C K    ],     P = sum_j E_j^T [[S_j^T H_qq S_j, S_j^T H_qy], [H_yq S_j, H_yy]] E_j,
///          [K C^T,      diag(h)]]
///
/// with q = (alpha, beta, gamma, delta) = S_j u_j the face's similarity coordinates, E_j the selection of its corners
/// and auxiliaries, and the global coupling of (10a) in C (two columns over (x, y)):
/// - bordered (p = inf): C = the faces' couplings with the T_m of their mesh, K = I, U = 0;
/// - rank two (p = 2): C = U = the objective cones' columns u_m on the e_j, K = diag(kappa_m).
/// A solve: each face's auxiliaries eliminated by a Schur complement in its corner coordinates,
/// K_j = S^T (H_qq - H_qy H_yy^-1 H_yq) S; the sparse sum of the K_j factorised once (CHOLMOD); P^-1 applied to the
/// right-hand side together with the coupling columns; then a 2 x 2 system in (dT_0, dT_1) (CoupledSolve).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Householder>
#include <Eigen/QR>
#include <array>
#include <vector>

#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem_faces.h"

namespace liftmap::subproblem {

/// The rows of a face's six corner coordinates in X (#unknowns by NC); those of the fixed gauge vertex are 0.
template <int NC, class Derived>
Eigen::Matrix<double, 6, NC> gather_corners(const FaceSetup& fs, const Eigen::MatrixBase<Derived>& X) {
  Eigen::Matrix<double, 6, NC> out = Eigen::Matrix<double, 6, NC>::Zero();
  for (int r = 0; r < 6; ++r) {
    const int v = fs.var[static_cast<size_t>(r)];
    if (v >= 0) out.row(r) = X.row(v);
  }
  return out;
}

/// Sets the values of the Schur system's stored entries to 0 (on two threads for large systems).
void clear_values(Pattern& pattern);

/// Adds a face's 6 x 6 corner block K into the Schur system's values at its entries `index` (Pattern::index).
inline void add_corner_block(double* values, const std::array<int, 36>& index, const Mat6& K) {
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const int i = index[static_cast<size_t>(6 * r + c)];
      if (i >= 0) values[i] += K(r, c);
    }
  }
}

/// X.row(v) -= rows[j].row(r) for every corner coordinate r (unknown v) of every face j.
template <int NC>
void subtract_corner_rows(const Setup& s, const FacePartition& p, const std::vector<Eigen::Matrix<double, 6, NC>>& rows,
                          Eigen::MatrixXd& X) {
  for_each_face_partitioned(p, [&](int j, int /*list*/) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    for (int r = 0; r < 6; ++r) {
      const int v = fs.var[static_cast<size_t>(r)];
      if (v >= 0) X.row(v) -= rows[static_cast<size_t>(j)].row(r);
    }
  });
}

/// Factorises the Schur system A. Rounding in the eliminated blocks of nearly active constraints can make it
/// numerically indefinite late in a solve: then its diagonal is shifted, relative to each entry (the curvatures span
/// many orders of magnitude), by 1e-2 times the shift that worked last time (at least 1e-14), growing 100-fold per
/// attempt (each a full factorisation). Any positive definite matrix still gives a descent direction, and the
/// solvers' steps keep the iterate feasible. Leaves A shifted if it was.
/// Once a solve has needed a shift, the unshifted attempt is skipped: the systems stay indefinite from then on, and
/// the floor of 1e-14 relative is below the factorisation's own rounding.
/// \param last_shift in: the last successful shift (0: none needed so far); out: this one's
/// \return false if no shift below 1e3 makes it factorise (the limit of double precision).
bool factorize_with_shift(SparseCholesky& cholesky, Eigen::SparseMatrix<double>& A, double& last_shift);

/// A vector over the Newton system's unknowns: positions x (#unknowns), auxiliaries y (A per face, face j's at rows
/// A j .. A j + A - 1), epigraph variables t. Directions, right-hand sides and residuals are such vectors.
struct NewtonVector {
  Eigen::VectorXd x, y;
  std::array<double, 2> t{0, 0};
};

/// A face's part of P with its two auxiliaries eliminated, from its local Hessian H over
/// (alpha, beta, gamma, delta, y_0, y_1, T): the barrier method's per-face system.
struct HessianFaceBlock {
  static constexpr int kAux = 2;
  Mat6 K;                         ///< Schur complement in the corner coordinates (positive semidefinite)
  Eigen::Matrix<double, 6, 2> B;  ///< coupling corners -> auxiliaries, S^T H_qy
  Eigen::Matrix2d Pinv;           ///< H_yy^-1 (symmetrised)
  Vec6 hxT = Vec6::Zero();        ///< coupling corners -> T of the face's mesh, S^T H_qT
  Eigen::Vector2d hyT = Eigen::Vector2d::Zero();  ///< coupling auxiliaries -> T, H_yT
  double h_tt = 0;                                ///< H_TT

  /// Eliminates the auxiliaries of the local Hessian H (7 x 7, symmetric, H_yy positive definite). The Schur
  /// complement H_qq - H_qy H_yy^-1 H_yq is formed as H_qq - W^T W, W = L^-1 H_yq (H_yy = L L^T): symmetric and
  /// positive semidefinite by construction where the plain product with H_yy^-1 is not (its entries span up to 20
  /// orders of magnitude on nearly active faces). Negative eigenvalues that rounding leaves are clamped
  /// (positive_corner_block). If `isotropic`, the (gamma, delta) block's smaller curvature is raised to its larger one
  /// (BarrierSettings::isotropic_anticonformal_curvature): the block only grows, so the step stays a descent direction.
  void eliminate(const Eigen::Matrix<double, 7, 7>& H, const Mat46& S, bool isotropic);

  /// B H_yy^-1 r: what the auxiliaries' right-hand side r contributes to the corner coordinates' one.
  /// (S, the face's corner map, is unused: B holds it.)
  template <int NC>
  [[nodiscard]] Eigen::Matrix<double, 6, NC> corner_rows(const Mat46& /*S*/,
                                                         const Eigen::Matrix<double, kAux, NC>& r) const {
    return B * (Pinv * r);
  }
  /// H_yy^-1 (r - B^T dx): the auxiliaries' part of the solution once the corners' part dx is known.
  template <int NC>
  [[nodiscard]] Eigen::Matrix<double, kAux, NC> back_substitute(const Mat46& /*S*/,
                                                                const Eigen::Matrix<double, kAux, NC>& r,
                                                                const Eigen::Matrix<double, 6, NC>& dx) const {
    return Pinv * (r - B.transpose() * dx);
  }
};

/// A face's part of P with its four auxiliaries eliminated, from the rows M of a Gram factor of its local Hessian,
/// H = M^T M over (alpha, beta, gamma, delta, y_0 .. y_3, T): the primal-dual method's per-face system, whose M is
/// W^-1 A (the cones' scaled rows). The elimination uses the QR factorisation M_y = Q R of the auxiliaries' columns:
/// the Schur complement is (Q_2^T M_q)^T (Q_2^T M_q), positive semidefinite in floating point too (formed as
/// H_qq - H_qy H_yy^-1 H_yq it lost all precision on slivers, where W^-2 has eigenvalues ~ wbar_0^2 and 1 / wbar_0^2).
struct GramFaceBlock {
  static constexpr int kAux = 4;
  static constexpr int kLocal = 4 + kAux + 1;
  Mat6 K;                                         ///< Schur complement in the corner coordinates
  Eigen::Matrix4d R;                              ///< H_yy = R^T R
  Eigen::Matrix4d Cq;                             ///< R^-T H_yq, so that H_yq = R^T Cq
  Vec6 hxT = Vec6::Zero();                        ///< S^T H_qT
  Eigen::Vector4d hyT = Eigen::Vector4d::Zero();  ///< H_yT
  double h_tt = 0;                                ///< H_TT

  /// Eliminates the auxiliaries of H = M^T M (Rows by kLocal). \return false if M_y has not full column rank.
  template <int Rows>
  bool eliminate(const Eigen::Matrix<double, Rows, kLocal>& M, const Mat46& S) {
    const Eigen::Matrix<double, Rows, kAux> My = M.template middleCols<kAux>(4);
    Eigen::Matrix<double, Rows, 5> Mq;  // the kept columns: (alpha, beta, gamma, delta, T)
    Mq.template leftCols<4>() = M.template leftCols<4>();
    Mq.col(4) = M.col(kLocal - 1);
    const Eigen::HouseholderQR<Eigen::Matrix<double, Rows, kAux>> qr(My);
    const Eigen::Matrix<double, Rows, 5> QtM = qr.householderQ().transpose() * Mq;
    R = qr.matrixQR().template topRows<kAux>().template triangularView<Eigen::Upper>();
    Cq = QtM.template topLeftCorner<kAux, 4>();
    const Eigen::Matrix<double, Rows - kAux, 4> Zq = QtM.template bottomLeftCorner<Rows - kAux, 4>();
    K = S.transpose() * (Zq.transpose() * Zq) * S;
    hxT = S.transpose() * (M.template leftCols<4>().transpose() * M.col(kLocal - 1));
    hyT = My.transpose() * M.col(kLocal - 1);
    h_tt = M.col(kLocal - 1).squaredNorm();
    return R.diagonal().cwiseAbs().minCoeff() > 0;
  }

  /// B H_yy^-1 r = S^T Cq^T R^-T r (B = S^T H_qy). S: the face's corner map.
  template <int NC>
  [[nodiscard]] Eigen::Matrix<double, 6, NC> corner_rows(const Mat46& S,
                                                         const Eigen::Matrix<double, kAux, NC>& r) const {
    const Eigen::Matrix<double, kAux, NC> t = R.transpose().template triangularView<Eigen::Lower>().solve(r);
    return S.transpose() * (Cq.transpose() * t);
  }
  /// H_yy^-1 (r - H_yq S dx) = R^-1 (R^-T r - Cq S dx).
  template <int NC>
  [[nodiscard]] Eigen::Matrix<double, kAux, NC> back_substitute(const Mat46& S,
                                                                const Eigen::Matrix<double, kAux, NC>& r,
                                                                const Eigen::Matrix<double, 6, NC>& dx) const {
    const Eigen::Matrix<double, kAux, NC> t = R.transpose().template triangularView<Eigen::Lower>().solve(r);
    return R.template triangularView<Eigen::Upper>().solve(t - Cq * (S * dx));
  }
};

/// The two coupling columns C of the epigraph variables, over the positions (x) and the auxiliaries (y).
struct CouplingColumns {
  Eigen::MatrixXd x, y;  ///< #unknowns by 2, A #faces by 2
};

/// How the Schur system's sum over faces is formed: the faces of the factorisation's two halves on two threads, the
/// rest after them (for_each_face_partitioned), or one face after the other. The two orders round differently, and
/// the primal-dual method's p = inf iterates follow that rounding (docs/performance.md), so each solver keeps its own.
enum class SchurAssembly { kPartitioned, kFaceOrder };

/// Bounds of a face's auxiliary c at given positions: lo = |(gamma, delta)| < c < l = alpha cos + beta sin, and
/// n = |(alpha, beta)|. A start is strictly feasible where lo < l on every face (sigma_tilde_j > 0).
struct FaceStart {
  double n = 0, lo = 0, l = 0;
};

/// FaceStart of every face of s at the positions pos (2 #slots).
/// \throw InvalidInputError naming the first face with lo >= l (sigma_tilde_j <= 0): pos is not strictly feasible.
std::vector<FaceStart> strictly_feasible_start(const Setup& s, const Eigen::VectorXd& pos);

/// The Newton system of one solve: the per-face blocks (set by the solver's elimination, every iteration), the
/// factorisation of their Schur sum, and P^-1. Face: HessianFaceBlock or GramFaceBlock.
template <class Face>
class NewtonSystem {
 public:
  static constexpr int kAux = Face::kAux;

  /// \param s the per-face data (kept by reference), \param assembly its pattern and face partition,
  /// \param cholesky analysed for the pattern (assembly_structure)
  NewtonSystem(const Setup& s, AssemblyStructure& assembly, SparseCholesky& cholesky)
      : s_(s), assembly_(assembly), cholesky_(cholesky), faces(static_cast<size_t>(s.n_faces)) {}

  /// Writes sum_j K_j into the Schur system's values.
  void assemble(SchurAssembly order) {
    Pattern& pattern = assembly_.pattern;
    clear_values(pattern);
    double* values = pattern.A.valuePtr();
    if (order == SchurAssembly::kPartitioned) {
      for_each_face_partitioned(assembly_.parts, [&](int j, int /*list*/) {
        add_corner_block(values, pattern.index[static_cast<size_t>(j)], faces[static_cast<size_t>(j)].K);
      });
      return;
    }
    for (int j = 0; j < s_.n_faces; ++j) {
      add_corner_block(values, pattern.index[static_cast<size_t>(j)], faces[static_cast<size_t>(j)].K);
    }
  }

  /// Factorises the assembled Schur system (factorize_with_shift, remembering the last shift); false if no shift
  /// made it factorise.
  bool factorize() { return factorize_with_shift(cholesky_, assembly_.pattern.A, last_shift_); }

  /// (Dx; Dy) = P^-1 (Rx; Ry) for NC columns: Rx #unknowns rows, Ry A #faces rows. Needs factorize().
  template <int NC>
  void apply_pinv(const Eigen::MatrixXd& Rx, const Eigen::MatrixXd& Ry, Eigen::MatrixXd& Dx,
                  Eigen::MatrixXd& Dy) const {
    using Corner = Eigen::Matrix<double, 6, NC>;
    using Aux = Eigen::Matrix<double, kAux, NC>;
    const int nf = s_.n_faces;
    std::vector<Corner> corner_rows(static_cast<size_t>(nf));
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const Aux r = Ry.template block<kAux, NC>(kAux * j, 0);
      corner_rows[static_cast<size_t>(j)].noalias() =
          faces[static_cast<size_t>(j)].template corner_rows<NC>(s_.faces[static_cast<size_t>(j)].S, r);
    }
    Eigen::MatrixXd Rt = Rx;
    subtract_corner_rows<NC>(s_, assembly_.parts, corner_rows, Rt);
    Dx = cholesky_.solve(Rt);
    Dy.resize(kAux * nf, NC);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const Aux r = Ry.template block<kAux, NC>(kAux * j, 0);
      const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
      Dy.template block<kAux, NC>(kAux * j, 0).noalias() =
          faces[static_cast<size_t>(j)].template back_substitute<NC>(fs.S, r, gather_corners<NC>(fs, Dx));
    }
  }

  /// The bordered coupling columns (p = inf): column m sums the couplings (hxT; hyT) of mesh m's faces.
  [[nodiscard]] CouplingColumns face_coupling() const {
    CouplingColumns C{Eigen::MatrixXd::Zero(s_.n_var, 2), Eigen::MatrixXd::Zero(kAux * s_.n_faces, 2)};
    for (int j = 0; j < s_.n_faces; ++j) {
      const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
      if (fs.ghost()) continue;
      const Face& f = faces[static_cast<size_t>(j)];
      C.y.template block<kAux, 1>(kAux * j, fs.mesh) = f.hyT;
      for (int r = 0; r < 6; ++r) {
        const int v = fs.var[static_cast<size_t>(r)];
        if (v >= 0) C.x(v, fs.mesh) += f.hxT(r);
      }
    }
    return C;
  }

  /// The rank-two coupling columns (p = 2): u(j) on auxiliary `aux` of every face j of mesh m, in column m.
  template <class Fn>
  [[nodiscard]] CouplingColumns rank_two_columns(int aux, Fn&& u) const {
    CouplingColumns C{Eigen::MatrixXd::Zero(s_.n_var, 2), Eigen::MatrixXd::Zero(kAux * s_.n_faces, 2)};
    for (int j = 0; j < s_.n_faces; ++j) {
      const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
      if (!fs.ghost()) C.y(kAux * j + aux, fs.mesh) = u(j);
    }
    return C;
  }

 private:
  const Setup& s_;
  AssemblyStructure& assembly_;
  SparseCholesky& cholesky_;
  double last_shift_ = 0;  // relative diagonal shift of the last factorisation that needed one

 public:
  std::vector<Face> faces;  ///< #faces blocks, set by the solver's elimination before assemble()
};

/// The last step of a Newton solve: the global coupling through (T_0, T_1), once P^-1 is known on the coupling
/// columns. Bordered (p = inf): [[P, C], [C^T, diag(h)]], by the 2 x 2 Schur complement diag(h) - C^T P^-1 C.
/// Rank two (p = 2): [[P + C C^T, C K], [K C^T, diag(h)]], K = diag(kappa): Woodbury for A = P + C C^T
/// (A^-1 C = P^-1 C M^-1, M = I + C^T P^-1 C, which is >= I: no cancellation), then the 2 x 2 Schur complement
/// diag(h) - K C^T A^-1 C K in (dT_0, dT_1), then back-substitution.
class CoupledSolve {
 public:
  /// Bordered system. \param C coupling columns, \param pinv_c P^-1 C, \param h H's diagonal on (T_0, T_1)
  static CoupledSolve bordered(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h);
  /// Rank-two system. \param kappa the coupling factors K
  static CoupledSolve rank_two(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h,
                               const std::array<double, 2>& kappa);

  /// The solution d of H d = r, given (pinv_rx; pinv_ry) = P^-1 (r.x; r.y) and r_t = r.t.
  [[nodiscard]] NewtonVector solve(Eigen::VectorXd pinv_rx, Eigen::VectorXd pinv_ry,
                                   const std::array<double, 2>& r_t) const;

 private:
  CoupledSolve(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h);
  [[nodiscard]] Eigen::Matrix2d gram() const;  // C^T P^-1 C, symmetrised

  CouplingColumns C_, pinv_c_;
  std::array<double, 2> h_{0, 0};
  bool rank_two_ = false;
  Eigen::Vector2d kappa_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d schur_ = Eigen::Matrix2d::Zero();  // the 2 x 2 Schur complement in (dT_0, dT_1)
  Eigen::Matrix2d Minv_ = Eigen::Matrix2d::Zero();   // rank two: M^-1
  Eigen::Matrix2d GM_ = Eigen::Matrix2d::Zero();     // rank two: C^T A^-1 C = G M^-1, G = C^T P^-1 C
};

}  // namespace liftmap::subproblem
