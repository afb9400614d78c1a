#include "disk_patches.h"

#include <algorithm>
#include <deque>
#include <numbers>
#include <random>
#include <stdexcept>

#include "flatten/boundary_loop.h"
#include "io/read_mesh.h"

namespace liftmap::testing {

void read_test_mesh(const std::string& name, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  TriangleMesh m = read_mesh(std::string(LIFTMAP_DATA_DIR) + "/" + name);
  V = std::move(m.V);
  F = std::move(m.F);
}

std::vector<int> grow_disk(const Eigen::MatrixXi& F, int n_vertices, int seed_face, int n_faces, int n_boundary) {
  const Mesh mesh(F, n_vertices);
  std::vector<char> in(static_cast<size_t>(mesh.n_faces()), 0);
  std::vector<int> vertex_faces(static_cast<size_t>(n_vertices), 0);
  std::vector<int> faces;
  int boundary_edges = 0;
  std::deque<int> queue{seed_face};
  auto neighbour = [&](int f, int k) { return mesh.face(Mesh::twin(mesh.face_halfedges(FaceId(f))[k])); };
  while (!queue.empty()) {
    if (static_cast<int>(faces.size()) >= n_faces && (n_boundary <= 0 || boundary_edges == n_boundary)) break;
    const int f = queue.front();
    queue.pop_front();
    if (in[static_cast<size_t>(f)]) continue;
    int shared = 0;
    for (int k = 0; k < 3; ++k) {
      const FaceId g = neighbour(f, k);
      if (g.valid() && in[static_cast<size_t>(g.idx)]) ++shared;
    }
    if (!faces.empty()) {
      if (shared == 0 || shared == 3) continue;
      if (shared == 1) {
        // The corner opposite the shared edge must be new, or the region would pinch or get a hole.
        const auto fv = mesh.face_vertices(FaceId(f));
        int opposite = -1;
        for (int k = 0; k < 3; ++k) {
          const FaceId g = neighbour(f, k);
          if (g.valid() && in[static_cast<size_t>(g.idx)]) opposite = fv[(k + 2) % 3].idx;
        }
        if (vertex_faces[static_cast<size_t>(opposite)] > 0) {
          queue.push_back(f);  // may become acceptable later
          if (queue.size() > 4 * static_cast<size_t>(mesh.n_faces())) break;
          continue;
        }
      }
    }
    in[static_cast<size_t>(f)] = 1;
    faces.push_back(f);
    boundary_edges += 3 - 2 * shared;
    for (const VertexId v : mesh.face_vertices(FaceId(f))) ++vertex_faces[static_cast<size_t>(v.idx)];
    for (int k = 0; k < 3; ++k) {
      const FaceId g = neighbour(f, k);
      if (g.valid() && !in[static_cast<size_t>(g.idx)]) queue.push_back(g.idx);
    }
  }
  if (n_boundary > 0 && boundary_edges != n_boundary) throw std::runtime_error("grow_disk: boundary count not met");
  return faces;
}

TestDisk make_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& faces, bool complement) {
  std::vector<char> chosen(static_cast<size_t>(F.rows()), complement ? 1 : 0);
  for (const int f : faces) chosen[static_cast<size_t>(f)] = complement ? 0 : 1;
  std::vector<int> index(static_cast<size_t>(V.rows()), -1);
  std::vector<int> kept;
  int nv = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!chosen[static_cast<size_t>(f)]) continue;
    kept.push_back(static_cast<int>(f));
    for (int k = 0; k < 3; ++k) {
      int& i = index[static_cast<size_t>(F(f, k))];
      if (i < 0) i = nv++;
    }
  }
  TestDisk d;
  d.V.resize(nv, 3);
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (index[static_cast<size_t>(v)] >= 0) d.V.row(index[static_cast<size_t>(v)]) = V.row(v);
  }
  d.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t i = 0; i < kept.size(); ++i) {
    for (int k = 0; k < 3; ++k) d.F(static_cast<Eigen::Index>(i), k) = index[static_cast<size_t>(F(kept[i], k))];
  }
  d.mesh = std::make_unique<Mesh>(d.F, nv);
  d.boundary = ccw_boundary_loop(*d.mesh);
  return d;
}

TestDisk jittered_planar_grid(int nx, int ny, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> move(-jitter, jitter);
  Eigen::MatrixXd V((nx + 1) * (ny + 1), 3);
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      const bool inside = i > 0 && i < nx && j > 0 && j < ny;
      V.row(i * (ny + 1) + j) << (i + (inside ? move(rng) : 0)) / ny, (j + (inside ? move(rng) : 0)) / ny, 0;
    }
  }
  Eigen::MatrixXi F(2 * nx * ny, 3);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const int a = i * (ny + 1) + j, b = a + ny + 1;
      F.row(2 * (i * ny + j)) << a, b, b + 1;
      F.row(2 * (i * ny + j) + 1) << a, b + 1, a + 1;
    }
  }
  std::vector<int> all(static_cast<size_t>(F.rows()));
  for (size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
  return make_disk(V, F, all);
}

TestDisk capped_tube(double length_over_girth, int around) {
  const double step = 2 * std::numbers::pi / around * 0.87;
  const double length = length_over_girth * 2 * std::numbers::pi;
  std::vector<std::pair<double, double>> rings;  // (radius, z) of each ring, then the tip
  for (double z = 0; z < length; z += step) rings.emplace_back(1.0, z);
  const int cap_rings = std::max(2, static_cast<int>(0.5 * std::numbers::pi / step));
  for (int k = 0; k < cap_rings; ++k) {
    const double t = 0.5 * std::numbers::pi * k / cap_rings;
    rings.emplace_back(std::cos(t), length + std::sin(t));
  }
  const auto nr = static_cast<int>(rings.size());
  Eigen::MatrixXd V(nr * around + 1, 3);
  for (int r = 0; r < nr; ++r) {
    for (int j = 0; j < around; ++j) {
      const double a = 2 * std::numbers::pi * (j + 0.5 * (r % 2)) / around;
      V.row(r * around + j) << rings[static_cast<size_t>(r)].first * std::cos(a),
          rings[static_cast<size_t>(r)].first * std::sin(a), rings[static_cast<size_t>(r)].second;
    }
  }
  V.row(nr * around) << 0, 0, length + 1;
  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < nr; ++r) {
    for (int j = 0; j < around; ++j) {
      const int a = r * around + j, b = r * around + (j + 1) % around;
      const int c = (r + 1) * around + j, d = (r + 1) * around + (j + 1) % around;
      if (r % 2 == 0) {
        faces.emplace_back(a, b, c);
        faces.emplace_back(b, d, c);
      } else {
        faces.emplace_back(a, d, c);
        faces.emplace_back(a, b, d);
      }
    }
  }
  for (int j = 0; j < around; ++j)
    faces.emplace_back((nr - 1) * around + j, (nr - 1) * around + (j + 1) % around, nr * around);
  Eigen::MatrixXi F(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  std::vector<int> all(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) all[f] = static_cast<int>(f);
  return make_disk(V, F, all);
}

TestDisk mesh_patch(const std::string& name, int seed_face, int n_faces, int n_boundary) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  read_test_mesh(name, V, F);
  return make_disk(V, F, grow_disk(F, static_cast<int>(V.rows()), seed_face, n_faces, n_boundary));
}

TestDisk deformed_copy(const TestDisk& d) {
  TestDisk c;
  const Eigen::RowVector3d lo = d.V.colwise().minCoeff(), hi = d.V.colwise().maxCoeff();
  const double size = (hi - lo).norm();
  c.V = d.V;
  for (Eigen::Index v = 0; v < c.V.rows(); ++v) {
    const Eigen::RowVector3d x = (d.V.row(v) - lo) / size;
    c.V.row(v) = Eigen::RowVector3d(1.4 * x(0) + 0.2 * std::sin(3 * x(1)), 0.8 * x(1) + 0.3 * x(0) * x(0),
                                    x(2) + 0.2 * std::cos(2 * x(0)));
  }
  c.F = d.F;
  c.mesh = std::make_unique<Mesh>(c.F, static_cast<int>(c.V.rows()));
  c.boundary = d.boundary;
  return c;
}

std::pair<TestDisk, TestDisk> patch_pair(const std::string& a, const std::string& b, int n_faces, int seed_a,
                                         int seed_b) {
  TestDisk da = mesh_patch(a, seed_a, n_faces);
  TestDisk db = mesh_patch(b, seed_b, n_faces / 2, static_cast<int>(da.boundary.size()));
  return {std::move(da), std::move(db)};
}

std::pair<TestDisk, TestDisk> punctured_pair(const std::string& a, const std::string& b, int hole_faces) {
  Eigen::MatrixXd Va, Vb;
  Eigen::MatrixXi Fa, Fb;
  read_test_mesh(a, Va, Fa);
  read_test_mesh(b, Vb, Fb);
  const auto ha = grow_disk(Fa, static_cast<int>(Va.rows()), 0, hole_faces);
  TestDisk da = make_disk(Va, Fa, ha, true);
  const auto hb = grow_disk(Fb, static_cast<int>(Vb.rows()), 0, 1, static_cast<int>(da.boundary.size()));
  return {std::move(da), make_disk(Vb, Fb, hb, true)};
}

JointFlattenProblem camel_cow_patch_problem(const Combo& combo) {
  const auto [a, b] = patch_pair("camel.off", "cow.off", 300, 0, 500);
  JointFlattenOptions opt;
  opt.p = combo.p;
  opt.h = combo.h;
  return make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), opt);
}

}  // namespace liftmap::testing
