#pragma once
/// Using a map file: carrying data from one mesh to the other and comparing maps.

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/surface_point.h"

namespace liftmap {

/// Interpolates per-vertex data of a mesh at points of it.
/// \param F #F by 3 faces of the mesh the points lie on
/// \param X #V by k per-vertex data of that mesh (positions, attributes, texture coordinates)
/// \param points face points of that mesh (e.g. a map file B_to_A read with read_vertex_map)
/// \return #points by k interpolated rows
/// \throw InvalidInputError if a point's face is out of range
Eigen::MatrixXd interpolate_at(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X,
                               const std::vector<SurfacePoint>& points);

/// The faces of a mesh placed on a target surface (`liftmap transfer mesh`) that are folded against it: face f of
/// `F_source`, with corners at `placed` (the images of its vertices), is folded if its normal
/// n_f = (p1 - p0) x (p2 - p0) satisfies n_f . N_f <= 0, where N_f is the sum of the unit normals of the target
/// faces that hold its three corners' images (a zero-area placed face counts as folded).
/// \param F_source #Fs by 3 faces of the source mesh
/// \param placed #Vs by 3 positions of the source vertices on the target (interpolate_at of `points`)
/// \param V_target, F_target the target mesh
/// \param points #Vs face points of the target, one per source vertex (the map)
/// \param containing if not empty (#Fs), the target face that holds each placed face whole (an overlay's face_b):
///        N_f is then that face's unit normal, and a face whose area is within OverlayCheck::kRoundingArea of its
///        containing face's area of zero (an overlay cell thinner than double precision shows) is not folded but
///        counted in `rounding_level`
/// \param rounding_level if not null, receives the number of such faces
/// \return indices of the folded faces of `F_source`, increasing
/// \pre every point's face is a face of `F_target` (interpolate_at has checked it)
std::vector<int> folded_faces(const Eigen::MatrixXi& F_source, const Eigen::MatrixXd& placed,
                              const Eigen::MatrixXd& V_target, const Eigen::MatrixXi& F_target,
                              const std::vector<SurfacePoint>& points, const Eigen::VectorXi& containing = {},
                              int* rounding_level = nullptr);

/// Reads a table of numbers: one row of whitespace-separated numbers per line, `#` comments, blank lines
/// ignored (per-vertex attributes, map files).
/// \param line if not null, receives the file line of every row (for messages)
/// \throw IoError naming the file and line for a malformed row or rows of different lengths, or no rows
Eigen::MatrixXd read_attributes(const std::string& path, std::vector<int>* line = nullptr);

/// read_attributes from a stream; `name` stands for the file in messages.
Eigen::MatrixXd read_attributes(std::istream& in, const std::string& name, std::vector<int>* line = nullptr);

/// Writes per-vertex attributes in the format of read_attributes (17 significant digits).
void write_attributes(const std::string& path, const Eigen::MatrixXd& X);

/// Distance between two maps into the same mesh, per source vertex, in R^3, relative to sqrt(area) of the
/// target (a Euclidean, not geodesic, distance).
struct MapDifference {
  double mean = 0;
  double max = 0;
  int worst_vertex = -1;
};

/// Compares a map with a ground-truth map (both face points of the target mesh, one per source vertex).
/// \param V, F the target mesh
/// \throw InvalidInputError if the two maps have different lengths
MapDifference compare_maps(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<SurfacePoint>& map,
                           const std::vector<SurfacePoint>& truth);

}  // namespace liftmap
