#pragma once
/// Per-face Jacobians of a flattening as constant linear maps of the vertex positions (paper §3.3,
/// "Optimizing Phi, Psi"; docs/algorithm.md: A_j = U D (X D)^+).

#include <Eigen/Core>

namespace liftmap {

/// The linear maps from a flattening to its per-face Jacobians, computed once per mesh.
/// Row j of `G` holds the gradients of the three hat functions of face j in an orthonormal frame of its plane,
/// (g0x, g0y, g1x, g1y, g2x, g2y), so that the Jacobian of the flattening U on face j is
/// A_j = sum_k U(F(j,k))^T (gkx, gky), i.e. a11 = sum_k u_k gkx, a12 = sum_k u_k gky, a21 = sum_k v_k gkx, ...
struct JacobianOperator {
  Eigen::MatrixXd G;     ///< #F by 6 hat-function gradients
  Eigen::VectorXd area;  ///< #F face areas |t_j|
};

/// Builds the Jacobian operator of a triangle mesh.
/// \param V #V by 3 vertex positions
/// \param F #F by 3 vertex indices
/// \throw InvalidInputError naming the face if a face is degenerate (zero area).
JacobianOperator jacobian_operator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// The Jacobians of a flattening in the 2-vector form of docs/algorithm.md, "The convexified distortion":
/// alpha = (a11+a22)/2, beta = (a21-a12)/2, gamma = (a11-a22)/2, delta = (a12+a21)/2.
/// \param op the mesh's Jacobian operator
/// \param F #F by 3 vertex indices
/// \param U #V by 2 flattened positions
/// \return #F by 4 rows (alpha, beta, gamma, delta)
Eigen::MatrixXd similarity_parts(const JacobianOperator& op, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U);

/// The 4 by 6 matrix mapping a face's flattened corners (u0, v0, u1, v1, u2, v2) to (alpha, beta, gamma, delta).
/// \param g one row of JacobianOperator::G
Eigen::Matrix<double, 4, 6> similarity_map(const Eigen::Matrix<double, 1, 6>& g);

}  // namespace liftmap
