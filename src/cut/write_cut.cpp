#include "cut/write_cut.h"

#include <cstdio>
#include <memory>

#include "core/errors.h"
#include "io/output_file.h"
#include "io/text_line.h"
#include "io/write_mesh.h"

namespace liftmap {

namespace {

void write_side(const std::string& dir, const std::string& name, const CutSide& s, const Eigen::MatrixXd& UV) {
  const Eigen::MatrixXd uv =
      UV.rows() == s.cut_to_refined.size() ? UV : Eigen::MatrixXd::Zero(s.cut_to_refined.size(), 2);
  write_obj_with_uv(dir + "/cut_" + name + ".obj", s.V, s.F, uv, s.F_cut);

  const std::string graph = dir + "/cut_graph_" + name + ".obj";
  OutputFile f(graph);
  TextLine line;
  for (Eigen::Index i = 0; i < s.V.rows(); ++i)
    line.add("v").add(s.V(i, 0)).add(s.V(i, 1)).add(s.V(i, 2)).write_to(f.get());
  for (const auto& path : s.paths) {
    std::fprintf(f.get(), "l");
    for (const int v : path) std::fprintf(f.get(), " %d", v + 1);
    std::fprintf(f.get(), "\n");
  }
  f.close();
}

}  // namespace

void write_cut(const std::string& dir, const CutResult& result, const Eigen::MatrixXd& UV_a,
               const Eigen::MatrixXd& UV_b) {
  write_side(dir, "A", result.a, UV_a);
  write_side(dir, "B", result.b, UV_b);
  const std::string pairs = dir + "/boundary_map.txt";
  OutputFile f(pairs);
  for (const auto& p : result.nu) std::fprintf(f.get(), "%d %d\n", p[0], p[1]);
  f.close();
}

std::vector<std::string> cut_output_names() {
  return {"cut_A.obj", "cut_B.obj", "cut_graph_A.obj", "cut_graph_B.obj", "boundary_map.txt"};
}

}  // namespace liftmap
