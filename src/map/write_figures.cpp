#include "map/write_figures.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/errors.h"
#include "io/output_file.h"
#include "io/write_mesh.h"
#include "render/figure.h"
#include "render/histogram.h"
#include "render/image.h"

namespace liftmap {

namespace {

Eigen::MatrixXd positions_on(const TriangleMesh& mesh, const std::vector<SurfacePoint>& points) {
  Eigen::MatrixXd P(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) {
    P.row(static_cast<Eigen::Index>(i)).setZero();
    for (int k = 0; k < 3; ++k) {
      P.row(static_cast<Eigen::Index>(i)) +=
          points[i].bary[static_cast<size_t>(k)] * mesh.V.row(mesh.F(points[i].face.idx, k));
    }
  }
  return P;
}

std::vector<Eigen::MatrixXd> cut_polylines(const CutSide& side) {
  std::vector<Eigen::MatrixXd> lines;
  for (const auto& path : side.paths) {
    Eigen::MatrixXd P(static_cast<Eigen::Index>(path.size()), 3);
    for (size_t i = 0; i < path.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = side.V.row(path[i]);
    lines.push_back(std::move(P));
  }
  return lines;
}

Eigen::MatrixXd landmark_positions(const TriangleMesh& mesh, const std::vector<SurfacePoint>& landmarks) {
  const Mesh connectivity(mesh.F, static_cast<int>(mesh.V.rows()));
  Eigen::MatrixXd L(static_cast<Eigen::Index>(landmarks.size()), 3);
  for (size_t i = 0; i < landmarks.size(); ++i)
    L.row(static_cast<Eigen::Index>(i)) = interpolate(connectivity, mesh.V, landmarks[i]);
  return L;
}

void write_mtl(const std::string& path, const std::string& texture) {
  OutputFile f(path);
  std::fprintf(f.get(), "newmtl material\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd %s\n", texture.c_str());
  f.close();
}

}  // namespace

void write_map_render(const std::string& path, const MapResult& map, const TriangleMesh& a, const TriangleMesh& b,
                      const std::vector<SurfacePoint>& landmarks_a, const std::vector<SurfacePoint>& landmarks_b,
                      const std::string& label_a, const std::string& label_b) {
  FigurePanel pa;
  pa.V = a.V;
  pa.F = a.F;
  pa.cut_paths = cut_polylines(map.cut.a);
  pa.landmarks = landmark_positions(a, landmarks_a);
  pa.label = label_a;
  FigurePanel pb;
  pb.V = b.V;
  pb.F = b.F;
  pb.T = positions_on(a, map.b_to_a);  // B's texture lookup point on A: g(V_B)
  pb.cut_paths = cut_polylines(map.cut.b);
  pb.landmarks = landmark_positions(b, landmarks_b);
  pb.label = label_b;
  write_png(path, render_map_figure(pa, pb));
}

void write_distortion_histogram(const std::string& path, const MapResult& map) {
  HistogramOptions options;
  options.title = "distortion of f (area-weighted samples)";
  render_histogram_png(map.f_samples, map.f_weights, path, options);
}

void write_textured_meshes(const std::string& folder, const MapResult& map) {
  const std::filesystem::path dir(folder);
  // One texture space for both: Phi and Psi share their boundary, so their common bounding box.
  const Eigen::MatrixXd& Phi = map.flattening.Phi;
  const Eigen::MatrixXd& Psi = map.flattening.Psi;
  const Eigen::RowVector2d lo = Phi.colwise().minCoeff().cwiseMin(Psi.colwise().minCoeff());
  const Eigen::RowVector2d hi = Phi.colwise().maxCoeff().cwiseMax(Psi.colwise().maxCoeff());
  const double size = (hi - lo).maxCoeff();
  const Eigen::MatrixXd UVa = (Phi.rowwise() - lo) / size;
  const Eigen::MatrixXd UVb = (Psi.rowwise() - lo) / size;
  write_mtl((dir / "A_textured.mtl").string(), "texture.png");
  write_mtl((dir / "B_textured.mtl").string(), "texture.png");
  write_obj_with_uv((dir / "A_textured.obj").string(), map.cut.a.V, map.cut.a.F, UVa, map.cut.a.F_cut,
                    "A_textured.mtl");
  write_obj_with_uv((dir / "B_textured.obj").string(), map.cut.b.V, map.cut.b.F, UVb, map.cut.b.F_cut,
                    "B_textured.mtl");
  // A checkerboard with a smooth colour ramp: distortion and orientation are both visible.
  const int n = 1024, cells = 16;
  Image texture(n, n);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const double u = (x + 0.5) / n, v = 1.0 - (y + 0.5) / n;  // OBJ's v runs upwards
      const bool dark = ((static_cast<int>(u * cells) + static_cast<int>(v * cells)) % 2) != 0;
      Eigen::Vector3d c(0.35 + 0.6 * u, 0.45 + 0.4 * v, 0.95 - 0.6 * u);
      if (dark) c *= 0.55;
      texture.set(x, y, c);
    }
  }
  write_png((dir / "texture.png").string(), texture);
}

}  // namespace liftmap
