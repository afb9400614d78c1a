#pragma once
/// The options of `liftmap map` as every front end takes them: command-line flags (`map`, `cut`, `batch`), per-pair
/// columns of a batch manifest and Python keywords are all parsed, checked and applied here, so that they accept the
/// same values and make the same MapOptions.

#include <optional>
#include <string>
#include <vector>

#include "map/map_meshes.h"

namespace liftmap {

/// The user-facing options of a map (README, "Command line"), with the CLI's defaults.
struct MapArguments {
  MapChoiceNames choices;   ///< p, h, solver, tree
  bool normalize = true;    ///< scale both meshes to the same area (--no-normalize sets false)
  double tolerance = 1e-3;  ///< relative energy gain below which the outer loop stops; finite > 0
  int max_iterations = 10;  ///< outer iterations, 0 to MapOptionLimits::kMaxOuterIterations
  /// Newton steps of the start's joint relaxation, common boundary free, 0 (off) to kMaxOuterIterations
  int start_relaxation = JointStartRelaxationOptions{}.newton.max_iterations;
  int samples = 2;               ///< n, the n^2 distortion samples per face, 1 to MapOptionLimits::kMaxSamplesPerEdge
  std::optional<int> threads;    ///< 1 to MapOptionLimits::max_threads(); unset: the calling thread's OpenMP setting
  bool fix_orientation = false;  ///< reverse an inside-out mesh with a warning instead of rejecting it
  bool overlay = true;           ///< compute and write the overlay (--no-overlay sets false)
  bool pictures = true;          ///< write render.png and distortion.png (--no-pictures sets false)
};

/// One option of MapArguments as the front ends name it.
struct MapArgumentSpec {
  std::string name;  ///< the Python keyword and manifest column ("max_iterations")
  std::string flag;  ///< the command-line option ("--max-iterations")
  std::string help;  ///< one line for --help
  std::string type;  ///< what --help shows for the value ("INT", "2|inf"); empty for a flag
  bool is_flag;      ///< takes no value on the command line (its name's value is "true"/"false" elsewhere)
  bool in_cut;       ///< also an option of `liftmap cut`
};

/// Every option of MapArguments, in the order of `liftmap map --help`. The flag --no-normalize is the name
/// "normalize" negated.
const std::vector<MapArgumentSpec>& map_argument_specs();

/// Why `value` is not an acceptable text for the option `name` (a MapArgumentSpec::name), e.g. "value 0 not in range
/// 1 to 8"; empty if it is acceptable, and then `args` holds it. Numbers are read whole ("1.5" is no iteration
/// count), booleans as true/false, yes/no, 1/0 (any case), p as 2 or inf (any numeric spelling of them).
/// \pre `name` is one of map_argument_specs()' names
std::string set_map_argument_text(MapArguments& args, const std::string& name, const std::string& value);

/// set_map_argument_text, throwing.
/// \throw UsageError "name: reason" if `name` is unknown or `value` is not acceptable
void set_map_argument(MapArguments& args, const std::string& name, const std::string& value);

/// The MapOptions of a map made with `args`: each option checked against its range.
/// \throw UsageError "name: reason" naming the first option out of its range (as set_map_argument would)
MapOptions map_options(const MapArguments& args);

}  // namespace liftmap
