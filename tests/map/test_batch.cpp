#include "map/batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/errors.h"

namespace liftmap {
namespace {

namespace fs = std::filesystem;

/// A fresh folder under the test's temporary folder.
fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("liftmap_batch_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Batch, ManifestColumnsQuotesCommentsAndRelativePaths) {
  const fs::path dir = fresh_folder("manifest");
  write_text(dir / "pairs.csv",
             "\xEF\xBB\xBF# a comment\r\n"
             "mesh_a, mesh_b ,landmarks,name,max_iterations,tree\r\n"
             "\r\n"
             "a.off,/abs/b.off,lm/x.txt,,3,\r\n"
             "\"c, d.off\",e.off,l.txt,\"say \"\"hi\"\"\",,path\n");
  MapArguments defaults;
  defaults.samples = 3;
  const std::vector<BatchPair> pairs = read_manifest((dir / "pairs.csv").string(), defaults);
  ASSERT_EQ(pairs.size(), 2U);
  EXPECT_EQ(pairs[0].name, "a-b");
  EXPECT_EQ(pairs[0].mesh_a, (dir / "a.off").string());
  EXPECT_EQ(pairs[0].mesh_b, "/abs/b.off");
  EXPECT_EQ(pairs[0].landmarks, (dir / "lm/x.txt").string());
  EXPECT_EQ(pairs[0].arguments.max_iterations, 3);
  EXPECT_EQ(pairs[0].arguments.choices.tree, "mst");
  EXPECT_EQ(pairs[0].arguments.samples, 3);
  EXPECT_EQ(pairs[0].line, 4);
  EXPECT_EQ(pairs[1].mesh_a, (dir / "c, d.off").string());
  EXPECT_EQ(pairs[1].name, "say \"hi\"");
  EXPECT_EQ(pairs[1].arguments.max_iterations, 10);
  EXPECT_EQ(pairs[1].arguments.choices.tree, "path");
}

TEST(Batch, ManifestErrorsNameTheLine) {
  const fs::path dir = fresh_folder("manifest_errors");
  const auto error_of = [&](const std::string& text) -> std::pair<std::string, std::string> {
    write_text(dir / "m.csv", text);
    try {
      read_manifest((dir / "m.csv").string(), {});
    } catch (const UsageError& e) {
      return {"usage", e.what()};
    } catch (const IoError& e) {
      return {"io", e.what()};
    }
    return {"none", ""};
  };
  const std::string m = (dir / "m.csv").string();
  EXPECT_EQ(error_of(""),
            std::make_pair(std::string("io"), m + ": no header (mesh_a,mesh_b,landmarks[,name][,options...])"));
  EXPECT_EQ(error_of("mesh_a,mesh_b,landmarks,mesh_a\n").second,
            m + ":1: the column 'mesh_a' appears twice in the header");
  EXPECT_EQ(error_of("mesh_a,mesh_b,landmarks\n\"a,b,c\n").second,
            m + ":2: a quoted field is not closed, or text follows its closing quote");
  EXPECT_EQ(error_of("mesh_a,mesh_b,landmarks\na,,c\n").second, m + ":2: the mesh_b field is empty");
  EXPECT_EQ(error_of("mesh_a,mesh_b,landmarks,samples\na,b,c,0\n"),
            std::make_pair(std::string("usage"), m + ":2: column samples: value 0 not in range 1 to 10"));
  EXPECT_EQ(error_of("name,mesh_a,mesh_b,landmarks\n.hidden,a,b,c\n").second,
            m + ":2: '.hidden' is a name starting with '.', not a folder name");
  EXPECT_EQ(error_of("name,mesh_a,mesh_b,landmarks\nsummary.csv,a,b,c\n").second,
            m + ":2: 'summary.csv' is the name of the summary, not a folder name");
  EXPECT_THROW(read_manifest((dir / "missing.csv").string(), {}), IoError);
}

TEST(Batch, ShardsTakeEveryNthPairAndTogetherAllOfThem) {
  EXPECT_EQ(shard_pairs(7, parse_shard("1/3")), (std::vector<size_t>{1, 4}));
  std::vector<size_t> all;
  for (int i = 0; i < 3; ++i) {
    for (const size_t k : shard_pairs(7, {i, 3})) all.push_back(k);
  }
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, (std::vector<size_t>{0, 1, 2, 3, 4, 5, 6}));
  for (const char* bad : {"3/3", "-1/3", "1/0", "1", "a/b", "1/2/3", "", "1/9999999999"}) {
    EXPECT_THROW(parse_shard(bad), UsageError) << bad;
  }
}

TEST(Batch, ThreadsAreDividedBetweenJobs) {
  EXPECT_EQ(threads_per_job(8, 4), 2);
  EXPECT_EQ(threads_per_job(3, 2), 1);
  EXPECT_EQ(threads_per_job(1, 4), 1);
  EXPECT_GE(threads_per_job(std::nullopt, 1), 1);
}

TEST(Batch, ExceptionsBecomeTheReadmesExitCodes) {
  std::string message;
  EXPECT_EQ(exit_code_of(std::make_exception_ptr(UsageError("u")), message), kExitUsage);
  EXPECT_EQ(exit_code_of(std::make_exception_ptr(IoError("i")), message), kExitIo);
  EXPECT_EQ(exit_code_of(std::make_exception_ptr(InvalidInputError("v")), message), kExitInvalidInput);
  EXPECT_EQ(exit_code_of(std::make_exception_ptr(PipelineError("p")), message), kExitPipeline);
  EXPECT_EQ(message, "p");
  EXPECT_EQ(exit_code_of(std::make_exception_ptr(std::logic_error("bug")), message), kExitInternal);
  EXPECT_EQ(message, "internal error: bug");
}

// A failed pair is recorded and retried; a complete one (a report.json, here written by hand) is skipped and its
// figures read from the report; summary.csv holds one row per pair in manifest order, pending ones included.
TEST(Batch, OutcomesRecordsAndSummary) {
  const fs::path dir = fresh_folder("summary");
  const fs::path out = dir / "out";
  std::vector<BatchPair> pairs(3);
  pairs[0].name = "missing";
  pairs[0].mesh_a = (dir / "missing.off").string();
  pairs[0].mesh_b = pairs[0].mesh_a;
  pairs[0].landmarks = (dir / "l.txt").string();
  pairs[1].name = "done";
  pairs[2].name = "later";
  write_text(out / "done" / "report.json",
             R"({"verification": {"passed": true, "failures": []}, "seconds": {"total": 1.5},
                 "distortion": {"f": {"mean": 1.25, "median": 1.0, "p95": 2.0, "max": 3.0},
                                "g": {"mean": 1.5, "median": 1.0, "p95": 2.0, "max": 4.0}}})");
  write_text(out / "missing" / ".A_to_B.txt.tmp-1-0", "left by a killed run");

  const PairOutcome failed = run_batch_pair(pairs[0], out.string());
  EXPECT_EQ(failed.status, PairStatus::kFailed);
  EXPECT_EQ(failed.exit_code, kExitIo);
  EXPECT_NE(failed.message.find("missing.off"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "missing" / ".A_to_B.txt.tmp-1-0"));
  const PairOutcome done = run_batch_pair(pairs[1], out.string());
  EXPECT_TRUE(done.skipped);
  EXPECT_EQ(done.status, PairStatus::kOk);
  EXPECT_EQ(done.f.mean, 1.25);
  EXPECT_EQ(done.seconds, 1.5);

  const BatchCounts c = write_batch_summary(pairs, out.string());
  EXPECT_EQ(c.pairs, 3);
  EXPECT_EQ(c.ok, 1);
  EXPECT_EQ(c.failed, 1);
  EXPECT_EQ(c.pending, 1);
  const std::string summary = read_text(out / "summary.csv");
  EXPECT_EQ(summary.substr(0, summary.find('\n')),
            "name,status,exit_code,seconds,f_mean,f_median,f_p95,f_max,g_mean,g_max,verified,message");
  EXPECT_NE(summary.find("\nmissing,failed,3,"), std::string::npos);
  EXPECT_NE(summary.find("\ndone,ok,0,1.5,1.25,1,2,3,1.5,4,yes,\n"), std::string::npos);
  EXPECT_NE(summary.find("\nlater,pending,,,,,,,,,,\n"), std::string::npos);

  // Removing a complete pair's folder makes it pending again.
  fs::remove_all(out / "done");
  EXPECT_EQ(write_batch_summary(pairs, out.string()).pending, 2);
}

// Processes (here threads, each with its own lock file description) rewriting the summary at once: every
// rewrite is whole.
TEST(Batch, ConcurrentSummariesAreWhole) {
  const fs::path out = fresh_folder("concurrent");
  std::vector<BatchPair> pairs(50);
  for (size_t i = 0; i < pairs.size(); ++i) pairs[i].name = "pair" + std::to_string(i);
  std::vector<std::thread> writers;
  for (int t = 0; t < 4; ++t) {
    writers.emplace_back([&] {
      for (int k = 0; k < 20; ++k) write_batch_summary(pairs, out.string());
    });
  }
  for (std::thread& t : writers) t.join();
  const std::string summary = read_text(out / "summary.csv");
  EXPECT_EQ(std::count(summary.begin(), summary.end(), '\n'), 51);
  for (const fs::directory_entry& e : fs::directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

}  // namespace
}  // namespace liftmap
