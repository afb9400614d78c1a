// liftmap: command line front end. Each subcommand is a thin wrapper over the library; every failure becomes
// one message on stderr and a documented exit code (README, "Exit codes").

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string>

#include "check/check_mesh.h"
#include "core/errors.h"
#include "io/landmarks.h"
#include "io/read_mesh.h"

namespace {

using liftmap::ExitCode;

/// Prints the report of one mesh; returns whether it is mappable.
bool report_mesh(const std::string& path, const liftmap::TriangleMesh& mesh, bool as_json) {
  const liftmap::MeshReport r = liftmap::check_mesh(mesh.V, mesh.F);
  if (as_json) {
    nlohmann::json j;
    j["mesh"] = path;
    j["vertices"] = r.n_vertices;
    j["faces"] = r.n_faces;
    j["edges"] = r.n_edges;
    j["connected_components"] = r.n_components;
    j["boundary_loops"] = r.n_boundary_loops;
    j["euler_characteristic"] = r.euler_characteristic;
    j["genus"] = r.genus ? nlohmann::json(*r.genus) : nlohmann::json(nullptr);
    j["mappable"] = r.mappable();
    j["problems"] = nlohmann::json::array();
    for (const auto& p : r.problems)
      j["problems"].push_back({{"kind", p.kind}, {"count", p.count}, {"examples", p.examples}});
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << "mesh:                 " << path << '\n'
              << "vertices:             " << r.n_vertices << '\n'
              << "faces:                " << r.n_faces << '\n'
              << "edges:                " << r.n_edges << '\n'
              << "connected components: " << r.n_components << '\n'
              << "boundary loops:       " << r.n_boundary_loops << '\n'
              << "Euler characteristic: " << r.euler_characteristic << '\n'
              << "genus:                " << (r.genus ? std::to_string(*r.genus) : "undefined (not a manifold)")
              << '\n';
    if (r.mappable()) {
      std::cout << "problems:             none\nmappable:             yes\n";
    } else {
      std::cout << "problems:\n";
      for (const auto& p : r.problems) {
        std::cout << "  " << p.kind << " (" << p.count << "):\n";
        for (const auto& e : p.examples) std::cout << "    " << e << '\n';
        if (p.count > static_cast<int>(p.examples.size())) {
          std::cout << "    ... " << p.count - static_cast<int>(p.examples.size()) << " more\n";
        }
      }
      std::cout << "mappable:             no\n";
    }
  }
  if (!r.mappable()) std::cerr << "liftmap: " << path << ": cannot be mapped: " << r.summary() << '\n';
  return r.mappable();
}

int run_check(const std::vector<std::string>& paths, const std::string& landmarks_path, bool as_json) {
  std::vector<liftmap::TriangleMesh> meshes;
  meshes.reserve(paths.size());
  for (const auto& p : paths) meshes.push_back(liftmap::read_mesh(p));
  bool ok = true;
  for (size_t i = 0; i < paths.size(); ++i) ok = report_mesh(paths[i], meshes[i], as_json) && ok;
  if (!landmarks_path.empty()) {
    const liftmap::Landmarks lm = liftmap::read_landmarks(landmarks_path, static_cast<int>(meshes[0].V.rows()),
                                                          static_cast<int>(meshes[1].V.rows()));
    if (!as_json) std::cout << "landmarks:            " << lm.a.size() << " pairs in " << landmarks_path << '\n';
  }
  return ok ? liftmap::kExitOk : liftmap::kExitInvalidInput;
}

int run(int argc, char** argv) {
  CLI::App app{
      "liftmap: continuous, bijective, low-distortion maps between two genus-0 triangle meshes\n"
      "(Aigerman, Poranne, Lipman: Lifted Bijections for Low Distortion Surface Mappings, 2014)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "liftmap 0.1.0");

  std::vector<std::string> check_paths;
  std::string check_landmarks;
  bool check_json = false;
  CLI::App* check = app.add_subcommand(
      "check", "Validate one mesh, or a pair and its landmarks: counts, topology, and why it cannot be mapped");
  check->add_option("meshes", check_paths, "One or two mesh files (.off, .obj, .ply, .stl)")
      ->required()
      ->expected(1, 2);
  check->add_option("-l,--landmarks", check_landmarks, "Landmark file to validate against the two meshes");
  check->add_flag("--json", check_json, "Print the report as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? liftmap::kExitOk : liftmap::kExitUsage;
  }

  if (*check) {
    if (!check_landmarks.empty() && check_paths.size() != 2) {
      std::cerr << "liftmap: check --landmarks needs two meshes\n";
      return liftmap::kExitUsage;
    }
    return run_check(check_paths, check_landmarks, check_json);
  }
  return liftmap::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const liftmap::IoError& e) {
    std::cerr << "liftmap: " << e.what() << '\n';
    return liftmap::kExitIo;
  } catch (const liftmap::InvalidInputError& e) {
    std::cerr << "liftmap: " << e.what() << '\n';
    return liftmap::kExitInvalidInput;
  } catch (const liftmap::PipelineError& e) {
    std::cerr << "liftmap: " << e.what() << '\n';
    return liftmap::kExitPipeline;
  } catch (const std::bad_alloc&) {
    std::cerr << "liftmap: out of memory\n";
    return liftmap::kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "liftmap: internal error: " << e.what() << '\n';
    return liftmap::kExitInternal;
  } catch (...) {
    return liftmap::kExitInternal;
  }
}
