#pragma once
/// Typed exceptions of liftmap. Each maps to one documented exit code of the CLI (see README, "Exit codes").

#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

namespace liftmap {

/// The command line asks for something that cannot be done as asked, e.g. an output path that is one of the
/// inputs (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file cannot be opened, read or parsed, or an output cannot be written (exit code 3). The message names the file
/// and, where known, the line or element.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input was read but is not acceptable: invalid mesh (non-manifold, open, wrong genus, degenerate faces,
/// non-finite coordinates) or invalid landmarks (exit code 4). The message names the offending element.
class InvalidInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A pipeline stage failed on valid input: solver breakdown, non-liftable flattenings, failed verification
/// (exit code 5). The message names the stage and what went wrong.
class PipelineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "(a, b)": how messages name an edge by its two vertex indices.
inline std::string edge_name(int a, int b) {
  std::string s("(");
  s += std::to_string(a);
  s += ", ";
  s += std::to_string(b);
  s += ')';
  return s;
}

/// How messages print a measured figure: `digits` significant digits, with an exponent when that is shorter
/// ("6e-09", "1.23e+12", "0.5"; never "0.000000").
inline std::string figure(double x, int digits = 3) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

/// Exit codes of the `liftmap` command line tool, documented in the README.
enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,  ///< a bug: an unexpected exception
  kExitUsage = 2,
  kExitIo = 3,
  kExitInvalidInput = 4,
  kExitPipeline = 5,
  kExitBatchFailures = 6,  ///< `liftmap batch`: some pairs failed (each with its own code in summary.csv)
};

}  // namespace liftmap
