#include "map/map_overlay.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/total_area.h"
#include "lift/disk_overlay.h"
#include "map/check_overlay.h"

namespace liftmap {

namespace {

/// An element of a cut disk named by the closed refined mesh's elements, so that the two copies of a cut-path
/// vertex or edge get one name: {kind, refined vertex or face, refined vertex or -1}.
std::array<int, 3> refined_key(const Mesh& disk, const Eigen::VectorXi& cut_to_refined, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::kVertex:
      return {0, cut_to_refined(p.vertex.idx), -1};
    case SurfacePoint::Kind::kEdge: {
      const HalfedgeId h = Mesh::halfedge(p.edge);
      const int a = cut_to_refined(disk.tail(h).idx), b = cut_to_refined(disk.head(h).idx);
      return {1, std::min(a, b), std::max(a, b)};
    }
    case SurfacePoint::Kind::kFace:
      return {2, p.face.idx, -1};
  }
  return {-1, -1, -1};
}

/// The position of p on a disk relative to the point o: rounding at the scale of the disk's size, not of its
/// distance from the origin.
Eigen::Vector3d relative_position(const Mesh& disk, const Eigen::MatrixXd& V, const SurfacePoint& p,
                                  const Eigen::Vector3d& o) {
  const SurfacePoint q = as_face_point(disk, p);
  const auto fv = disk.face_vertices(q.face);
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < 3; ++k) x += q.bary[k] * (V.row(fv[k].idx).transpose() - o);
  return x;
}

/// Distance in R^3 between the image of x under a one-way map (lift) and the point y of the target disk.
double image_distance(const Mesh& target, const Eigen::MatrixXd& V, const SurfacePoint& image, const SurfacePoint& y) {
  const Eigen::Vector3d o = V.row(target.face_vertices(as_face_point(target, y).face)[0].idx).transpose();
  return (relative_position(target, V, image, o) - relative_position(target, V, y, o)).norm();
}

/// Max over the disk overlay's vertices of |f(x_M) - x_N| / sqrt(area of N^) and |g(x_N) - x_M| / sqrt(area of M^).
double disk_agreement(const MapResult& map, const DiskOverlay& disk) {
  const double unit_a = std::sqrt(total_area(map.disk_va, map.cut.a.F_cut));
  const double unit_b = std::sqrt(total_area(map.disk_vb, map.cut.b.F_cut));
  const std::vector<SurfacePoint> f = map.bijection->evaluate_f(disk.on_m);
  const std::vector<SurfacePoint> g = map.bijection->evaluate_g(disk.on_n);
  double worst = 0;
  const auto n = static_cast<int>(disk.on_m.size());
#pragma omp parallel for schedule(static) reduction(max : worst)
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<size_t>(k);
    const double ef = image_distance(map.disk_b, map.disk_vb, f[i], disk.on_n[i]);
    const double eg = image_distance(map.disk_a, map.disk_va, g[i], disk.on_m[i]);
    worst = std::max({worst, ef / unit_b, eg / unit_a});
  }
  return worst;
}

/// Per face of a disk flattened to X: the fraction of its area below which the sign of a cell in it is rounding.
/// The cell's corners are points of the plane, rounded to eps |x| at most |x| <= R (the face's largest corner);
/// their barycentric coordinates in the face's flattened triangle then err by up to eps R / h, h its smallest
/// altitude, and so does the cell's area as a fraction of the face's (the cell is at most the face). The factor
/// 64 covers the few roundings of each corner (a crossing's parameter, the corner, its coordinates) and of the
/// area. Never below OverlayCheck::kRoundingArea, the rounding of the area on the input face itself; 1 for a
/// degenerate flattened face, where no sign is meaningful (verify_map reports the face).
Eigen::VectorXd sign_rounding(const Mesh& disk, const Eigen::MatrixXd& X) {
  Eigen::VectorXd rounding(disk.n_faces());
  for (int f = 0; f < disk.n_faces(); ++f) {
    const auto fv = disk.face_vertices(FaceId(f));
    const Eigen::Vector2d p0 = X.row(fv[0].idx).transpose(), p1 = X.row(fv[1].idx).transpose(),
                          p2 = X.row(fv[2].idx).transpose();
    const double twice_area = std::abs((p1 - p0).x() * (p2 - p0).y() - (p1 - p0).y() * (p2 - p0).x());
    const double longest = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
    const double radius = std::max({p0.norm(), p1.norm(), p2.norm()});
    rounding(f) = twice_area > 0 ? std::max(OverlayCheck::kRoundingArea, 64 * std::numeric_limits<double>::epsilon() *
                                                                             radius / (twice_area / longest))
                                 : 1.0;
  }
  return rounding;
}

}  // namespace

Overlay overlay_of_map(const MapResult& map, double* agreement) {
  const DiskOverlay disk =
      overlay_disks(*map.bijection, map.disk_a, map.flattening.Phi, map.disk_b, map.flattening.Psi);
  if (agreement != nullptr) *agreement = disk_agreement(map, disk);
  std::map<std::array<int, 6>, int> ids;
  std::vector<int> new_id(disk.on_m.size());
  std::vector<size_t> first;  // a disk vertex of each overlay vertex
  for (size_t i = 0; i < disk.on_m.size(); ++i) {
    const auto ka = refined_key(map.disk_a, map.cut.a.cut_to_refined, disk.on_m[i]);
    const auto kb = refined_key(map.disk_b, map.cut.b.cut_to_refined, disk.on_n[i]);
    const auto [it, fresh] =
        ids.emplace(std::array<int, 6>{ka[0], ka[1], ka[2], kb[0], kb[1], kb[2]}, static_cast<int>(first.size()));
    if (fresh) first.push_back(i);
    new_id[i] = it->second;
  }
  Overlay o;
  const auto nv = static_cast<Eigen::Index>(first.size());
  o.VA.resize(nv, 3);
  o.VB.resize(nv, 3);
  o.on_a.resize(first.size());
  o.on_b.resize(first.size());
#pragma omp parallel for schedule(static)
  for (Eigen::Index v = 0; v < nv; ++v) {
    const size_t i = first[static_cast<size_t>(v)];
    o.on_a[static_cast<size_t>(v)] = disk_to_input(map, Side::kA, disk.on_m[i]);
    o.on_b[static_cast<size_t>(v)] = disk_to_input(map, Side::kB, disk.on_n[i]);
    o.VA.row(v) = interpolate(map.disk_a, map.disk_va, disk.on_m[i]);
    o.VB.row(v) = interpolate(map.disk_b, map.disk_vb, disk.on_n[i]);
  }
  const auto nt = static_cast<Eigen::Index>(disk.triangles.size());
  o.F.resize(nt, 3);
  o.face_a.resize(nt);
  o.face_b.resize(nt);
  o.rounding_a.resize(nt);
  o.rounding_b.resize(nt);
  const Eigen::VectorXd rounding_m = sign_rounding(map.disk_a, map.flattening.Phi);
  const Eigen::VectorXd rounding_n = sign_rounding(map.disk_b, map.flattening.Psi);
  for (Eigen::Index t = 0; t < nt; ++t) {
    const auto i = static_cast<size_t>(t);
    for (int k = 0; k < 3; ++k) o.F(t, k) = new_id[static_cast<size_t>(disk.triangles[i][k])];
    o.face_a(t) = map.cut.a.face_to_input(disk.face_m[i]);
    o.face_b(t) = map.cut.b.face_to_input(disk.face_n[i]);
    o.rounding_a(t) = rounding_m(disk.face_m[i]);
    o.rounding_b(t) = rounding_n(disk.face_n[i]);
  }
  return o;
}

}  // namespace liftmap
