// The arithmetic of the supernodal numeric factorisation, once per instruction set (supernodal_numeric.h). It uses
// Eigen's types for its arrays, not the standard library's: a standard template instance compiled here for AVX2
// could be the one the linker keeps for every object, and fail on a CPU without it.

#include "flatten/supernodal_numeric.h"

#include <omp.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#ifndef LIFTMAP_KERNELS
#define LIFTMAP_KERNELS baseline
#endif

namespace liftmap::LIFTMAP_KERNELS {

namespace {

using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using ConstBlock = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

/// One thread's scratch: the row map of the supernode being factorised and the update block.
struct Workspace {
  Eigen::VectorXi position;  // row -> its index in the current supernode's rows
  Eigen::MatrixXd update;
};

/// Per supernode: the first supernode whose update to it is pending (-1: none). Each thread links into its own
/// lists; the top reads all three.
using Lists = Eigen::VectorXi;

/// The factorisation's state shared by both threads: each thread writes only its own supernodes' blocks, links and
/// positions.
class Factorization {
 public:
  Factorization(const LowerColumns& B, const SupernodalStructure& L, double* x)
      : B_(B),
        L_(L),
        x_(x),
        supernode_of_(L.n),
        next_(Eigen::VectorXi::Constant(L.count, -1)),
        position_(Eigen::VectorXi::Zero(L.count)) {
    for (int s = 0; s < L.count; ++s) supernode_of_.segment(L.super[s], L.columns(s)).setConstant(s);
  }

  /// Factorises `order`'s supernodes (ascending), taking their pending updates from the first `n_from` lists of
  /// `from` and linking each finished supernode into `to`. \return -1, or the first column of a failing supernode.
  int run(SupernodeOrder order, Lists* const* from, int n_from, Lists& to, Workspace& w) {
    w.position.resize(L_.n);
    for (int k = 0; k < order.count; ++k) {
      const int s = order.supernodes[k];
      scatter_columns(s, w);
      for (int l = 0; l < n_from; ++l) apply_pending_updates(s, *from[l], to, w);
      if (!factorize_block(s)) return L_.super[s];
      link_to_next_row(s, L_.super[s + 1] - L_.super[s], to);
    }
    return -1;
  }

 private:
  [[nodiscard]] int rows_of(int s) const { return L_.rows_of(s); }
  [[nodiscard]] int columns_of(int s) const { return L_.columns(s); }
  [[nodiscard]] Block block(int s) const {
    return {x_ + L_.px[s], rows_of(s), columns_of(s), Eigen::OuterStride<>(rows_of(s))};
  }

  /// Step 1: L_s = B's columns of s, zero elsewhere; the row map of s into w.
  void scatter_columns(int s, Workspace& w) const {
    const int* rows = L_.rows + L_.pi[s];
    for (int i = 0; i < rows_of(s); ++i) w.position(rows[i]) = i;
    Block Ls = block(s);
    Ls.setZero();
    for (int k = L_.super[s]; k < L_.super[s + 1]; ++k) {
      for (int e = B_.p[k]; e < B_.p[k + 1]; ++e) Ls(w.position(B_.i[e]), k - L_.super[s]) = B_.x[e];
    }
  }

  /// Step 2 for every supernode pending in lists[s].
  void apply_pending_updates(int s, Lists& lists, Lists& to, Workspace& w) {
    int d = lists(s);
    lists(s) = -1;
    while (d >= 0) {
      const int after = next_(d);
      subtract_update(d, s, w);
      link_to_next_row(d, position_(d), to);
      d = after;
    }
  }

  /// L_s -= L_d[R_d >= k1] L_d[k1 <= R_d < k2]^T, scattered by rows; d's position moves past k2.
  void subtract_update(int d, int s, Workspace& w) {
    const int k1 = L_.super[s], k2 = L_.super[s + 1], nd = rows_of(d);
    const int* rows = L_.rows + L_.pi[d];
    const int p1 = position_(d);
    int p2 = p1;
    while (p2 < nd && rows[p2] < k2) ++p2;
    const int n1 = p2 - p1, n2 = nd - p1;
    const ConstBlock Ld(x_ + L_.px[d], nd, columns_of(d), Eigen::OuterStride<>(nd));
    w.update.resize(n2, n1);
    const auto top = Ld.middleRows(p1, n1);
    w.update.topRows(n1).triangularView<Eigen::Lower>() = top * top.transpose();
    w.update.bottomRows(n2 - n1).noalias() = Ld.middleRows(p2, n2 - n1) * top.transpose();
    Block Ls = block(s);
    for (int j = 0; j < n1; ++j) {
      auto column = Ls.col(rows[p1 + j] - k1);
      for (int i = j; i < n2; ++i) column(w.position(rows[p1 + i])) -= w.update(i, j);
    }
    position_(d) = p2;
  }

  /// Step 3: L_11 = chol(top square), L_21 = L_21 L_11^-T. False if the square is not positive definite.
  bool factorize_block(int s) const {
    Block Ls = block(s);
    const int nc = columns_of(s);
    auto square = Ls.topRows(nc);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>> llt(square);
    if (llt.info() != Eigen::Success) return false;
    if (rows_of(s) > nc) {
      square.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(Ls.bottomRows(rows_of(s) - nc));
    }
    return true;
  }

  /// Puts d (whose rows before `at` are done) in the list of the supernode holding its row `at`, if any.
  void link_to_next_row(int d, int at, Lists& to) {
    position_(d) = at;
    if (at >= rows_of(d)) return;
    const int target = supernode_of_(L_.rows[L_.pi[d] + at]);
    next_(d) = to(target);
    to(target) = d;
  }

  const LowerColumns& B_;
  const SupernodalStructure& L_;
  double* x_;
  Eigen::VectorXi supernode_of_, next_, position_;
};

}  // namespace

int factorize_numeric(const LowerColumns& B, const SupernodalStructure& L, double* x, SupernodeOrder group0,
                      SupernodeOrder group1, SupernodeOrder top) {
  Factorization f(B, L, x);
  Lists lists[3] = {Lists::Constant(L.count, -1), Lists::Constant(L.count, -1), Lists::Constant(L.count, -1)};
  Lists* const all[3] = {&lists[0], &lists[1], &lists[2]};
  const SupernodeOrder groups[2] = {group0, group1};
  Workspace work[2];
  int failed[2] = {-1, -1};
  const int threads = omp_get_max_threads() < 2 ? 1 : 2;
#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (int g = 0; g < 2; ++g) failed[g] = f.run(groups[g], &all[g], 1, lists[g], work[g]);
  if (failed[0] >= 0) return failed[0];
  if (failed[1] >= 0) return failed[1];
  return f.run(top, all, 3, lists[2], work[0]);
}

}  // namespace liftmap::LIFTMAP_KERNELS
