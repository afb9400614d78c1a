#include "map/transfer.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "core/errors.h"
#include "io/input_file.h"
#include "io/line_reader.h"
#include "io/output_file.h"
#include "io/text_line.h"
#include "map/check_overlay.h"

namespace liftmap {

Eigen::MatrixXd interpolate_at(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X,
                               const std::vector<SurfacePoint>& points) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(points.size()), X.cols());
  for (size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    if (p.kind != SurfacePoint::Kind::kFace || p.face.idx < 0 || p.face.idx >= F.rows()) {
      throw InvalidInputError("point " + std::to_string(i) + " names face " + std::to_string(p.face.idx) +
                              ", but the mesh has " + std::to_string(F.rows()) + " faces");
    }
    const auto r = static_cast<Eigen::Index>(i);
    out.row(r).setZero();
    for (int k = 0; k < 3; ++k) {
      const int v = F(p.face.idx, k);
      if (v >= X.rows()) {
        throw InvalidInputError("the data has " + std::to_string(X.rows()) + " rows, but face " +
                                std::to_string(p.face.idx) + " uses vertex " + std::to_string(v));
      }
      out.row(r) += p.bary[static_cast<size_t>(k)] * X.row(v);
    }
  }
  return out;
}

std::vector<int> folded_faces(const Eigen::MatrixXi& F_source, const Eigen::MatrixXd& placed,
                              const Eigen::MatrixXd& V_target, const Eigen::MatrixXi& F_target,
                              const std::vector<SurfacePoint>& points, const Eigen::VectorXi& containing,
                              int* rounding_level) {
  const auto unit_normal = [&](int f) -> Eigen::Vector3d {
    const Eigen::Vector3d a = V_target.row(F_target(f, 0)), b = V_target.row(F_target(f, 1)),
                          c = V_target.row(F_target(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double l = n.norm();
    return l > 0 ? Eigen::Vector3d(n / l) : Eigen::Vector3d::Zero();
  };
  std::vector<int> folded;
  for (Eigen::Index f = 0; f < F_source.rows(); ++f) {
    const Eigen::Vector3d p0 = placed.row(F_source(f, 0)), p1 = placed.row(F_source(f, 1)),
                          p2 = placed.row(F_source(f, 2));
    Eigen::Vector3d surface = Eigen::Vector3d::Zero();
    if (containing.size() > 0) {
      surface = unit_normal(containing(f));
      const int g = containing(f);
      const Eigen::Vector3d a = V_target.row(F_target(g, 0)), b = V_target.row(F_target(g, 1)),
                            c = V_target.row(F_target(g, 2));
      const double face_area = (b - a).cross(c - a).norm();
      if (std::abs((p1 - p0).cross(p2 - p0).dot(surface)) <= OverlayCheck::kRoundingArea * face_area) {
        if (rounding_level != nullptr) ++*rounding_level;
        continue;
      }
    } else {
      for (int k = 0; k < 3; ++k) surface += unit_normal(points[static_cast<size_t>(F_source(f, k))].face.idx);
    }
    if (!((p1 - p0).cross(p2 - p0).dot(surface) > 0)) folded.push_back(static_cast<int>(f));
  }
  return folded;
}

Eigen::MatrixXd read_attributes(const std::string& path, std::vector<int>* line_of_row) {
  std::ifstream in = open_input_file(path, "attribute file");
  return read_attributes(in, path, line_of_row);
}

Eigen::MatrixXd read_attributes(std::istream& in, const std::string& path, std::vector<int>* line_of_row) {
  std::vector<std::vector<double>> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1) skip_byte_order_mark(line);
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream s(line);
    std::vector<double> row;
    std::string token;
    while (s >> token) {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        throw IoError(path + ":" + std::to_string(line_no) + ": '" + token + "' is not a number");
      }
      row.push_back(x);
    }
    if (row.empty()) continue;
    if (!rows.empty() && row.size() != rows.front().size()) {
      throw IoError(path + ":" + std::to_string(line_no) + ": " + std::to_string(row.size()) +
                    " columns, but the first row has " + std::to_string(rows.front().size()));
    }
    rows.push_back(std::move(row));
    if (line_of_row != nullptr) line_of_row->push_back(line_no);
  }
  if (in.bad()) throw IoError(path + ": read error");
  if (rows.empty()) throw IoError(path + ": no rows of numbers");
  Eigen::MatrixXd X(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.front().size()));
  for (size_t i = 0; i < rows.size(); ++i) {
    for (size_t j = 0; j < rows[i].size(); ++j)
      X(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
  }
  return X;
}

void write_attributes(const std::string& path, const Eigen::MatrixXd& X) {
  OutputFile f(path);
  TextLine line;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (Eigen::Index j = 0; j < X.cols(); ++j) line.add(X(i, j));
    line.write_to(f.get());
  }
  f.close();
}

MapDifference compare_maps(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<SurfacePoint>& map,
                           const std::vector<SurfacePoint>& truth) {
  if (map.size() != truth.size()) {
    throw InvalidInputError("the maps have " + std::to_string(map.size()) + " and " + std::to_string(truth.size()) +
                            " lines: they do not start from the same mesh");
  }
  double area = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  const Eigen::MatrixXd P = interpolate_at(F, V, map);
  const Eigen::MatrixXd Q = interpolate_at(F, V, truth);
  MapDifference d;
  if (map.empty()) return d;
  const Eigen::VectorXd dist = (P - Q).rowwise().norm() / std::sqrt(area);
  d.mean = dist.mean();
  Eigen::Index worst = 0;
  d.max = dist.maxCoeff(&worst);
  d.worst_vertex = static_cast<int>(worst);
  return d;
}

}  // namespace liftmap
