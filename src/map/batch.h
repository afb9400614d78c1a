#pragma once
/// Many pairs (`liftmap batch`, `liftmap.batch` in Python): a manifest of pairs, each mapped into its own folder as
/// `liftmap map` would map it, resumable (a pair whose report.json exists is complete and skipped), sharded (every
/// n-th pair from i, for job arrays with no coordination) and with several pairs at once in one process. Every
/// process that works on an output folder rebuilds its summary.csv from per-pair records, under a file lock.

#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "map/map_arguments.h"
#include "map/map_files.h"

namespace liftmap {

/// One pair of a manifest.
struct BatchPair {
  std::string name;                       ///< its output folder's name, OUT/<name>/
  std::string mesh_a, mesh_b, landmarks;  ///< paths; relative ones in the manifest are joined to its folder
  MapArguments arguments;                 ///< the batch's options with the line's own columns applied
  int line = 0;                           ///< line of the manifest
};

/// Reads a batch manifest: CSV (RFC 4180 quoting; blank lines and lines starting with '#' skipped) whose header
/// names the columns mesh_a, mesh_b, landmarks (required), name (optional: default "<stem of A>-<stem of B>") and any
/// option of map_argument_specs() but threads (a per-pair value overriding `defaults`; empty: the default).
/// \param defaults the options of the whole batch
/// \return the pairs in the order of the file
/// \throw IoError naming the file (and line) if it cannot be read, has no header, a header without a required
///        column or with a column twice, or a line with another number of fields than the header or an empty path;
///        UsageError naming the file and line for an unknown column, an option value out of its range, or a
///        name that is not a plain folder name (empty, starting with '.', containing '/', or "summary.csv") or that
///        an earlier line already has
std::vector<BatchPair> read_manifest(const std::string& path, const MapArguments& defaults);

/// Which pairs one process of several maps: every `count`-th pair from `index` (0-based).
struct Shard {
  int index = 0;
  int count = 1;
};

/// The shard "i/n", 0 <= i < n.
/// \throw UsageError naming `text` otherwise
Shard parse_shard(const std::string& text);

/// Indices of the pairs of `shard` among `n_pairs`: index, index + count, ...
std::vector<size_t> shard_pairs(size_t n_pairs, const Shard& shard);

/// Threads per map when `jobs` maps run at once: `threads` (default: the calling thread's OpenMP setting, all hardware
/// threads unless OMP_NUM_THREADS says otherwise) divided between them, at least 1 each.
/// \pre jobs >= 1
int threads_per_job(std::optional<int> threads, int jobs);

/// The README's exit code of an exception thrown by the library (UsageError 2, IoError 3, InvalidInputError 4,
/// PipelineError 5, anything else 1) and the message the CLI prints for it (without "liftmap: ").
int exit_code_of(const std::exception_ptr& error, std::string& message);

/// Where a pair stands.
enum class PairStatus {
  kOk,      ///< mapped and verified: OUT/<name>/ holds every file of `liftmap map`
  kFailed,  ///< failed with exit_code (5 with the files kept if only the verification failed)
  kPending  ///< not (yet) mapped: another shard's, or interrupted
};

/// What became of one pair: one row of summary.csv.
struct PairOutcome {
  PairStatus status = PairStatus::kPending;
  bool skipped = false;  ///< already complete before this run
  int exit_code = 0;     ///< 0, or the README's exit code of its failure
  std::string message;   ///< why it failed
  double seconds = 0;    ///< wall time of the pair (reading, mapping, writing)
  bool mapped = false;   ///< its files were written: ok, or failed in the verification only (exit 5)
  DistortionStats f, g;  ///< distortion of the maps (report.json's "distortion"), if mapped
  bool verified = false;
};

/// Whether OUT/<name>/ holds a complete pair (its report.json, written last).
bool batch_pair_complete(const std::string& out_dir, const std::string& name);

/// Maps one pair into OUT/<name>/ exactly as `liftmap map` does (map_files with pair.arguments, threads included),
/// unless it is complete already (then `skipped`). Files an interrupted run left there are removed first. Records
/// the outcome in OUT/.batch/<name>.json, from which write_batch_summary builds its row. A failure of the pair
/// (unreadable or invalid input, pipeline failure, failed verification) is returned, never thrown.
/// \param warning receives warnings (--fix-orientation) prefixed by the pair's name
/// \throw IoError only if the record cannot be written (OUT not writable)
PairOutcome run_batch_pair(const BatchPair& pair, const std::string& out_dir, const MessageSink& warning = {});

/// Counts of summary.csv's rows.
struct BatchCounts {
  int pairs = 0, ok = 0, failed = 0, pending = 0;
};

/// Rebuilds OUT/summary.csv from the records of run_batch_pair, one row per pair of `pairs` in their order (name,
/// status, exit_code, seconds, f_mean, f_median, f_p95, f_max, g_mean, g_max, verified, message), under an exclusive
/// lock on OUT/.batch/lock so that processes that share OUT (shards) rewrite it one at a time, and atomically.
/// \throw IoError if OUT cannot be written
BatchCounts write_batch_summary(const std::vector<BatchPair>& pairs, const std::string& out_dir);

/// Settings of run_batch.
struct BatchOptions {
  Shard shard;
  int jobs = 1;                ///< pairs mapped at once, each on its own thread
  std::optional<int> threads;  ///< threads of all maps together (threads_per_job)
  /// Called on the calling thread with one line per finished pair: its name and status, pairs done of the
  /// shard's, failures, elapsed and estimated remaining time; empty: silent.
  MessageSink progress;
  MessageSink warning;  ///< as run_batch_pair's (called from the worker threads, one at a time)
};

/// What run_batch did.
struct BatchResult {
  BatchCounts summary;   ///< of summary.csv after the run (every shard's pairs)
  int shard_pairs = 0;   ///< pairs of this shard
  int mapped = 0;        ///< of them, mapped by this run (failures included)
  int skipped = 0;       ///< complete before this run
  int shard_failed = 0;  ///< of this shard's pairs, failed (including complete ones whose verification failed)
};

/// `liftmap batch`: run_batch_pair for every pair of the shard, `jobs` at a time with threads_per_job threads each
/// (set per map, on the worker threads: the calling thread's settings are untouched), summary.csv rewritten as the
/// pairs finish (at most every few seconds) and at the end.
/// \pre options.jobs >= 1, a valid shard
/// \throw IoError if OUT cannot be created or written
BatchResult run_batch(const std::vector<BatchPair>& pairs, const std::string& out_dir, const BatchOptions& options);

}  // namespace liftmap
