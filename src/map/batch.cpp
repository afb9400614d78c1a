#include "map/batch.h"

#include <fcntl.h>
#include <omp.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/errors.h"
#include "core/seconds_since.h"
#include "io/input_file.h"
#include "io/line_reader.h"
#include "io/output_file.h"

namespace liftmap {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

/// Summary rewrites while pairs finish: at most one per this many seconds (each reads every pair's record).
constexpr double kSummarySeconds = 5;

const char* const kRecordFolder = ".batch";

/// The fields of one CSV line (RFC 4180: a field in double quotes may hold commas and "" for a quote), each
/// unquoted field trimmed of spaces; nullopt for an unterminated quote or text after a closing quote.
std::optional<std::vector<std::string>> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  size_t i = 0;
  while (true) {
    std::string field;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (true) {
        if (i >= line.size()) return std::nullopt;
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        field += line[i++];
      }
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',') return std::nullopt;
    } else {
      const size_t end = std::min(line.find(',', i), line.size());
      field = line.substr(i, end - i);
      while (!field.empty() && (field.back() == ' ' || field.back() == '\t')) field.pop_back();
      i = end;
    }
    fields.push_back(field);
    if (i >= line.size()) return fields;
    ++i;  // the comma
  }
}

/// A field as CSV writes it: quoted if it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    quoted += c;
    if (c == '"') quoted += '"';
  }
  return quoted + '"';
}

/// Why `name` cannot be a pair's folder name in OUT, or empty.
std::string name_problem(const std::string& name) {
  if (name.empty()) return "an empty name";
  if (name.front() == '.') return "a name starting with '.'";
  if (name.find_first_of("/\\") != std::string::npos) return "a name with a '/' or '\\'";
  if (name == "summary.csv") return "the name of the summary";
  return {};
}

std::string record_path(const std::string& out_dir, const std::string& name) {
  return (fs::path(out_dir) / kRecordFolder / (name + ".json")).string();
}

std::string report_path(const std::string& out_dir, const std::string& name) {
  return (fs::path(out_dir) / name / "report.json").string();
}

std::string status_name(PairStatus s) {
  switch (s) {
    case PairStatus::kOk:
      return "ok";
    case PairStatus::kFailed:
      return "failed";
    case PairStatus::kPending:
      break;
  }
  return "pending";
}

PairStatus status_from(const std::string& name) {
  if (name == "ok") return PairStatus::kOk;
  if (name == "failed") return PairStatus::kFailed;
  return PairStatus::kPending;
}

nlohmann::json stats_json(const DistortionStats& s) {
  return {{"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

DistortionStats stats_from(const nlohmann::json& j) {
  return {j.value("mean", 0.0), j.value("median", 0.0), j.value("p95", 0.0), j.value("max", 0.0)};
}

/// The outcome of a pair whose map was made: ok if verified, failed with exit code 5 (files kept) otherwise.
PairOutcome outcome_of_map(bool passed, const std::string& first_failure, const std::string& dir,
                           const DistortionStats& f, const DistortionStats& g) {
  PairOutcome o;
  o.status = passed ? PairStatus::kOk : PairStatus::kFailed;
  o.exit_code = passed ? kExitOk : kExitPipeline;
  if (!passed) o.message = "verification failed (outputs kept in " + dir + ", see report.json): " + first_failure;
  o.mapped = true;
  o.f = f;
  o.g = g;
  o.verified = passed;
  return o;
}

/// The outcome of a complete pair from its report.json (a run killed after it and before the record).
PairOutcome outcome_from_report(const std::string& out_dir, const std::string& name) {
  const std::string path = report_path(out_dir, name);
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_discarded()) throw IoError(path + ": not a report.json of liftmap map");
  const nlohmann::json& v = report["verification"];
  const std::vector<std::string> failures = v.value("failures", std::vector<std::string>{});
  PairOutcome o = outcome_of_map(v.value("passed", false), failures.empty() ? "" : failures.front(),
                                 (fs::path(out_dir) / name).string(), stats_from(report["distortion"]["f"]),
                                 stats_from(report["distortion"]["g"]));
  o.seconds = report["seconds"].value("total", 0.0);
  return o;
}

std::optional<PairOutcome> read_record(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  PairOutcome o;
  o.status = status_from(j.value("status", ""));
  o.exit_code = j.value("exit_code", 0);
  o.message = j.value("message", "");
  o.seconds = j.value("seconds", 0.0);
  o.mapped = j.value("mapped", false);
  o.f = stats_from(j.value("f", nlohmann::json::object()));
  o.g = stats_from(j.value("g", nlohmann::json::object()));
  o.verified = j.value("verified", false);
  return o;
}

void write_record(const std::string& path, const PairOutcome& o) {
  const nlohmann::json j = {{"status", status_name(o.status)},
                            {"exit_code", o.exit_code},
                            {"message", o.message},
                            {"seconds", o.seconds},
                            {"mapped", o.mapped},
                            {"f", stats_json(o.f)},
                            {"g", stats_json(o.g)},
                            {"verified", o.verified}};
  OutputFile file(path);
  const std::string text = j.dump(2) + '\n';
  std::fputs(text.c_str(), file.get());
  file.close();
}

/// Removes what an interrupted run left in a pair's folder: the temporary files of OutputFile (".NAME.tmp-...")
/// for the outputs of `liftmap map` and the write probe of prepare_output_folder.
void remove_leftovers(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  const std::vector<std::string> outputs = map_output_names();
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string file = e.path().filename().string();
    const bool probe = file.rfind(".liftmap-write-test-", 0) == 0;
    const bool temp = std::any_of(outputs.begin(), outputs.end(),
                                  [&](const std::string& n) { return file.rfind("." + n + ".tmp-", 0) == 0; });
    if (probe || temp) fs::remove(e.path(), ec);
  }
}

/// Removes the temporary files of OutputFile whose names start with `prefix` (".NAME.tmp-") from `dir`: what a killed
/// writer left. Only for files no other process writes at the same time.
void remove_temporary_files(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (e.path().filename().string().rfind(prefix, 0) == 0) fs::remove(e.path(), ec);
  }
}

/// An exclusive flock(2) on a file, held while the object lives.
class FileLock {
 public:
  explicit FileLock(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666)) {
    if (fd_ < 0) throw IoError(path + ": cannot open the lock file: " + std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) {
        const std::string reason = std::strerror(errno);
        ::close(fd_);
        throw IoError(path + ": cannot lock: " + reason);
      }
    }
  }
  ~FileLock() { ::close(fd_); }  // releases the lock
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

/// "45 s", "3 min 05 s", "2 h 07 min".
std::string duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buffer[48];
  if (s < 60) {
    std::snprintf(buffer, sizeof buffer, "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return buffer;
}

/// One progress line: the pair that finished, then pairs finished of the shard's, failures of this run, elapsed and
/// estimated remaining time (from the pairs mapped so far by this run).
std::string progress_line(const std::string& name, const PairOutcome& o, size_t finished, size_t total, int failed,
                          double elapsed, size_t mapped, size_t to_map) {
  std::string line = "[" + std::to_string(finished) + "/" + std::to_string(total) + "] " + name + ": ";
  line += o.status == PairStatus::kFailed ? "failed (exit " + std::to_string(o.exit_code) + "): " + o.message
                                          : "ok in " + duration(o.seconds);
  line += " | " + std::to_string(failed) + " failed, " + duration(elapsed) + " elapsed";
  if (mapped < to_map) {
    line +=
        ", about " + duration(elapsed / static_cast<double>(mapped) * static_cast<double>(to_map - mapped)) + " left";
  }
  return line;
}

void make_folder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir.string() + ": cannot create the output folder: " + ec.message());
}

}  // namespace

std::vector<BatchPair> read_manifest(const std::string& path, const MapArguments& defaults) {
  std::ifstream in = open_input_file(path, "manifest");
  const fs::path folder = fs::path(path).parent_path();
  std::vector<std::string> header;
  std::map<std::string, size_t> column;
  std::map<std::string, int> line_of_name;
  std::vector<BatchPair> pairs;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (line == 1) skip_byte_order_mark(text);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    const std::string where = path + ":" + std::to_string(line) + ": ";
    const std::optional<std::vector<std::string>> fields = csv_fields(text);
    if (!fields) throw IoError(where + "a quoted field is not closed, or text follows its closing quote");
    if (header.empty()) {
      header = *fields;
      for (size_t c = 0; c < header.size(); ++c) {
        const std::string& h = header[c];
        if (!column.emplace(h, c).second) throw IoError(where + "the column '" + h + "' appears twice in the header");
        const bool known = h == "mesh_a" || h == "mesh_b" || h == "landmarks" || h == "name";
        const auto& specs = map_argument_specs();
        const bool option =
            std::any_of(specs.begin(), specs.end(), [&](const MapArgumentSpec& s) { return s.name == h; });
        if (h == "threads") {
          throw UsageError(where +
                           "threads cannot be set per pair (the batch's --threads are divided between its "
                           "--jobs)");
        }
        if (!known && !option) {
          std::string names;
          for (const MapArgumentSpec& s : specs) names += s.name == "threads" ? "" : ", " + s.name;
          throw UsageError(where + "unknown column '" + h + "' (columns: mesh_a, mesh_b, landmarks, name" + names +
                           ")");
        }
      }
      for (const char* required : {"mesh_a", "mesh_b", "landmarks"}) {
        if (column.count(required) == 0) throw IoError(where + "the header has no column '" + required + "'");
      }
      continue;
    }
    if (fields->size() != header.size()) {
      throw IoError(where + std::to_string(fields->size()) + " fields, but the header has " +
                    std::to_string(header.size()));
    }
    BatchPair pair;
    pair.line = line;
    pair.arguments = defaults;
    for (const char* required : {"mesh_a", "mesh_b", "landmarks"}) {
      if ((*fields)[column[required]].empty()) throw IoError(where + "the " + required + " field is empty");
    }
    pair.mesh_a = (folder / (*fields)[column["mesh_a"]]).string();
    pair.mesh_b = (folder / (*fields)[column["mesh_b"]]).string();
    pair.landmarks = (folder / (*fields)[column["landmarks"]]).string();
    for (size_t c = 0; c < header.size(); ++c) {
      const std::string& value = (*fields)[c];
      if (value.empty() || header[c] == "name" || column["mesh_a"] == c || column["mesh_b"] == c ||
          column["landmarks"] == c) {
        continue;
      }
      const std::string problem = set_map_argument_text(pair.arguments, header[c], value);
      if (!problem.empty()) throw UsageError(where + "column " + header[c] + ": " + problem);
    }
    const auto name_column = column.find("name");
    if (name_column != column.end()) pair.name = (*fields)[name_column->second];
    if (pair.name.empty()) {
      pair.name = fs::path(pair.mesh_a).stem().string() + "-" + fs::path(pair.mesh_b).stem().string();
    }
    const std::string problem = name_problem(pair.name);
    if (!problem.empty()) throw UsageError(where + "'" + pair.name + "' is " + problem + ", not a folder name");
    const auto [earlier, added] = line_of_name.emplace(pair.name, line);
    if (!added) {
      throw UsageError(where + "the name '" + pair.name + "' is already the name of line " +
                       std::to_string(earlier->second) + " (give each pair its own name in a name column)");
    }
    pairs.push_back(std::move(pair));
  }
  if (in.bad()) throw IoError(path + ": read error");
  if (header.empty()) throw IoError(path + ": no header (mesh_a,mesh_b,landmarks[,name][,options...])");
  return pairs;
}

Shard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  const auto whole = [](const std::string& s) -> std::optional<int> {
    if (s.empty() || s.size() > 9 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      return std::nullopt;
    }
    return std::stoi(s);
  };
  const std::optional<int> index = slash == std::string::npos ? std::nullopt : whole(text.substr(0, slash));
  const std::optional<int> count = slash == std::string::npos ? std::nullopt : whole(text.substr(slash + 1));
  if (!index || !count || *count < 1 || *index >= *count) {
    throw UsageError("shard: '" + text + "' is not i/n with 0 <= i < n");
  }
  return {*index, *count};
}

std::vector<size_t> shard_pairs(size_t n_pairs, const Shard& shard) {
  std::vector<size_t> indices;
  for (size_t i = static_cast<size_t>(shard.index); i < n_pairs; i += static_cast<size_t>(shard.count)) {
    indices.push_back(i);
  }
  return indices;
}

int threads_per_job(std::optional<int> threads, int jobs) {
  return std::max(1, threads.value_or(omp_get_max_threads()) / std::max(1, jobs));
}

int exit_code_of(const std::exception_ptr& error, std::string& message) {
  try {
    std::rethrow_exception(error);
  } catch (const UsageError& e) {
    message = e.what();
    return kExitUsage;
  } catch (const IoError& e) {
    message = e.what();
    return kExitIo;
  } catch (const InvalidInputError& e) {
    message = e.what();
    return kExitInvalidInput;
  } catch (const PipelineError& e) {
    message = e.what();
    return kExitPipeline;
  } catch (const std::bad_alloc&) {
    message = "out of memory";
    return kExitInternal;
  } catch (const std::exception& e) {
    message = std::string("internal error: ") + e.what();
    return kExitInternal;
  } catch (...) {
    message = "internal error";
    return kExitInternal;
  }
}

bool batch_pair_complete(const std::string& out_dir, const std::string& name) {
  std::error_code ec;
  return fs::is_regular_file(report_path(out_dir, name), ec);
}

PairOutcome run_batch_pair(const BatchPair& pair, const std::string& out_dir, const MessageSink& warning) {
  make_folder(fs::path(out_dir) / kRecordFolder);
  const std::string record = record_path(out_dir, pair.name);
  const std::string dir = (fs::path(out_dir) / pair.name).string();
  if (batch_pair_complete(out_dir, pair.name)) {
    std::optional<PairOutcome> o = read_record(record);
    if (!o || o->status == PairStatus::kPending) {
      o = outcome_from_report(out_dir, pair.name);
      write_record(record, *o);
    }
    o->skipped = true;
    return *o;
  }
  std::error_code ec;
  fs::remove(record, ec);  // a previous failure's: the pair is retried
  remove_leftovers(dir);
  remove_temporary_files(fs::path(out_dir) / kRecordFolder, "." + pair.name + ".json.tmp-");
  const auto t0 = Clock::now();
  PairOutcome o;
  try {
    const MessageSink named = [&](const std::string& m) {
      if (warning) warning(pair.name + ": " + m);
    };
    const MapResult map = map_files(pair.mesh_a, pair.mesh_b, pair.landmarks, dir, pair.arguments, {}, named);
    const MapVerification& v = map.verification;
    o = outcome_of_map(v.passed, v.failures.empty() ? "" : v.failures.front(), dir, map.distortion_f, map.distortion_g);
  } catch (...) {
    o.status = PairStatus::kFailed;
    o.exit_code = exit_code_of(std::current_exception(), o.message);
  }
  o.seconds = seconds_since(t0);
  write_record(record, o);
  return o;
}

BatchCounts write_batch_summary(const std::vector<BatchPair>& pairs, const std::string& out_dir) {
  make_folder(fs::path(out_dir) / kRecordFolder);
  const FileLock lock((fs::path(out_dir) / kRecordFolder / "lock").string());
  BatchCounts counts;
  std::string text = "name,status,exit_code,seconds,f_mean,f_median,f_p95,f_max,g_mean,g_max,verified,message\n";
  for (const BatchPair& pair : pairs) {
    std::optional<PairOutcome> o = read_record(record_path(out_dir, pair.name));
    // A record of a map whose folder was removed since (to map it again) no longer holds.
    if (o && o->mapped && !batch_pair_complete(out_dir, pair.name)) o.reset();
    const PairStatus status = o ? o->status : PairStatus::kPending;
    ++counts.pairs;
    counts.ok += status == PairStatus::kOk ? 1 : 0;
    counts.failed += status == PairStatus::kFailed ? 1 : 0;
    counts.pending += status == PairStatus::kPending ? 1 : 0;
    text += csv_field(pair.name) + ',' + status_name(status);
    if (!o || status == PairStatus::kPending) {
      text += ",,,,,,,,,,\n";
      continue;
    }
    const auto figure_or_empty = [&](double x) { return o->mapped ? number(x) : std::string(); };
    text += ',' + std::to_string(o->exit_code) + ',' + number(o->seconds);
    for (const double x : {o->f.mean, o->f.median, o->f.p95, o->f.max, o->g.mean, o->g.max}) {
      text += ',' + figure_or_empty(x);
    }
    text += std::string(",") + (o->verified ? "yes" : "no") + ',' + csv_field(o->message) + '\n';
  }
  remove_temporary_files(out_dir, ".summary.csv.tmp-");  // of a writer killed while it held the lock
  OutputFile file((fs::path(out_dir) / "summary.csv").string());
  std::fputs(text.c_str(), file.get());
  file.close();
  return counts;
}

BatchResult run_batch(const std::vector<BatchPair>& pairs, const std::string& out_dir, const BatchOptions& options) {
  make_folder(fs::path(out_dir) / kRecordFolder);
  const std::vector<size_t> shard = shard_pairs(pairs.size(), options.shard);
  BatchResult result;
  result.shard_pairs = static_cast<int>(shard.size());
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };

  // Complete pairs first, on this thread: a resumed run reports them in one line.
  std::vector<size_t> todo;
  for (const size_t i : shard) {
    if (!batch_pair_complete(out_dir, pairs[i].name)) {
      todo.push_back(i);
      continue;
    }
    const PairOutcome o = run_batch_pair(pairs[i], out_dir);
    ++result.skipped;
    result.shard_failed += o.status == PairStatus::kFailed ? 1 : 0;
  }
  if (result.skipped > 0) {
    say(std::to_string(result.skipped) + " of " + std::to_string(shard.size()) + " pairs already complete: skipped" +
        (result.shard_failed > 0 ? " (" + std::to_string(result.shard_failed) + " of them unverified)" : ""));
  }

  struct Finished {
    size_t index;
    PairOutcome outcome;
  };
  std::mutex mutex;
  std::condition_variable finished_one;
  std::deque<Finished> finished;
  std::exception_ptr error;
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  const MessageSink warning = [&](const std::string& m) {
    const std::lock_guard<std::mutex> lock(mutex);
    if (options.warning) options.warning(m);
  };
  const int threads = threads_per_job(options.threads, options.jobs);
  const auto work = [&] {
    for (size_t k = next++; k < todo.size() && !stop; k = next++) {
      BatchPair pair = pairs[todo[k]];
      pair.arguments.threads = threads;
      try {
        PairOutcome o = run_batch_pair(pair, out_dir, warning);
        const std::lock_guard<std::mutex> lock(mutex);
        finished.push_back({todo[k], std::move(o)});
      } catch (...) {  // the record could not be written: OUT is not writable, so no other pair can be either
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
      finished_one.notify_one();
    }
  };
  std::vector<std::thread> workers;
  const size_t n_workers = std::min(todo.size(), static_cast<size_t>(std::max(1, options.jobs)));
  workers.reserve(n_workers);
  for (size_t w = 0; w < n_workers; ++w) workers.emplace_back(work);

  const auto t0 = Clock::now();
  auto last_summary = t0;
  int failed_now = 0;
  try {
    for (size_t done = 0; done < todo.size();) {
      std::unique_lock<std::mutex> lock(mutex);
      finished_one.wait(lock, [&] { return !finished.empty() || error; });
      if (finished.empty()) break;
      const Finished f = finished.front();
      finished.pop_front();
      ++done;
      ++result.mapped;
      const bool failed = f.outcome.status == PairStatus::kFailed;
      failed_now += failed ? 1 : 0;
      result.shard_failed += failed ? 1 : 0;
      // Under the lock: a line never interleaves with a worker's warning.
      say(progress_line(pairs[f.index].name, f.outcome, static_cast<size_t>(result.skipped) + done, shard.size(),
                        failed_now, seconds_since(t0), done, todo.size()));
      lock.unlock();
      if (seconds_since(last_summary) >= kSummarySeconds) {
        write_batch_summary(pairs, out_dir);
        last_summary = Clock::now();
      }
    }
  } catch (...) {  // the summary could not be written: the workers finish the pairs they map, then it is reported
    stop = true;
    for (std::thread& t : workers) t.join();
    throw;
  }
  for (std::thread& t : workers) t.join();
  if (error) std::rethrow_exception(error);
  result.summary = write_batch_summary(pairs, out_dir);
  return result;
}

}  // namespace liftmap
