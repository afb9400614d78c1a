#include "flatten/sparse_cholesky.h"

#include <omp.h>

#include <cholmod.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/errors.h"
#include "flatten/supernodal_factorization.h"

namespace liftmap {

/// A split of the supernodal elimination tree between two threads (find_split).
struct TreeSplit {
  bool split = false;                      ///< false: one thread, all supernodes in order
  std::array<std::vector<int>, 2> groups;  ///< supernodes of each thread's subtrees, ascending
  std::vector<int> top;                    ///< the supernodes above both groups, ascending
  std::array<double, 3> fractions{};       ///< the weight in group 0, group 1 and the top
};

/// How solve() shares the supernodes between two threads (plan_solve): its split and where the groups' forward
/// updates of the top's rows go.
struct SolvePlan {
  TreeSplit tree;
  std::vector<int> own_rows;     ///< per supernode of a group: its off-diagonal rows outside the top
  std::vector<int> top_slot;     ///< per column: its index among the top's columns, or -1
  std::vector<int> top_columns;  ///< the top's columns, by slot
};

// Supernodal LL^T of P A P': CHOLMOD's fill-reducing ordering and symbolic factorisation (supernodes, their rows,
// the factor's storage), our numeric factorisation (supernodal_factorization.h, on two threads) and triangular
// solves. One gather of A's values into the lower triangle of P A P', whose pattern and source indices are built
// once in analyze(), gives the factorisation its input.
struct SparseCholesky::Impl {
  cholmod_common cm{};
  cholmod_factor* L = nullptr;        // factor of P A P' (natural ordering)
  SupernodalStructure structure;      // L's supernodes, rows and value offsets
  cholmod_sparse* B = nullptr;        // lower triangle of P A P', the matrix factorised
  std::vector<int> perm;              // row i of P A P' is row perm[i] of A
  std::vector<int> source;            // B's k-th value is A's source[k]-th value
  std::vector<int> a_outer, a_inner;  // the pattern of A given to analyze()
  SolvePlan plan;                     // how solve() splits the supernodes between two threads
  SupernodeSchedule schedule;         // how factorize() splits them
  DenseKernels kernels = DenseKernels::kAuto;
  Eigen::Index n = 0;
  bool analyzed = false;

  Impl() {
    cholmod_start(&cm);
    // CHOLMOD's own warnings would only flood stdout; failures are reported by exceptions.
    cm.print = 0;
    cm.supernodal = CHOLMOD_SUPERNODAL;  // a supernodal symbolic factor: the numeric factorisation's structure
    // CHOLMOD's default supernode relaxation (nrelax 4/16/48, zrelax 0.8/0.1/0.05), measured with CHOLMOD's own
    // numeric factorisation: coarser or finer supernodes were not faster (docs/performance.md).
  }
  ~Impl() {
    if (L != nullptr) cholmod_free_factor(&L, &cm);
    if (B != nullptr) cholmod_free_sparse(&B, &cm);
    cholmod_finish(&cm);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  Impl(Impl&&) = delete;
  Impl& operator=(Impl&&) = delete;
};

namespace {

/// Systems with at least this many unknowns are ordered by nested dissection (METIS), smaller ones by AMD.
constexpr Eigen::Index kNestedDissectionUnknowns = 20000;

/// Systems with fewer unknowns are solved on one thread (and their callers' sums over faces stay on one):
/// about the size where the flattening's per-face loops go parallel (subproblem::kParallelFaces, 4000 faces).
constexpr Eigen::Index kParallelSolveUnknowns = 8000;

/// A CHOLMOD view (no copy) of the lower triangle of A.
cholmod_sparse lower_view(const Eigen::SparseMatrix<double>& A) {
  cholmod_sparse v{};
  v.nrow = static_cast<size_t>(A.rows());
  v.ncol = static_cast<size_t>(A.cols());
  v.nzmax = static_cast<size_t>(A.nonZeros());
  v.p = const_cast<int*>(A.outerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast): CHOLMOD's C API
  v.i = const_cast<int*>(A.innerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  v.x = const_cast<double*>(A.valuePtr());    // NOLINT(cppcoreguidelines-pro-type-const-cast)
  v.stype = -1;
  v.itype = CHOLMOD_INT;
  v.xtype = CHOLMOD_REAL;
  v.dtype = CHOLMOD_DOUBLE;
  v.sorted = 1;
  v.packed = 1;
  return v;
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The supernodal structure of CHOLMOD's factor L (views of its arrays).
SupernodalStructure structure_of(const cholmod_factor& L) {
  return {.super = static_cast<const int*>(L.super),
          .pi = static_cast<const int*>(L.pi),
          .px = static_cast<const int*>(L.px),
          .rows = static_cast<const int*>(L.s),
          .count = static_cast<int>(L.nsuper),
          .n = static_cast<int>(L.n)};
}

// The triangular solves: per supernode, the dense triangle, then the rectangle below it as one dense product into
// a small buffer and one scattered update per row (forward), or one gather per row and dense dot products
// (backward). CHOLMOD's own supernodal solve calls BLAS twice per supernode and direction, which for the few
// right-hand sides of a Newton step costs more in call and buffer overhead than in arithmetic (camel-cow: 12 ms
// per solve of 3 columns against 25 ms per factorisation). Y is row-major with K columns.

/// Forward step of supernode s (L Z = Y), K right-hand sides. The first `own` off-diagonal rows are updated in y;
/// the others (columns of the top of the tree, when two threads share the solve) in the private `top` block, at
/// their top_slot.
template <int K>
void forward_supernode(const SupernodalStructure& L, const double* x, int s, double* y, double* w, int own, double* top,
                       const int* top_slot) {
  const int k1 = L.super[s], nscol = L.columns(s), nsrow = L.rows_of(s), m = nsrow - nscol;
  const double* ls = x + L.px[s];
  double* y1 = y + static_cast<ptrdiff_t>(k1) * K;
  for (int j = 0; j < nscol; ++j) {
    const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow;
    for (int c = 0; c < K; ++c) y1[j * K + c] /= col[j];
    for (int i = j + 1; i < nscol; ++i) {
      for (int c = 0; c < K; ++c) y1[i * K + c] -= col[i] * y1[j * K + c];
    }
  }
  if (m == 0) return;
  std::fill(w, w + static_cast<ptrdiff_t>(m) * K, 0.0);
  for (int j = 0; j < nscol; ++j) {
    const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow + nscol;
    for (int i = 0; i < m; ++i) {
      for (int c = 0; c < K; ++c) w[i * K + c] += col[i] * y1[j * K + c];
    }
  }
  const int* r = L.rows + L.pi[s] + nscol;
  for (int i = 0; i < own; ++i) {
    double* yi = y + static_cast<ptrdiff_t>(r[i]) * K;
    for (int c = 0; c < K; ++c) yi[c] -= w[i * K + c];
  }
  for (int i = own; i < m; ++i) {
    double* yi = top + static_cast<ptrdiff_t>(top_slot[r[i]]) * K;
    for (int c = 0; c < K; ++c) yi[c] -= w[i * K + c];
  }
}

/// Backward step of supernode s (L^T X = Z): reads the solution at its off-diagonal rows, which belong to later
/// supernodes (its ancestors), and writes its own columns.
template <int K>
void backward_supernode(const SupernodalStructure& L, const double* x, int s, double* y, double* w) {
  const int k1 = L.super[s], nscol = L.columns(s), nsrow = L.rows_of(s), m = nsrow - nscol;
  const double* ls = x + L.px[s];
  double* y1 = y + static_cast<ptrdiff_t>(k1) * K;
  if (m > 0) {
    const int* r = L.rows + L.pi[s] + nscol;
    for (int i = 0; i < m; ++i) {
      const double* yi = y + static_cast<ptrdiff_t>(r[i]) * K;
      for (int c = 0; c < K; ++c) w[i * K + c] = yi[c];
    }
    for (int j = 0; j < nscol; ++j) {
      const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow + nscol;
      std::array<double, K> acc{};
      for (int i = 0; i < m; ++i) {
        for (int c = 0; c < K; ++c) acc[static_cast<size_t>(c)] += col[i] * w[i * K + c];
      }
      for (int c = 0; c < K; ++c) y1[j * K + c] -= acc[static_cast<size_t>(c)];
    }
  }
  for (int j = nscol - 1; j >= 0; --j) {
    const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow;
    for (int i = j + 1; i < nscol; ++i) {
      for (int c = 0; c < K; ++c) y1[j * K + c] -= col[i] * y1[i * K + c];
    }
    for (int c = 0; c < K; ++c) y1[j * K + c] /= col[j];
  }
}

/// Solves L L^T Y = Y in place, K right-hand sides (row-major Y). With a split plan the two groups of independent
/// subtrees go to two threads (forward: each keeps its updates of the top's rows in a block of its own, added in
/// afterwards), the top in between on one.
template <int K>
void supernodal_solve(const cholmod_factor& factor, const SupernodalStructure& L, const SolvePlan& plan, double* y) {
  const auto* x = static_cast<const double*>(factor.x);
  const size_t wsize = factor.maxesize * K;
  if (!plan.tree.split) {
    std::vector<double> w(wsize);
    for (int s = 0; s < L.count; ++s)
      forward_supernode<K>(L, x, s, y, w.data(), L.rows_of(s) - L.columns(s), nullptr, nullptr);
    for (int s = L.count - 1; s >= 0; --s) backward_supernode<K>(L, x, s, y, w.data());
    return;
  }
  const auto n_top = static_cast<ptrdiff_t>(plan.top_columns.size());
  std::array<std::vector<double>, 2> top;
#pragma omp parallel for num_threads(std::min(2, omp_get_max_threads())) schedule(static, 1)
  for (int g = 0; g < 2; ++g) {
    std::vector<double> w(wsize);
    auto& mine = top[static_cast<size_t>(g)];
    mine.assign(static_cast<size_t>(n_top * K), 0.0);
    for (const int s : plan.tree.groups[static_cast<size_t>(g)]) {
      forward_supernode<K>(L, x, s, y, w.data(), plan.own_rows[static_cast<size_t>(s)], mine.data(),
                           plan.top_slot.data());
    }
  }
  for (ptrdiff_t k = 0; k < n_top; ++k) {
    double* yk = y + static_cast<ptrdiff_t>(plan.top_columns[static_cast<size_t>(k)]) * K;
    for (int c = 0; c < K; ++c)
      yk[c] += top[0][static_cast<size_t>(k * K + c)] + top[1][static_cast<size_t>(k * K + c)];
  }
  std::vector<double> w(wsize);
  for (const int s : plan.tree.top)
    forward_supernode<K>(L, x, s, y, w.data(), L.rows_of(s) - L.columns(s), nullptr, nullptr);
  for (auto it = plan.tree.top.rbegin(); it != plan.tree.top.rend(); ++it)
    backward_supernode<K>(L, x, *it, y, w.data());
#pragma omp parallel for num_threads(std::min(2, omp_get_max_threads())) schedule(static, 1)
  for (int g = 0; g < 2; ++g) {
    std::vector<double> wg(wsize);
    const auto& group = plan.tree.groups[static_cast<size_t>(g)];
    for (auto it = group.rbegin(); it != group.rend(); ++it) backward_supernode<K>(L, x, *it, y, wg.data());
  }
}

/// supernodal_solve on k <= 3 columns, row-major.
void supernodal_solve(const cholmod_factor& factor, const SupernodalStructure& L, const SolvePlan& plan, Eigen::Index k,
                      double* y) {
  if (k == 3) supernodal_solve<3>(factor, L, plan, y);
  if (k == 2) supernodal_solve<2>(factor, L, plan, y);
  if (k == 1) supernodal_solve<1>(factor, L, plan, y);
}

/// Splits the supernodal elimination tree in two: the top (the supernodes whose subtrees are too heavy to give to
/// one thread, from the roots down) and below it two groups of whole subtrees of about equal weight (`cost`: per
/// supernode). A group's supernodes have their off-diagonal rows in their own group first, then in the top, never
/// in the other group. No split (split false) if the top would carry more than `max_top` of the whole weight or
/// the groups stay more unequal than 60:40, or below kParallelSolveUnknowns.
TreeSplit find_split(const SupernodalStructure& L, const std::vector<double>& cost, double max_top) {
  const int ns = L.count;
  if (ns < 2 || L.n < kParallelSolveUnknowns) return {};
  std::vector<int> supernode_of(static_cast<size_t>(L.n));
  for (int s = 0; s < ns; ++s)
    std::fill(&supernode_of[static_cast<size_t>(L.super[s])],
              &supernode_of[static_cast<size_t>(L.super[s + 1] - 1)] + 1, s);
  std::vector<int> first(static_cast<size_t>(ns));
  std::vector<double> weight(static_cast<size_t>(ns));  // cost of the subtree
  std::vector<std::vector<int>> children(static_cast<size_t>(ns));
  std::vector<int> frontier;
  std::iota(first.begin(), first.end(), 0);  // the first supernode of each subtree (postorder: contiguous)
  for (int s = 0; s < ns; ++s) {
    const auto us = static_cast<size_t>(s);
    weight[us] += cost[us];
    if (L.rows_of(s) > L.columns(s)) {
      const int p = supernode_of[static_cast<size_t>(L.rows[L.pi[s] + L.columns(s)])];
      if (p <= s) return {};  // not postordered: no split
      weight[static_cast<size_t>(p)] += weight[us];
      first[static_cast<size_t>(p)] = std::min(first[static_cast<size_t>(p)], first[us]);
      children[static_cast<size_t>(p)].push_back(s);
    } else {
      frontier.push_back(s);
    }
  }
  double total = 0;
  for (const int r : frontier) total += weight[static_cast<size_t>(r)];
  std::vector<char> is_top(static_cast<size_t>(ns), 0);
  double top_weight = 0;
  std::array<std::vector<int>, 2> bins;
  for (;;) {
    // Heaviest subtrees first, each into the lighter bin.
    std::sort(frontier.begin(), frontier.end(),
              [&](int a, int b) { return weight[static_cast<size_t>(a)] > weight[static_cast<size_t>(b)]; });
    std::array<double, 2> load{0, 0};
    bins = {};
    for (const int f : frontier) {
      const size_t b = load[0] <= load[1] ? 0 : 1;
      load[b] += weight[static_cast<size_t>(f)];
      bins[b].push_back(f);
    }
    if (!bins[1].empty() && std::max(load[0], load[1]) <= 0.6 * (load[0] + load[1])) break;
    // Too unequal: the heaviest subtree's root joins the top, its children the frontier.
    const int h = frontier.front();
    const auto uh = static_cast<size_t>(h);
    if (children[uh].empty()) return {};
    top_weight += cost[uh];
    if (top_weight > max_top * total) return {};
    is_top[uh] = 1;
    frontier.erase(frontier.begin());
    frontier.insert(frontier.end(), children[uh].begin(), children[uh].end());
  }
  constexpr int kTop = 2;
  std::vector<int> part(static_cast<size_t>(ns), -1);  // 0, 1 or kTop
  for (size_t b = 0; b < 2; ++b) {
    for (const int f : bins[b]) {
      std::fill(&part[static_cast<size_t>(first[static_cast<size_t>(f)])], &part[static_cast<size_t>(f)] + 1,
                static_cast<int>(b));
    }
  }
  TreeSplit split;
  for (int s = 0; s < ns; ++s) {
    const auto us = static_cast<size_t>(s);
    if (part[us] < 0) {
      if (!is_top[us]) return {};  // neither in a group nor above them: not a tree, no split
      part[us] = kTop;
    }
    (part[us] == kTop ? split.top : split.groups[static_cast<size_t>(part[us])]).push_back(s);
  }
  // A subtree's off-diagonal rows are its ancestors: first those inside the subtree, then (higher) the top's.
  for (int b = 0; b < 2; ++b) {
    for (const int s : split.groups[static_cast<size_t>(b)]) {
      const int* r = L.rows + L.pi[s] + L.columns(s);
      const int m = L.rows_of(s) - L.columns(s);
      int i = 0;
      while (i < m && part[static_cast<size_t>(supernode_of[static_cast<size_t>(r[i])])] == b) ++i;
      while (i < m && part[static_cast<size_t>(supernode_of[static_cast<size_t>(r[i])])] == kTop) ++i;
      if (i < m) return {};
    }
  }
  split.split = true;
  split.fractions = {0, 0, top_weight / total};
  for (size_t b = 0; b < 2; ++b) {
    for (const int f : bins[b]) split.fractions[b] += weight[static_cast<size_t>(f)] / total;
  }
  return split;
}

/// The plan of solve(): groups of equal numbers of stored values (the solve reads each once per direction and is
/// bound by memory bandwidth), the top at most a fifth of them; each group supernode's rows outside the top, and
/// the top's columns numbered for the groups' private blocks of top updates.
SolvePlan plan_solve(const SupernodalStructure& L) {
  std::vector<double> values(static_cast<size_t>(L.count));
  for (int s = 0; s < L.count; ++s) values[static_cast<size_t>(s)] = static_cast<double>(L.rows_of(s)) * L.columns(s);
  SolvePlan plan{.tree = find_split(L, values, 0.2), .own_rows = {}, .top_slot = {}, .top_columns = {}};
  if (!plan.tree.split) return plan;
  plan.top_slot.assign(static_cast<size_t>(L.n), -1);
  for (const int s : plan.tree.top) {
    for (int k = L.super[s]; k < L.super[s + 1]; ++k) {
      plan.top_slot[static_cast<size_t>(k)] = static_cast<int>(plan.top_columns.size());
      plan.top_columns.push_back(k);
    }
  }
  plan.own_rows.assign(static_cast<size_t>(L.count), 0);
  for (const auto& group : plan.tree.groups) {
    for (const int s : group) {
      const int* r = L.rows + L.pi[s] + L.columns(s);
      const int m = L.rows_of(s) - L.columns(s);
      int own = 0;
      while (own < m && plan.top_slot[static_cast<size_t>(r[own])] < 0) ++own;
      plan.own_rows[static_cast<size_t>(s)] = own;
    }
  }
  return plan;
}

/// The schedule of factorize(): groups of equal flops (a supernode's column j updates the rows below it, about
/// (rows - j)^2 multiply-adds), the top (the dense separators, which hold a larger share of the flops than of the
/// values) at most half of them; no split: every supernode in order.
SupernodeSchedule plan_factorization(const SupernodalStructure& L) {
  std::vector<double> flops(static_cast<size_t>(L.count));
  for (int s = 0; s < L.count; ++s) {
    for (int j = 0; j < L.columns(s); ++j) flops[static_cast<size_t>(s)] += std::pow(L.rows_of(s) - j, 2.0);
  }
  TreeSplit split = find_split(L, flops, 0.5);
  SupernodeSchedule schedule;
  if (split.split) {
    schedule.groups = std::move(split.groups);
    schedule.top = std::move(split.top);
  } else {
    schedule.top.resize(static_cast<size_t>(L.count));
    std::iota(schedule.top.begin(), schedule.top.end(), 0);
  }
  return schedule;
}

}  // namespace

SparseCholesky::SparseCholesky(DenseKernels kernels) : impl_(std::make_unique<Impl>()) {
  require_dense_kernels(kernels);
  impl_->kernels = kernels;
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() != A.cols() || !A.isCompressed())
    throw PipelineError("sparse Cholesky: A must be square and compressed");
  Impl& m = *impl_;
  if (m.L != nullptr) cholmod_free_factor(&m.L, &m.cm);
  if (m.B != nullptr) cholmod_free_sparse(&m.B, &m.cm);
  m.analyzed = false;
  m.n = A.rows();
  m.a_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
  m.a_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  // The fill-reducing ordering, postordered: METIS's nested dissection for large systems, else CHOLMOD's default
  // (AMD). CHOLMOD's default keeps AMD on the flattening systems, whose fill it finds acceptable, but nested
  // dissection needs fewer flops on these 2D-mesh graphs: camel-cow (46k unknowns) 1.33e8 against 1.54e8 per
  // factorisation, fandisk-bunny (105k) 5.97e8 against 8.09e8, for 0.16-0.35 s more analysis, once per
  // flattening. Measured side by side (profile_flatten, fandisk-bunny, 2 outer iterations, 81 factorisations):
  // 4.71-5.04 s of factorisation against 5.24-5.38 s with AMD, but the flattening as a whole equal within the
  // noise (14.6-15.3 s against 14.9-15.1 s); camel-cow equal (7.09-7.23 s against 7.12-7.32 s for 3 outer
  // iterations). On small systems the analysis would cost more than the factorisations save.
  cholmod_sparse view = lower_view(A);
  const bool nested_dissection = m.n >= kNestedDissectionUnknowns;
  if (nested_dissection) {
    m.cm.nmethods = 1;
    m.cm.method[0].ordering = CHOLMOD_METIS;
  }
  cholmod_factor* L0 = cholmod_analyze(&view, &m.cm);
  m.cm.nmethods = 0;  // CHOLMOD's defaults again
  m.cm.method[0].ordering = CHOLMOD_GIVEN;
  if (nested_dissection && (L0 == nullptr || m.cm.status < CHOLMOD_OK)) {  // a CHOLMOD built without METIS
    if (L0 != nullptr) cholmod_free_factor(&L0, &m.cm);
    L0 = cholmod_analyze(&view, &m.cm);
  }
  if (L0 == nullptr || m.cm.status < CHOLMOD_OK) throw PipelineError("sparse Cholesky: symbolic analysis failed");
  const auto* p0 = static_cast<const int*>(L0->Perm);
  m.perm.assign(p0, p0 + m.n);
  cholmod_free_factor(&L0, &m.cm);
  std::vector<int> inverse(static_cast<size_t>(m.n));
  for (Eigen::Index i = 0; i < m.n; ++i)
    inverse[static_cast<size_t>(m.perm[static_cast<size_t>(i)])] = static_cast<int>(i);

  // The lower triangle of P A P' in compressed columns, each value remembering where it comes from in A.
  struct Entry {
    int col, row, src;
  };
  std::vector<Entry> entries;
  entries.reserve(m.a_inner.size());
  for (int c = 0; c < A.cols(); ++c) {
    for (int k = A.outerIndexPtr()[c]; k < A.outerIndexPtr()[c + 1]; ++k) {
      const int r = A.innerIndexPtr()[k];
      if (r < c) continue;  // only the lower triangle is read
      const int pr = inverse[static_cast<size_t>(r)], pc = inverse[static_cast<size_t>(c)];
      entries.push_back({std::min(pr, pc), std::max(pr, pc), k});
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.col != b.col ? a.col < b.col : a.row < b.row; });
  m.B = cholmod_allocate_sparse(static_cast<size_t>(m.n), static_cast<size_t>(m.n), entries.size(), 1, 1, -1,
                                CHOLMOD_REAL, &m.cm);
  if (m.B == nullptr) throw PipelineError("sparse Cholesky: out of memory");
  auto* bp = static_cast<int*>(m.B->p);
  auto* bi = static_cast<int*>(m.B->i);
  m.source.resize(entries.size());
  std::fill(bp, bp + m.n + 1, 0);
  for (size_t e = 0; e < entries.size(); ++e) {
    ++bp[entries[e].col + 1];
    bi[e] = entries[e].row;
    m.source[e] = entries[e].src;
  }
  for (Eigen::Index c = 0; c < m.n; ++c) bp[c + 1] += bp[c];

  // Symbolic factorisation of P A P' as it stands: natural ordering, no postordering (P is already postordered).
  m.cm.nmethods = 1;
  m.cm.method[0].ordering = CHOLMOD_NATURAL;
  m.cm.postorder = 0;
  m.L = cholmod_analyze(m.B, &m.cm);
  m.cm.nmethods = 0;
  m.cm.method[0].ordering = CHOLMOD_GIVEN;
  m.cm.postorder = 1;
  if (m.L == nullptr || m.cm.status < CHOLMOD_OK || m.L->ordering != CHOLMOD_NATURAL) {
    throw PipelineError("sparse Cholesky: symbolic analysis failed");
  }
  // The numeric factor's storage (supernodal LL'), filled by factorize(); minor < n until a factorisation succeeds.
  if (!cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, m.L, &m.cm) || m.L->xtype != CHOLMOD_REAL) {
    throw PipelineError("sparse Cholesky: out of memory");
  }
  m.structure = structure_of(*m.L);
  m.plan = plan_solve(m.structure);
  m.schedule = plan_factorization(m.structure);
  m.L->minor = 0;
  m.analyzed = true;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!impl_->analyzed) analyze(A);
  Impl& m = *impl_;
  // The whole pattern, not only its size: a matrix of the same size and entry count but other entries would be
  // factorised silently wrong. 0.44 ms per factorisation at 735k entries (fandisk-bunny), under 1% of one.
  if (!has_pattern_of(A)) throw PipelineError("sparse Cholesky: the matrix does not have the analysed pattern");
  auto* bx = static_cast<double*>(m.B->x);
  const double* ax = A.valuePtr();
  const auto nb = static_cast<Eigen::Index>(m.source.size());
#pragma omp parallel for schedule(static) if (nb > 100000)
  for (Eigen::Index e = 0; e < nb; ++e) bx[e] = ax[m.source[static_cast<size_t>(e)]];
  const LowerColumns b{.p = static_cast<const int*>(m.B->p), .i = static_cast<const int*>(m.B->i), .x = bx};
  const int failed = factorize_supernodal(b, m.structure, static_cast<double*>(m.L->x), m.schedule, m.kernels);
  m.L->minor = failed < 0 ? m.L->n : static_cast<size_t>(failed);
  return failed < 0;
}

bool SparseCholesky::has_pattern_of(const Eigen::SparseMatrix<double>& A) const {
  const Impl& m = *impl_;
  return m.analyzed && A.isCompressed() && A.rows() == m.n && A.cols() == m.n &&
         static_cast<size_t>(A.nonZeros()) == m.a_inner.size() &&
         std::equal(m.a_outer.begin(), m.a_outer.end(), A.outerIndexPtr()) &&
         std::equal(m.a_inner.begin(), m.a_inner.end(), A.innerIndexPtr());
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  const Impl& m = *impl_;
  if (!m.analyzed || m.L->xtype == CHOLMOD_PATTERN || m.L->minor != m.L->n || !m.L->is_super || B.rows() != m.n) {
    throw PipelineError("sparse Cholesky: solve failed (no factorisation of this size)");
  }
  // Three columns at a time, permuted into a row-major block (one row per unknown: the solve's scattered
  // accesses touch one cache line per row), and permuted back.
  Eigen::MatrixXd X(m.n, B.cols());
  RowMajor Y;
  for (Eigen::Index c0 = 0; c0 < B.cols(); c0 += 3) {
    const Eigen::Index k = std::min<Eigen::Index>(3, B.cols() - c0);
    Y.resize(m.n, k);
    for (Eigen::Index i = 0; i < m.n; ++i) Y.row(i) = B.block(m.perm[static_cast<size_t>(i)], c0, 1, k);
    supernodal_solve(*m.L, m.structure, m.plan, k, Y.data());
    for (Eigen::Index i = 0; i < m.n; ++i) X.block(m.perm[static_cast<size_t>(i)], c0, 1, k) = Y.row(i);
  }
  return X;
}

bool SparseCholesky::analyzed() const { return impl_->analyzed; }

std::vector<int> SparseCholesky::unknown_halves() const {
  const Impl& m = *impl_;
  if (!m.plan.tree.split) return {};
  const SupernodalStructure& L = m.structure;
  std::vector<int> halves(static_cast<size_t>(m.n), -1);  // the top's unknowns stay -1
  for (int h = 0; h < 2; ++h) {
    for (const int s : m.plan.tree.groups[static_cast<size_t>(h)]) {
      for (int k = L.super[s]; k < L.super[s + 1]; ++k) halves[static_cast<size_t>(m.perm[static_cast<size_t>(k)])] = h;
    }
  }
  return halves;
}

SparseCholesky::SolveSplit SparseCholesky::solve_split() const {
  const TreeSplit& t = impl_->plan.tree;
  return {t.split, t.fractions[0], t.fractions[1], t.fractions[2]};
}

}  // namespace liftmap
