#include "batch_functions.h"

#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "map/batch.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace liftmap::python {

namespace {

/// The batch's options as set_map_argument texts, keyed by keyword (liftmap_batch.py converts the Python values).
using OptionTexts = std::map<std::string, std::string>;

MapArguments arguments_from(const OptionTexts& options) {
  MapArguments args;
  for (const auto& [name, value] : options) set_map_argument(args, name, value);
  map_options(args);
  return args;
}

/// The pairs of the manifest (with the batch's options), in its order.
std::vector<BatchPair> pairs_of(const std::string& manifest, const OptionTexts& options) {
  return read_manifest(manifest, arguments_from(options));
}

py::dict stats_dict(const DistortionStats& s) {
  return py::dict("mean"_a = s.mean, "median"_a = s.median, "p95"_a = s.p95, "max"_a = s.max);
}

std::string status_text(PairStatus s) {
  return s == PairStatus::kOk ? "ok" : s == PairStatus::kFailed ? "failed" : "pending";
}

py::list plan(const std::string& manifest, const OptionTexts& options, const std::string& out) {
  std::vector<BatchPair> pairs;
  {
    const py::gil_scoped_release unlocked;
    pairs = pairs_of(manifest, options);
  }
  py::list rows;
  for (const BatchPair& p : pairs) {
    rows.append(py::dict("name"_a = p.name, "line"_a = p.line, "mesh_a"_a = p.mesh_a, "mesh_b"_a = p.mesh_b,
                         "landmarks"_a = p.landmarks, "complete"_a = batch_pair_complete(out, p.name)));
  }
  return rows;
}

py::dict run_pair(const std::string& manifest, size_t index, const std::string& out, const OptionTexts& options,
                  std::optional<int> threads) {
  PairOutcome o;
  std::vector<std::string> warnings;
  std::string name;
  {
    const py::gil_scoped_release unlocked;
    const std::vector<BatchPair> pairs = pairs_of(manifest, options);
    if (index >= pairs.size()) {
      throw UsageError(manifest + ": no pair " + std::to_string(index) + " (" + std::to_string(pairs.size()) +
                       " pairs)");
    }
    BatchPair pair = pairs[index];
    if (threads) pair.arguments.threads = *threads;
    name = pair.name;
    o = run_batch_pair(pair, out, [&](const std::string& w) { warnings.push_back(w); });
  }
  return py::dict("name"_a = name, "status"_a = status_text(o.status), "skipped"_a = o.skipped,
                  "exit_code"_a = o.exit_code, "message"_a = o.message, "seconds"_a = o.seconds,
                  "f"_a = stats_dict(o.f), "g"_a = stats_dict(o.g), "verified"_a = o.verified, "warnings"_a = warnings);
}

py::dict summary(const std::string& manifest, const std::string& out, const OptionTexts& options) {
  BatchCounts c;
  {
    const py::gil_scoped_release unlocked;
    c = write_batch_summary(pairs_of(manifest, options), out);
  }
  return py::dict("pairs"_a = c.pairs, "ok"_a = c.ok, "failed"_a = c.failed, "pending"_a = c.pending);
}

constexpr const char* kBatchDoc =
    R"(batch(manifest, out, client=None, *, shard=None, jobs=1, progress=True, **options) -> dict

Maps every pair of a manifest into out/<name>/, each folder with the files `liftmap map` writes (README, "Many
pairs"): the work of `liftmap batch`, on threads of this process or, with a dask.distributed client, one task per
pair on the cluster's workers (on a multi-machine cluster the workers must see the manifest, the meshes and out at
the same paths). A pair whose report.json exists is skipped (a killed run resumes); a pair that fails is recorded in
out/summary.csv with its exit code and message and does not stop the others.
  manifest: CSV with a header: mesh_a, mesh_b, landmarks, optional name and per-pair options (README); relative
    paths are read from the manifest's folder. Its path is made absolute before it is read.
  out: the output folder (created if missing), made absolute.
  client: None (threads of this process) or a dask.distributed.Client.
  shard: None or (i, n) or "i/n": every n-th pair from the i-th.
  jobs: without a client, pairs mapped at once, the threads divided between them (as the CLI's --jobs).
  progress: True: a tqdm bar if tqdm is installed, else one line per pair on stderr; False: silent.
  options: the keywords of liftmap.map that are options of `liftmap map` (p, h, normalize, tolerance,
    max_iterations, solver, tree, samples, start_relaxation, fix_orientation, overlay, threads) and pictures=False
    (the CLI's --no-pictures: no render.png and distortion.png), for every pair unless its manifest line sets
    them. threads: without a client, of all maps together (divided between the jobs); with a client, of each map
    (default: the worker's OpenMP setting).
Returns a dict: "pairs", "ok", "failed", "pending" (of summary.csv, every shard's pairs), "mapped" and "skipped" (of
this call's pairs), "failures": [{"name", "exit_code", "message"}] of this call's pairs, "summary": its path.
Raises UsageError for an option out of its range or a bad manifest column value, ReadError if the manifest cannot
be read or out cannot be written.)";

}  // namespace

void bind_batch(py::module_& m) {
  m.def("_batch_plan", &plan, "manifest"_a, "options"_a, "out"_a,
        "The manifest's pairs: [{name, line, mesh_a, mesh_b, landmarks, complete}] (liftmap.batch's planning).");
  m.def("_batch_run_pair", &run_pair, "manifest"_a, "index"_a, "out"_a, "options"_a, "threads"_a = py::none(),
        "Maps pair `index` of the manifest into out/<name>/ unless complete; returns its outcome as a dict.");
  m.def("_batch_summary", &summary, "manifest"_a, "out"_a, "options"_a,
        "Rewrites out/summary.csv from the pairs' records; returns the counts of its rows.");
  m.def("_threads_per_job", &threads_per_job, "threads"_a, "jobs"_a,
        "Threads per map when `jobs` maps run at once in this process.");
  py::options signature_in_doc;  // the lambda's (*args, **kwargs) would hide the documented signature
  signature_in_doc.disable_function_signatures();
  m.def(
      "batch",
      [](const py::args& args, const py::kwargs& kwargs) {
        return py::module_::import("liftmap_batch").attr("batch")(*args, **kwargs);
      },
      kBatchDoc);
}

}  // namespace liftmap::python
