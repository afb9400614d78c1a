#include "io/landmarks.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "core/errors.h"
#include "io/output_file.h"

namespace liftmap {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InvalidInputError(path + ":" + std::to_string(line) + ": " + what);
}

/// A vertex index token: a plain non-negative integer (other forms are reserved for surface points).
long long parse_index(const std::string& path, int line, const std::string& token, char side, int n) {
  const bool digits = !token.empty() && token.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) {
    if (token[0] == '-') fail(path, line, "negative vertex index '" + token + "' for mesh " + side);
    if (token[0] == 'f' || token[0] == 'e') {
      fail(path, line, "surface-point landmarks ('" + token + "') are not supported yet; use a vertex index");
    }
    fail(path, line, "'" + token + "' is not a vertex index for mesh " + side);
  }
  long long v = 0;
  const auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc()) {
    fail(path, line, "vertex " + token + " is out of range for mesh " + side + " (" + std::to_string(n) + " vertices)");
  }
  return v;
}

/// The checks every landmark pair passes, from a file or from arrays: indices in range, no vertex twice per side.
class LandmarkCollector {
 public:
  /// \param unit how messages call a pair's position: "line" (a file's line) or "row" (an array's row)
  LandmarkCollector(std::string name, std::string unit, int n_vertices_a, int n_vertices_b)
      : name_(std::move(name)), unit_(std::move(unit)), n_a_(n_vertices_a), n_b_(n_vertices_b) {}

  void add(long long a, long long b, int line) {
    const int va = vertex(a, 'A', n_a_, line), vb = vertex(b, 'B', n_b_, line);
    unique(line_of_a_, va, 'A', line);
    unique(line_of_b_, vb, 'B', line);
    lm_.a.emplace_back(va);
    lm_.b.emplace_back(vb);
    lm_.line.push_back(line);
  }

  Landmarks finish() {
    if (lm_.a.size() < 2) {
      throw InvalidInputError(name_ + ": " + std::to_string(lm_.a.size()) + " landmark pair(s); at least 2 are needed");
    }
    return std::move(lm_);
  }

 private:
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    if (unit_ == "line") fail(name_, line, what);
    throw InvalidInputError(name_ + ": " + unit_ + " " + std::to_string(line) + ": " + what);
  }

  int vertex(long long v, char side, int n, int line) const {
    if (v < 0) fail_at(line, "negative vertex index '" + std::to_string(v) + "' for mesh " + side);
    if (v >= n) {
      fail_at(line, "vertex " + std::to_string(v) + " is out of range for mesh " + side + " (" + std::to_string(n) +
                        " vertices)");
    }
    return static_cast<int>(v);
  }

  void unique(std::map<int, int>& line_of, int v, char side, int line) const {
    if (auto [it, fresh] = line_of.emplace(v, line); !fresh) {
      fail_at(line, "vertex " + std::to_string(v) + " of mesh " + side + " is already a landmark (" + unit_ + " " +
                        std::to_string(it->second) + ")");
    }
  }

  std::string name_, unit_;
  int n_a_, n_b_;
  std::map<int, int> line_of_a_, line_of_b_;
  Landmarks lm_;
};

}  // namespace

Landmarks read_landmarks(const std::string& path, int n_vertices_a, int n_vertices_b) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path + ": is a directory, not a landmark file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open landmark file");
  return read_landmarks(in, path, n_vertices_a, n_vertices_b);
}

Landmarks read_landmarks(std::istream& in, const std::string& path, int n_vertices_a, int n_vertices_b) {
  LandmarkCollector collector(path, "line", n_vertices_a, n_vertices_b);
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (line_no == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 byte-order mark
    for (char c : text) {
      const auto u = static_cast<unsigned char>(c);
      if (u == 0 || (u < 32 && c != '\t' && c != '\r')) fail(path, line_no, "not a text line (binary data?)");
    }
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream tokens(text);
    std::vector<std::string> t;
    for (std::string s; tokens >> s;) t.push_back(s);
    if (t.empty()) continue;
    if (t.size() != 2) {
      fail(path, line_no, "expected two vertex indices 'iA iB', found " + std::to_string(t.size()) + " fields");
    }
    collector.add(parse_index(path, line_no, t[0], 'A', n_vertices_a),
                  parse_index(path, line_no, t[1], 'B', n_vertices_b), line_no);
  }
  if (in.bad()) throw IoError(path + ": read error");
  return collector.finish();
}

Landmarks make_landmarks(const std::vector<std::array<long long, 2>>& pairs, const std::string& name, int n_vertices_a,
                         int n_vertices_b) {
  LandmarkCollector collector(name, "row", n_vertices_a, n_vertices_b);
  for (size_t i = 0; i < pairs.size(); ++i) collector.add(pairs[i][0], pairs[i][1], static_cast<int>(i));
  return collector.finish();
}

void write_landmarks(const std::string& path, const Landmarks& landmarks) {
  OutputFile f(path);
  std::fprintf(f.get(), "# liftmap landmarks: vertex of A, vertex of B (0-based)\n");
  for (size_t i = 0; i < landmarks.a.size(); ++i)
    std::fprintf(f.get(), "%d %d\n", landmarks.a[i].idx, landmarks.b[i].idx);
  f.close();
}

}  // namespace liftmap
