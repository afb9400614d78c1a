#pragma once
/// The Python objects of a computed map: `liftmap.Map` and its `VertexMap`s.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/surface_point.h"
#include "io/read_mesh.h"
#include "map/map_meshes.h"
#include "map/write_map.h"

namespace liftmap::python {

/// Everything a map was made of and from; shared, never changed, by a Map and its VertexMaps.
struct MapState {
  MapResult result;
  MapInputs inputs;               ///< meshes as mapped (faces reversed where inputs.reversed_a / reversed_b)
  MapOptions options;             ///< without the progress callback
  nlohmann::json report;          ///< report.json
  TriangleMesh given_a, given_b;  ///< the meshes as the caller gave them
  TriangleMesh disk_a, disk_b;    ///< the cut meshes: disk positions (#Vc by 3) and faces F_cut
};

/// A map on the vertices of its source: per source vertex, a face of the target and barycentric coordinates in
/// the order of that face's vertices as given.
struct VertexMap {
  std::vector<SurfacePoint> images;
  std::shared_ptr<const TriangleMesh> target;  ///< positions and faces the images refer to (part of a MapState)

  [[nodiscard]] pybind11::array_t<int> faces() const;           ///< (#V,) int32
  [[nodiscard]] pybind11::array_t<double> barycentric() const;  ///< (#V, 3) float64
  [[nodiscard]] pybind11::array_t<double> points() const;       ///< (#V, 3) float64 positions on the target
};

/// `liftmap.Map`: the map between two input meshes, its cut, flattenings and report.
class Map {
 public:
  explicit Map(std::shared_ptr<const MapState> state) : state_(std::move(state)) {}

  /// f (side A) or g (side B) on the input vertices; faces and coordinates of the other mesh as given.
  [[nodiscard]] VertexMap on_inputs(Side side) const;
  /// f or g on the cut mesh's vertices (vt of cut_A.obj / cut_B.obj), faces of the other cut mesh.
  [[nodiscard]] VertexMap on_cut(Side side) const;
  /// Images of face points of `source`: (faces, barycentric) of the other mesh.
  [[nodiscard]] pybind11::tuple evaluate(const pybind11::handle& faces, const pybind11::handle& barycentric,
                                         const std::string& source) const;
  /// Per-vertex values of `source` (shape (#V,) or (#V, k)) carried onto the other mesh's vertices.
  [[nodiscard]] pybind11::array_t<double> transfer(const pybind11::handle& values, const std::string& source) const;
  /// Phi (side A) or Psi (side B): (#Vc, 2) positions of the cut mesh's vertices in the plane.
  [[nodiscard]] pybind11::array_t<double> flattening(Side side) const;
  /// The cut as arrays (see the docstring of Map.cut).
  [[nodiscard]] pybind11::dict cut() const;
  /// The overlay as arrays (see the docstring of Map.overlay).
  [[nodiscard]] pybind11::dict overlay() const;
  /// report.json as a dict.
  [[nodiscard]] pybind11::object report() const;
  [[nodiscard]] bool verified() const { return state_->result.verification.passed; }
  /// Writes the files of `liftmap map` into `dir`; without `pictures`, all but render.png and distortion.png.
  void save(const std::string& dir, bool pictures) const;

 private:
  std::shared_ptr<const MapState> state_;
};

/// "A" -> Side::kA, "B" -> Side::kB. \throw UsageError naming `name` otherwise.
Side side_named(const std::string& value, const std::string& name);

}  // namespace liftmap::python
