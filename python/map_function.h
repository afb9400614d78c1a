#pragma once
/// `liftmap.map`: the keyword arguments of the Python call, checked as the CLI checks its options, and the call.

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "map/map_arguments.h"
#include "map/map_meshes.h"
#include "map_object.h"

namespace liftmap::python {

/// The keyword arguments of liftmap.map: the options of `liftmap map` (README "Command line") and the Python call's.
struct MapKeywords {
  MapArguments arguments;     ///< p, h, normalize, tolerance, max_iterations, samples, threads, ...
  pybind11::object progress;  ///< None or callable(stage: str, message: str)
  std::string name_a = "mesh A", name_b = "mesh B";
  bool accept_unverified = false;
};

/// The CLI's name of an energy norm given as 2, 2.0, "2", inf or "inf".
std::string norm_name(const pybind11::handle& p);

/// MapOptions from the keywords, checked as the CLI checks its options (map_options).
/// \throw UsageError naming the keyword and the accepted values.
MapOptions options_from(const MapKeywords& keywords);

/// Checks the arrays, runs map_meshes with the GIL released and returns the Map.
/// \throw InvalidInputError for invalid arrays, meshes or landmarks; UsageError for an invalid keyword;
///        PipelineError if a stage fails or (unless accept_unverified) the verification fails.
Map compute_map(const pybind11::handle& VA, const pybind11::handle& FA, const pybind11::handle& VB,
                const pybind11::handle& FB, const pybind11::handle& landmarks, const MapKeywords& keywords);

}  // namespace liftmap::python
