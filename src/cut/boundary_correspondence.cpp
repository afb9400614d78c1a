#include "cut/boundary_correspondence.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/errors.h"
#include "cut/edge_key.h"

namespace liftmap {

double cubic_reparameterisation(double s, double l, double L) {
  const double x = s / l;
  return s + (L - l) * (3.0 * x * x - 2.0 * x * x * x);
}

double inverse_cubic_reparameterisation(double y, double l, double L) {
  double lo = 0.0, hi = l;
  for (int i = 0; i < 100 && hi - lo > 1e-15 * l; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cubic_reparameterisation(mid, l, L) < y ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

/// The square root of the surface area of a refined mesh: the unit in which both sides' arc lengths are compared.
double length_unit(const RefinedMesh& r) {
  double area = 0;
  for (const auto& f : r.faces) {
    const Eigen::Vector3d& p0 = r.positions[static_cast<size_t>(f[0])];
    area +=
        0.5 * (r.positions[static_cast<size_t>(f[1])] - p0).cross(r.positions[static_cast<size_t>(f[2])] - p0).norm();
  }
  return std::sqrt(area);
}

/// Arc lengths of the path's vertices from its first, in units of `unit`.
std::vector<double> arc_lengths(const RefinedMesh& r, const std::vector<int>& path, double unit) {
  std::vector<double> s{0.0};
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    s.push_back(s.back() +
                (r.positions[static_cast<size_t>(path[i + 1])] - r.positions[static_cast<size_t>(path[i])]).norm() /
                    unit);
  }
  return s;
}

/// Points to insert into one path: per path edge i, the sorted parameters t in (0, 1).
using Insertions = std::vector<std::vector<double>>;

/// Adds the point at arc length `s` to the insertions of a path with arc lengths `arc`.
void insert_at(const std::vector<double>& arc, double s, Insertions& ins) {
  const auto it = std::upper_bound(arc.begin(), arc.end(), s);
  size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(it - arc.begin() - 1, 0));
  i = std::min(i, arc.size() - 2);
  const double len = arc[i + 1] - arc[i];
  ins[i].push_back(len > 0 ? (s - arc[i]) / len : 0.5);
}

/// Applies insertions to one mesh: new vertex ids follow `split_refined_mesh`'s numbering; points too close to
/// each other or to an edge end are spread evenly over their edge (keeping their order).
void apply(RefinedMesh& r, const Mesh& input, std::vector<std::vector<int>>& paths, std::vector<Insertions>& ins) {
  std::vector<EdgeSplit> splits;
  const int n_old = r.n_vertices();
  for (size_t e = 0; e < paths.size(); ++e) {
    std::vector<int> out{paths[e][0]};
    for (size_t i = 0; i + 1 < paths[e].size(); ++i) {
      auto& ts = ins[e][i];
      std::sort(ts.begin(), ts.end());
      const double gap = std::min(0.1, 0.5 / static_cast<double>(ts.size() + 1));
      bool even = false;
      for (size_t j = 0; j <= ts.size(); ++j) {
        const double lo = j == 0 ? 0.0 : ts[j - 1];
        const double hi = j == ts.size() ? 1.0 : ts[j];
        if (hi - lo < gap) even = true;
      }
      for (size_t j = 0; j < ts.size(); ++j) {
        const double t = even ? static_cast<double>(j + 1) / static_cast<double>(ts.size() + 1) : ts[j];
        out.push_back(n_old + static_cast<int>(splits.size()));
        splits.push_back({paths[e][i], paths[e][i + 1], t});
      }
      out.push_back(paths[e][i + 1]);
    }
    paths[e] = std::move(out);
  }
  // Several points on one edge: split_refined_mesh takes t along (a, b) for each, all on the original edge.
  split_refined_mesh(r, input, splits);
}

}  // namespace

void equalize_paths(RefinedMesh& a, const Mesh& input_a, std::vector<std::vector<int>>& paths_a, RefinedMesh& b,
                    const Mesh& input_b, std::vector<std::vector<int>>& paths_b, double snap) {
  std::vector<Insertions> ins_a(paths_a.size()), ins_b(paths_b.size());
  const double unit_a = length_unit(a), unit_b = length_unit(b);
  for (size_t e = 0; e < paths_a.size(); ++e) {
    const auto sa = arc_lengths(a, paths_a[e], unit_a);
    const auto sb = arc_lengths(b, paths_b[e], unit_b);
    ins_a[e].resize(sa.size() - 1);
    ins_b[e].resize(sb.size() - 1);
    const double la = sa.back(), lb = sb.back();
    // phi: arc length on A -> arc length on B, and its inverse.
    const auto phi = [&](double s) {
      return la <= lb ? cubic_reparameterisation(s, la, lb) : inverse_cubic_reparameterisation(s, lb, la);
    };
    const auto phi_inv = [&](double s) {
      return la <= lb ? inverse_cubic_reparameterisation(s, la, lb) : cubic_reparameterisation(s, lb, la);
    };
    // Interior vertices of both paths, in B's arc length, with a snapping tolerance each.
    struct Item {
      double s_b;
      int side;  // 0: vertex of A, 1: vertex of B
      size_t index;
      double tol;
    };
    std::vector<Item> items;
    for (size_t i = 1; i + 1 < sa.size(); ++i) {
      const double local = std::min(sa[i] - sa[i - 1], sa[i + 1] - sa[i]);
      items.push_back({phi(sa[i]), 0, i, snap * local});
    }
    for (size_t j = 1; j + 1 < sb.size(); ++j) {
      const double local = std::min(sb[j] - sb[j - 1], sb[j + 1] - sb[j]);
      items.push_back({sb[j], 1, j, snap * local});
    }
    std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.s_b < y.s_b; });
    for (size_t i = 0; i < items.size(); ++i) {
      if (i + 1 < items.size() && items[i].side != items[i + 1].side &&
          items[i + 1].s_b - items[i].s_b < std::min(items[i].tol, items[i + 1].tol)) {
        ++i;  // an A vertex and a B vertex close enough to correspond without insertion
        continue;
      }
      if (items[i].side == 0) {
        insert_at(sb, items[i].s_b, ins_b[e]);
      } else {
        insert_at(sa, phi_inv(items[i].s_b), ins_a[e]);
      }
    }
  }
  apply(a, input_a, paths_a, ins_a);
  apply(b, input_b, paths_b, ins_b);
}

namespace {

/// A boundary loop split into sides between consecutive landmark copies.
struct Loop {
  std::vector<int> vertices;                   ///< cut vertices, counter-clockwise
  std::vector<size_t> side_start;              ///< positions of landmark copies in `vertices`
  std::vector<std::array<int, 2>> side_label;  ///< per side: {tree edge, landmark at its start}
};

Loop make_loop(const CutBoundaryInput& in, const char* name) {
  const Mesh& cut = *in.cut;
  const auto loops = cut.boundary_loops();
  if (loops.size() != 1 || cut.euler_characteristic() != 1) {
    throw PipelineError(std::string("cut: mesh ") + name + " is not a disk after cutting (" +
                        std::to_string(loops.size()) + " boundary loops, Euler characteristic " +
                        std::to_string(cut.euler_characteristic()) + ")");
  }
  Loop loop;
  for (const HalfedgeId h : loops[0]) loop.vertices.push_back(cut.head(h).idx);
  std::reverse(loop.vertices.begin(), loop.vertices.end());
  std::unordered_map<int, int> landmark_of;
  for (size_t i = 0; i < in.landmarks->size(); ++i) landmark_of[(*in.landmarks)[i]] = static_cast<int>(i);
  std::unordered_map<std::uint64_t, int> tree_edge;
  for (size_t e = 0; e < in.paths->size(); ++e) {
    const auto& p = (*in.paths)[e];
    for (size_t i = 0; i + 1 < p.size(); ++i) tree_edge[edge_key(p[i], p[i + 1])] = static_cast<int>(e);
  }
  const size_t n = loop.vertices.size();
  const auto refined = [&](size_t i) { return (*in.to_refined)(loop.vertices[i % n]); };
  for (size_t i = 0; i < n; ++i) {
    const auto it = landmark_of.find(refined(i));
    if (it == landmark_of.end()) continue;
    const auto te = tree_edge.find(edge_key(refined(i), refined(i + 1)));
    if (te == tree_edge.end())
      throw PipelineError(std::string("cut: boundary edge of mesh ") + name + " is on no cut path");
    loop.side_start.push_back(i);
    loop.side_label.push_back({te->second, it->second});
  }
  return loop;
}

}  // namespace

std::vector<std::array<int, 2>> match_boundaries(const CutBoundaryInput& a, const CutBoundaryInput& b) {
  const Loop la = make_loop(a, "A");
  const Loop lb = make_loop(b, "B");
  if (la.vertices.size() != lb.vertices.size() || la.side_start.size() != lb.side_start.size() ||
      la.side_start.empty()) {
    throw PipelineError("cut: the two boundaries have different vertex or side counts (" +
                        std::to_string(la.vertices.size()) + " and " + std::to_string(lb.vertices.size()) + ")");
  }
  const auto first = std::find(lb.side_label.begin(), lb.side_label.end(), la.side_label[0]);
  if (first == lb.side_label.end()) throw PipelineError("cut: boundary sides do not correspond");
  const size_t shift_side = static_cast<size_t>(first - lb.side_label.begin());
  const size_t n = la.vertices.size(), m = la.side_label.size();
  const size_t offset_a = la.side_start[0], offset_b = lb.side_start[shift_side];
  for (size_t s = 0; s < m; ++s) {
    const size_t sb = (s + shift_side) % m;
    if (la.side_label[s] != lb.side_label[sb] ||
        (la.side_start[s] + n - offset_a) % n != (lb.side_start[sb] + n - offset_b) % n) {
      throw PipelineError("cut: boundary side " + std::to_string(s) + " does not correspond between the meshes");
    }
  }
  std::vector<std::array<int, 2>> nu(n);
  for (size_t i = 0; i < n; ++i) {
    nu[i] = {la.vertices[(offset_a + i) % n], lb.vertices[(offset_b + i) % n]};
  }
  return nu;
}

}  // namespace liftmap
