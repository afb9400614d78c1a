#include "map/map_arguments.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include "core/errors.h"

namespace liftmap {

namespace {

std::string range_problem(long long value, int low, int high) {
  if (value >= low && value <= high) return {};
  return "value " + std::to_string(value) + " not in range " + std::to_string(low) + " to " + std::to_string(high);
}

std::string tolerance_problem(double value, const std::string& text) {
  if (std::isfinite(value) && value > 0) return {};
  return "value " + text + " is not a finite number > 0";
}

std::string choice_problem(const std::string& value, const std::vector<std::string>& accepted) {
  if (std::find(accepted.begin(), accepted.end(), value) != accepted.end()) return {};
  std::string list;
  for (const std::string& a : accepted) list += (list.empty() ? "" : ", ") + a;
  return "'" + value + "' is not one of " + list;
}

/// The whole of `text` as an integer (no sign-less overflow, no trailing characters).
std::optional<long long> parse_integer(const std::string& text) {
  long long value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

/// The whole of `text` as a double ("nan", "inf" and exponents included).
std::optional<double> parse_double(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) != 0) return std::nullopt;
  size_t used = 0;
  try {
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::out_of_range&) {
    return std::nullopt;
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
  return std::nullopt;
}

std::optional<bool> parse_bool(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  if (text == "true" || text == "yes" || text == "1") return true;
  if (text == "false" || text == "no" || text == "0") return false;
  return std::nullopt;
}

/// The norm's canonical name ("2" or "inf") for any numeric spelling of 2 or +inf; the text itself otherwise.
std::string norm_text(const std::string& text) {
  const std::optional<double> x = parse_double(text);
  if (x && *x == 2) return "2";
  if (x && std::isinf(*x) && *x > 0) return "inf";
  return text;
}

std::string integer_argument(int& target, const std::string& text, int low, int high) {
  const std::optional<long long> value = parse_integer(text);
  if (!value) return "value " + text + " is not an integer";
  std::string problem = range_problem(*value, low, high);
  if (problem.empty()) target = static_cast<int>(*value);
  return problem;
}

std::string boolean_argument(bool& target, const std::string& text) {
  const std::optional<bool> value = parse_bool(text);
  if (!value) return "value " + text + " is not one of true, false";
  target = *value;
  return {};
}

std::string choice_argument(std::string& target, const std::string& text, const std::vector<std::string>& accepted) {
  std::string problem = choice_problem(text, accepted);
  if (problem.empty()) target = text;
  return problem;
}

const std::vector<std::string> kNorms = {"2", "inf"};
const std::vector<std::string> kCombiners = {"eq3", "eq2"};
const std::vector<std::string> kSolvers = {"auto", "barrier", "primal-dual"};
const std::vector<std::string> kTrees = {"mst", "path"};

}  // namespace

const std::vector<MapArgumentSpec>& map_argument_specs() {
  static const std::vector<MapArgumentSpec> specs = {
      {"tree", "--tree", "Cut tree: mst (paper) or path (through all landmarks)", "mst|path", false, true},
      {"fix_orientation", "--fix-orientation",
       "Reverse the faces of an inside-out mesh (negative signed volume) with a warning, instead of rejecting it", "",
       true, true},
      {"threads", "--threads",
       "Threads for the per-face work, 1 to 4 per hardware thread (default: all hardware threads)", "INT", false, true},
      {"p", "--p", "Norm of the energy (10a): 2 or inf", "2|inf", false, false},
      {"h", "--h", "Per-face distortion: eq3 = sqrt(Sigma^2 + sigma^-2), eq2 = max", "eq3|eq2", false, false},
      {"normalize", "--no-normalize", "Do not scale both meshes to the same area", "", true, false},
      {"solver", "--solver",
       "Solver of the convex subproblems: barrier, primal-dual, or auto (barrier for p = 2, primal-dual for p = inf)",
       "auto|barrier|primal-dual", false, false},
      {"tolerance", "--tolerance", "Stop when the energy improves by less than this (relative)", "FLOAT", false, false},
      {"max_iterations", "--max-iterations", "Outer iterations of the flattening", "INT", false, false},
      {"start_relaxation", "--start-relaxation",
       "Newton steps at most of the start's joint relaxation, common boundary free (0: off)", "INT", false, false},
      {"samples", "--samples", "Distortion of f, g: n^2 samples per face", "INT", false, false},
      {"overlay", "--no-overlay",
       "Do not compute the overlay (overlay.obj and its tables): for large meshes, a faster map and a smaller folder",
       "", true, false},
      {"pictures", "--no-pictures",
       "Do not draw render.png and distortion.png: about a second less per map, for many maps (the files with the "
       "map's data are all written)",
       "", true, false},
  };
  return specs;
}

std::string set_map_argument_text(MapArguments& args, const std::string& name, const std::string& value) {
  if (name == "p") return choice_argument(args.choices.p, norm_text(value), kNorms);
  if (name == "h") return choice_argument(args.choices.h, value, kCombiners);
  if (name == "solver") return choice_argument(args.choices.solver, value, kSolvers);
  if (name == "tree") return choice_argument(args.choices.tree, value, kTrees);
  if (name == "normalize") return boolean_argument(args.normalize, value);
  if (name == "fix_orientation") return boolean_argument(args.fix_orientation, value);
  if (name == "overlay") return boolean_argument(args.overlay, value);
  if (name == "pictures") return boolean_argument(args.pictures, value);
  if (name == "max_iterations") {
    return integer_argument(args.max_iterations, value, 0, MapOptionLimits::kMaxOuterIterations);
  }
  if (name == "start_relaxation") {
    return integer_argument(args.start_relaxation, value, 0, MapOptionLimits::kMaxOuterIterations);
  }
  if (name == "samples") return integer_argument(args.samples, value, 1, MapOptionLimits::kMaxSamplesPerEdge);
  if (name == "threads") {
    int threads = 0;
    std::string problem = integer_argument(threads, value, 1, MapOptionLimits::max_threads());
    if (problem.empty()) args.threads = threads;
    return problem;
  }
  if (name == "tolerance") {
    const std::optional<double> x = parse_double(value);
    std::string problem = tolerance_problem(x.value_or(std::numeric_limits<double>::quiet_NaN()), value);
    if (problem.empty()) args.tolerance = *x;
    return problem;
  }
  std::string names;
  for (const MapArgumentSpec& s : map_argument_specs()) names += (names.empty() ? "" : ", ") + s.name;
  return "not an option of a map (options: " + names + ")";
}

void set_map_argument(MapArguments& args, const std::string& name, const std::string& value) {
  const std::string problem = set_map_argument_text(args, name, value);
  if (!problem.empty()) throw UsageError(name + ": " + problem);
}

MapOptions map_options(const MapArguments& args) {
  const auto require = [](const std::string& name, const std::string& problem) {
    if (!problem.empty()) throw UsageError(name + ": " + problem);
  };
  MapOptions o;
  set_map_choices(o, args.choices);
  require("tolerance", tolerance_problem(args.tolerance, figure(args.tolerance)));
  require("max_iterations", range_problem(args.max_iterations, 0, MapOptionLimits::kMaxOuterIterations));
  require("samples", range_problem(args.samples, 1, MapOptionLimits::kMaxSamplesPerEdge));
  require("start_relaxation", range_problem(args.start_relaxation, 0, MapOptionLimits::kMaxOuterIterations));
  if (args.threads) require("threads", range_problem(*args.threads, 1, MapOptionLimits::max_threads()));
  o.flatten.normalize_area = args.normalize;
  o.flatten.relative_tolerance = args.tolerance;
  o.flatten.max_iterations = args.max_iterations;
  o.flatten.joint_start.newton.max_iterations = args.start_relaxation;
  o.distortion_samples_per_edge = args.samples;
  o.overlay = args.overlay;
  o.threads = args.threads.value_or(0);
  return o;
}

}  // namespace liftmap
