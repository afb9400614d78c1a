#include "io/landmarks.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "io/output_file.h"

namespace liftmap {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InvalidInputError(path + ":" + std::to_string(line) + ": " + what);
}

int parse_index(const std::string& path, int line, const std::string& token, char side, int n) {
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
  if (ec != std::errc() || v >= n) {
    fail(path, line, "vertex " + token + " is out of range for mesh " + side + " (" + std::to_string(n) + " vertices)");
  }
  return static_cast<int>(v);
}

}  // namespace

Landmarks read_landmarks(const std::string& path, int n_vertices_a, int n_vertices_b) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path + ": is a directory, not a landmark file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open landmark file");
  return read_landmarks(in, path, n_vertices_a, n_vertices_b);
}

Landmarks read_landmarks(std::istream& in, const std::string& path, int n_vertices_a, int n_vertices_b) {
  Landmarks lm;
  std::map<int, int> line_of_a, line_of_b;
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
    const int a = parse_index(path, line_no, t[0], 'A', n_vertices_a);
    const int b = parse_index(path, line_no, t[1], 'B', n_vertices_b);
    if (auto [it, fresh] = line_of_a.emplace(a, line_no); !fresh) {
      fail(
          path, line_no,
          "vertex " + std::to_string(a) + " of mesh A is already a landmark (line " + std::to_string(it->second) + ")");
    }
    if (auto [it, fresh] = line_of_b.emplace(b, line_no); !fresh) {
      fail(
          path, line_no,
          "vertex " + std::to_string(b) + " of mesh B is already a landmark (line " + std::to_string(it->second) + ")");
    }
    lm.a.emplace_back(a);
    lm.b.emplace_back(b);
    lm.line.push_back(line_no);
  }
  if (in.bad()) throw IoError(path + ": read error");
  if (lm.a.size() < 2) {
    throw InvalidInputError(path + ": " + std::to_string(lm.a.size()) + " landmark pair(s); at least 2 are needed");
  }
  return lm;
}

void write_landmarks(const std::string& path, const Landmarks& landmarks) {
  OutputFile f(path);
  std::fprintf(f.get(), "# liftmap landmarks: vertex of A, vertex of B (0-based)\n");
  for (size_t i = 0; i < landmarks.a.size(); ++i)
    std::fprintf(f.get(), "%d %d\n", landmarks.a[i].idx, landmarks.b[i].idx);
  f.close();
}

}  // namespace liftmap
