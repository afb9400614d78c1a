#include "io/write_mesh.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/errors.h"
#include "io/output_file.h"
#include "io/text_line.h"

namespace liftmap {

void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".obj") {
    write_obj_with_uv(path, V, F, Eigen::MatrixXd(), Eigen::MatrixXi());
    return;
  }
  if (ext != ".off" && ext != ".ply") throw IoError(path + ": cannot write format '" + ext + "'");
  OutputFile f(path);
  if (ext == ".off") {
    std::fprintf(f.get(), "OFF\n%td %td 0\n", V.rows(), F.rows());
  } else {
    std::fprintf(f.get(),
                 "ply\nformat ascii 1.0\nelement vertex %td\nproperty double x\nproperty double y\n"
                 "property double z\nelement face %td\nproperty list uchar int vertex_indices\nend_header\n",
                 V.rows(), F.rows());
  }
  TextLine line;
  for (Eigen::Index i = 0; i < V.rows(); ++i) line.add(V(i, 0)).add(V(i, 1)).add(V(i, 2)).write_to(f.get());
  for (Eigen::Index i = 0; i < F.rows(); ++i) line.add(3).add(F(i, 0)).add(F(i, 1)).add(F(i, 2)).write_to(f.get());
  f.close();
}

void write_obj_with_uv(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       const Eigen::MatrixXd& UV, const Eigen::MatrixXi& FT, const std::string& mtl) {
  OutputFile f(path);
  if (!mtl.empty()) std::fprintf(f.get(), "mtllib %s\nusemtl material\n", mtl.c_str());
  TextLine line;
  for (Eigen::Index i = 0; i < V.rows(); ++i) line.add("v").add(V(i, 0)).add(V(i, 1)).add(V(i, 2)).write_to(f.get());
  for (Eigen::Index i = 0; i < UV.rows(); ++i) line.add("vt").add(UV(i, 0)).add(UV(i, 1)).write_to(f.get());
  const bool with_uv = FT.rows() == F.rows() && UV.rows() > 0;
  for (Eigen::Index i = 0; i < F.rows(); ++i) {
    if (with_uv) {
      std::fprintf(f.get(), "f %d/%d %d/%d %d/%d\n", F(i, 0) + 1, FT(i, 0) + 1, F(i, 1) + 1, FT(i, 1) + 1, F(i, 2) + 1,
                   FT(i, 2) + 1);
    } else {
      line.add("f").add(F(i, 0) + 1).add(F(i, 1) + 1).add(F(i, 2) + 1).write_to(f.get());
    }
  }
  f.close();
}

}  // namespace liftmap
