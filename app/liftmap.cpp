// liftmap: command line front end. Each subcommand is a thin wrapper over the library; every failure becomes
// one message on stderr and a documented exit code (README, "Exit codes").

#include <omp.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "check/check_mesh.h"
#include "core/errors.h"
#include "cut/write_cut.h"
#include "io/landmarks.h"
#include "io/output_file.h"
#include "io/output_folder.h"
#include "io/read_mesh.h"
#include "io/read_obj_with_uv.h"
#include "io/vertex_map.h"
#include "io/write_mesh.h"
#include "keep_freed_memory.h"
#include "map/bake_texture.h"
#include "map/batch.h"
#include "map/map_arguments.h"
#include "map/map_files.h"
#include "map/map_meshes.h"
#include "map/overlay_files.h"
#include "map/transfer.h"
#include "map/write_map.h"
#include "passive_openmp_waits.h"

namespace {

using liftmap::ExitCode;

/// Prints the report of one mesh as text.
void print_mesh_report(const std::string& path, const liftmap::MeshReport& r) {
  std::cout << "mesh:                 " << path << '\n'
            << "vertices:             " << r.n_vertices << '\n'
            << "faces:                " << r.n_faces << '\n'
            << "edges:                " << r.n_edges << '\n'
            << "connected components: " << r.n_components << '\n'
            << "boundary edges:       " << r.n_boundary_edges << '\n'
            << "boundary loops:       "
            << (r.n_boundary_loops ? std::to_string(*r.n_boundary_loops) : "undefined (not a manifold)") << '\n'
            << "Euler characteristic: " << r.euler_characteristic << '\n'
            << "genus:                " << (r.genus ? std::to_string(*r.genus) : "undefined (not a manifold)") << '\n';
  if (r.mappable()) {
    std::cout << "problems:             none\nmappable:             yes\n";
    return;
  }
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

void print_warning(const std::string& message) { std::cerr << "liftmap: warning: " << message << '\n'; }

/// `liftmap check`: the report of every mesh, then the landmark file's verdict; with --json one document
/// {"meshes": [...], "landmarks": {...} (with -l), "mappable": ...}.
int run_check(const std::vector<std::string>& paths, const std::string& landmarks_path, bool as_json) {
  std::vector<liftmap::TriangleMesh> meshes;
  meshes.reserve(paths.size());
  for (const auto& p : paths) meshes.push_back(liftmap::read_mesh(p));
  nlohmann::json doc;
  doc["meshes"] = nlohmann::json::array();
  int code = liftmap::kExitOk;
  std::vector<std::string> errors;
  for (size_t i = 0; i < paths.size(); ++i) {
    const liftmap::MeshReport r = liftmap::check_mesh(meshes[i].V, meshes[i].F);
    if (as_json) {
      doc["meshes"].push_back(liftmap::mesh_report_json(r, paths[i]));
    } else {
      print_mesh_report(paths[i], r);
    }
    if (!r.mappable()) {
      errors.push_back(paths[i] + ": cannot be mapped: " + r.summary());
      code = liftmap::kExitInvalidInput;
    }
  }
  if (!landmarks_path.empty()) {
    nlohmann::json lm = {{"file", landmarks_path}};
    try {
      const liftmap::Landmarks landmarks =
          liftmap::read_landmarks(landmarks_path, meshes[0].V, meshes[0].F, meshes[1].V, meshes[1].F);
      lm["warnings"] = landmarks.warnings;
      if (!as_json) {
        for (const std::string& w : landmarks.warnings) print_warning(w);
      }
      lm["pairs"] = landmarks.a.size();
      lm["valid"] = true;
      lm["error"] = nullptr;
      if (!as_json)
        std::cout << "landmarks:            " << landmarks.a.size() << " pairs in " << landmarks_path << '\n';
    } catch (const liftmap::IoError& e) {
      lm["valid"] = false;
      lm["error"] = e.what();
      errors.emplace_back(e.what());
      if (code == liftmap::kExitOk) code = liftmap::kExitIo;
    } catch (const liftmap::InvalidInputError& e) {
      lm["valid"] = false;
      lm["error"] = e.what();
      errors.emplace_back(e.what());
      if (code == liftmap::kExitOk) code = liftmap::kExitInvalidInput;
    }
    if (!as_json && !lm["valid"].get<bool>())
      std::cout << "landmarks:            invalid: " << lm["error"].get<std::string>() << '\n';
    doc["landmarks"] = lm;
  }
  doc["mappable"] = code == liftmap::kExitOk;
  if (as_json) std::cout << doc.dump(2) << '\n';
  for (const std::string& e : errors) std::cerr << "liftmap: " << e << '\n';
  return code;
}

/// Usage errors in the form of every other message: one line starting with `liftmap:`.
std::string usage_message(const CLI::App* app, const CLI::Error& e) {
  std::string command = app->get_name();
  for (const CLI::App* p = app->get_parent(); p != nullptr; p = p->get_parent()) command.insert(0, p->get_name() + " ");
  return "liftmap: " + std::string(e.what()) + " (see '" + command + " --help')\n";
}

/// The text of an option's default in --help; empty if it has none to show.
std::string default_text(const liftmap::MapArguments& args, const std::string& name) {
  if (name == "p") return args.choices.p;
  if (name == "h") return args.choices.h;
  if (name == "solver") return args.choices.solver;
  if (name == "tree") return args.choices.tree;
  if (name == "tolerance") return liftmap::figure(args.tolerance);
  if (name == "max_iterations") return std::to_string(args.max_iterations);
  if (name == "start_relaxation") return std::to_string(args.start_relaxation);
  if (name == "samples") return std::to_string(args.samples);
  return {};
}

/// The options of a map (map_argument_specs: all for `map` and `batch`, those of `cut` for `cut`), each value checked
/// by the library's parser when the command line is parsed, before any file is read.
void add_map_arguments(CLI::App* cmd, liftmap::MapArguments& args, bool cut_only) {
  for (const liftmap::MapArgumentSpec& spec : liftmap::map_argument_specs()) {
    if (cut_only && !spec.in_cut) continue;
    const std::string name = spec.name;
    if (spec.is_flag) {
      // --no-normalize is the name "normalize" negated; the other flags set their option.
      const std::string value = spec.flag == "--no-" + name ? "false" : "true";
      cmd->add_flag_callback(
          spec.flag, [&args, name, value] { liftmap::set_map_argument(args, name, value); }, spec.help);
      continue;
    }
    const CLI::Validator check(
        [name](std::string& value) {
          liftmap::MapArguments scratch;
          return liftmap::set_map_argument_text(scratch, name, value);
        },
        "");
    CLI::Option* option = cmd->add_option_function<std::string>(
        spec.flag, [&args, name](const std::string& value) { liftmap::set_map_argument(args, name, value); },
        spec.help);
    option->check(check)->type_name(spec.type);
    if (const std::string d = default_text(args, name); !d.empty()) option->default_str(d);
  }
}

/// Inputs and options shared by `map` and `cut`.
struct PairJob {
  std::string path_a, path_b, landmarks_path, out_dir = "out";
  liftmap::MapArguments args;
  bool quiet = false;
};

void add_pair_options(CLI::App* cmd, PairJob& job) {
  cmd->add_option("A", job.path_a, "Mesh A (.off, .obj, .ply, .stl)")->required();
  cmd->add_option("B", job.path_b, "Mesh B")->required();
  cmd->add_option("-l,--landmarks", job.landmarks_path, "Landmark file: 'iA iB' per line")->required();
  cmd->add_option("-o,--out", job.out_dir, "Output folder (created if missing)")->capture_default_str();
  cmd->add_flag("-q,--quiet", job.quiet, "No progress on stderr");
}

/// Progress lines of the pipeline on stderr, timed from now; empty if quiet.
std::function<void(const std::string&, const std::string&)> progress_printer(bool quiet) {
  if (quiet) return {};
  const auto t0 = std::chrono::steady_clock::now();
  return [t0](const std::string& stage, const std::string& message) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "[%7.2f s] %-8s %s\n", t, stage.c_str(), message.c_str());
  };
}

int run_map(const PairJob& job) {
  const liftmap::MapResult map = liftmap::map_files(job.path_a, job.path_b, job.landmarks_path, job.out_dir, job.args,
                                                    progress_printer(job.quiet), print_warning);
  if (!map.verification.passed) {
    std::cerr << "liftmap: verification failed (outputs kept in " << job.out_dir
              << ", see report.json): " << map.verification.failures.front() << '\n';
    return liftmap::kExitPipeline;
  }
  if (!job.quiet) {
    std::fprintf(stderr, "liftmap: map written to %s (total %.2f s; distortion of f: mean %.3f, max %.3f)%s\n",
                 job.out_dir.c_str(), map.seconds.total, map.distortion_f.mean, map.distortion_f.max,
                 map.flattening.stop_reason.empty() ? "" : "; the flattening stopped early (report.json: stop_reason)");
  }
  return liftmap::kExitOk;
}

int run_cut(const PairJob& job) {
  liftmap::MapOptions options = liftmap::map_options(job.args);
  const liftmap::MapInputs in = liftmap::read_map_inputs(job.path_a, job.path_b, job.landmarks_path, job.out_dir,
                                                         job.args.fix_orientation, print_warning);
  liftmap::require_mappable(liftmap::check_mesh(in.a.V, in.a.F), job.path_a);
  liftmap::require_mappable(liftmap::check_mesh(in.b.V, in.b.F), job.path_b);
  options.progress = progress_printer(job.quiet);
  if (options.progress) options.progress("cut", "cutting both meshes to disks");
  const liftmap::CutResult cut =
      liftmap::cut_meshes(in.a.V, in.a.F, in.b.V, in.b.F, in.landmarks.a, in.landmarks.b, options.cut);
  // The texture coordinates are the common Tutte start of the flattening: the cut as the optimiser sees it.
  const liftmap::Mesh disk_a(cut.a.F_cut, static_cast<int>(cut.a.cut_to_refined.size()));
  const liftmap::Mesh disk_b(cut.b.F_cut, static_cast<int>(cut.b.cut_to_refined.size()));
  liftmap::FlatteningDisk m{&disk_a, cut.a.V(cut.a.cut_to_refined, Eigen::all), {}};
  liftmap::FlatteningDisk n{&disk_b, cut.b.V(cut.b.cut_to_refined, Eigen::all), {}};
  for (const auto& pair : cut.nu) {
    m.boundary.emplace_back(pair[0]);
    n.boundary.emplace_back(pair[1]);
  }
  options.flatten.max_iterations = 0;
  const liftmap::JointFlattenResult tutte = liftmap::joint_flatten(m, n, options.flatten);
  liftmap::write_cut(job.out_dir, cut, tutte.Phi, tutte.Psi);
  if (!job.quiet) {
    std::fprintf(stderr, "liftmap: cut written to %s: %zu tree edges, %zu boundary vertices per disk\n",
                 job.out_dir.c_str(), cut.tree.size(), cut.nu.size());
  }
  return liftmap::kExitOk;
}

/// `liftmap batch`: the manifest, the output folder and the map options every pair starts from.
struct BatchJob {
  std::string manifest, out_dir, shard = "0/1";
  int jobs = 1;
  liftmap::MapArguments args;
  bool quiet = false;
};

void add_batch_options(CLI::App* cmd, BatchJob& job) {
  cmd->add_option("MANIFEST", job.manifest,
                  "CSV with a header: mesh_a,mesh_b,landmarks[,name][,options of map...], one pair per line; "
                  "relative paths from the manifest's folder")
      ->required();
  cmd->add_option("-o,--out", job.out_dir, "Output folder: OUT/<name>/ per pair, OUT/summary.csv")->required();
  cmd->add_option("--shard", job.shard, "Map every n-th pair from the i-th (0-based), i/n, e.g. $SLURM_ARRAY_TASK_ID/8")
      ->check(CLI::Validator(
          [](std::string& value) {
            try {
              liftmap::parse_shard(value);
            } catch (const liftmap::UsageError&) {
              return "'" + value + "' is not i/n with 0 <= i < n";
            }
            return std::string();
          },
          "i/n"))
      ->capture_default_str();
  cmd->add_option("--jobs", job.jobs, "Pairs mapped at once, the threads divided between them")
      ->check(CLI::Range(1, liftmap::MapOptionLimits::max_threads()))
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", job.quiet, "No progress on stderr");
  add_map_arguments(cmd, job.args, false);
  cmd->get_option("--threads")
      ->description("Threads of all maps together, divided between the --jobs (default: all hardware threads)");
}

int run_batch(const BatchJob& job) {
  liftmap::map_options(job.args);  // the batch's own options, checked before the manifest is read
  const std::vector<liftmap::BatchPair> pairs = liftmap::read_manifest(job.manifest, job.args);
  liftmap::BatchOptions options;
  options.shard = liftmap::parse_shard(job.shard);
  options.jobs = job.jobs;
  options.threads = job.args.threads;
  options.warning = print_warning;
  if (!job.quiet) options.progress = [](const std::string& line) { std::cerr << "liftmap: batch: " << line << '\n'; };
  const liftmap::BatchResult r = liftmap::run_batch(pairs, job.out_dir, options);
  const liftmap::BatchCounts& s = r.summary;
  std::printf(
      "liftmap: batch: %d pairs in %s/summary.csv: %d ok, %d failed, %d pending; shard %s: %d pairs, %d mapped now, "
      "%d complete before, %d failed\n",
      s.pairs, job.out_dir.c_str(), s.ok, s.failed, s.pending, job.shard.c_str(), r.shard_pairs, r.mapped, r.skipped,
      r.shard_failed);
  return r.shard_failed > 0 ? liftmap::kExitBatchFailures : liftmap::kExitOk;
}

struct TransferJob {
  std::string map_path, onto_path, data_path, connectivity_path, out_path;
  bool exact = false;  ///< transfer mesh: map_path is a map's overlay.obj
};

/// A mesh read from `path`, as a map file applied to it names it.
liftmap::MeshOfMap mesh_of_map(const std::string& path, const liftmap::TriangleMesh& mesh) {
  return {path, liftmap::mesh_fingerprint(mesh.V.rows(), mesh.F)};
}

int run_transfer_attributes(const TransferJob& job) {
  liftmap::refuse_overwriting_inputs(job.out_path, {job.map_path, job.onto_path, job.data_path});
  const liftmap::TriangleMesh onto = liftmap::read_mesh(job.onto_path);
  const auto points = liftmap::read_map_file(job.map_path, mesh_of_map(job.onto_path, onto)).images;
  const Eigen::MatrixXd data = liftmap::read_attributes(job.data_path);
  if (data.rows() != onto.V.rows()) {
    throw liftmap::InvalidInputError(job.data_path + ": " + std::to_string(data.rows()) + " rows, but " +
                                     job.onto_path + " has " + std::to_string(onto.V.rows()) + " vertices");
  }
  liftmap::write_attributes(job.out_path, liftmap::interpolate_at(onto.F, data, points));
  return liftmap::kExitOk;
}

/// The mesh to place on ONTO and the points of ONTO its vertices go to: the source's connectivity through a
/// map file, or (--exact) the overlay, A's surface refined so that the map is affine on every triangle.
struct PlacedMesh {
  Eigen::MatrixXi F;
  std::vector<liftmap::SurfacePoint> points;
  Eigen::VectorXi containing;  ///< --exact: the face of ONTO holding each triangle
};

PlacedMesh mesh_to_place(const TransferJob& job, const liftmap::TriangleMesh& onto) {
  const liftmap::TriangleMesh source = liftmap::read_mesh(job.connectivity_path);
  if (job.exact) {
    liftmap::Overlay o =
        liftmap::read_overlay(job.map_path, source.V, source.F, onto.V, onto.F, {job.connectivity_path, job.onto_path});
    return {std::move(o.F), std::move(o.on_b), std::move(o.face_b)};
  }
  // Per source vertex: of the source only its vertex count matters (its faces may be any over those vertices).
  auto points = liftmap::read_map_file(job.map_path, mesh_of_map(job.onto_path, onto)).images;
  if (points.size() != static_cast<size_t>(source.V.rows())) {
    throw liftmap::InvalidInputError(job.map_path + ": " + std::to_string(points.size()) + " lines, but " +
                                     job.connectivity_path + " has " + std::to_string(source.V.rows()) + " vertices");
  }
  return {source.F, std::move(points), {}};
}

int run_transfer_mesh(const TransferJob& job) {
  std::vector<std::string> inputs = {job.map_path, job.onto_path, job.connectivity_path};
  if (job.exact) {
    for (const std::string& table : liftmap::overlay_table_paths(job.map_path)) inputs.push_back(table);
  }
  liftmap::refuse_overwriting_inputs(job.out_path, inputs);
  const liftmap::TriangleMesh onto = liftmap::read_mesh(job.onto_path);
  const PlacedMesh source = mesh_to_place(job, onto);
  const auto& points = source.points;
  const Eigen::MatrixXd placed = liftmap::interpolate_at(onto.F, onto.V, points);
  liftmap::write_mesh(job.out_path, placed, source.F);
  // Folded triangles: reported and listed (one face index per line) next to the output, never silently.
  int rounding_level = 0;
  const std::vector<int> folded =
      liftmap::folded_faces(source.F, placed, onto.V, onto.F, points, source.containing, &rounding_level);
  const std::string folded_path = job.out_path + ".folded.txt";
  liftmap::refuse_overwriting_inputs(folded_path, inputs);
  std::ofstream list(folded_path);
  list << "# faces of " << job.connectivity_path << " folded against the surface of " << job.onto_path << ": "
       << folded.size() << " of " << source.F.rows() << "\n";
  for (const int f : folded) list << f << "\n";
  if (!list) throw liftmap::IoError(folded_path + ": cannot write file");
  std::fprintf(stderr, "liftmap: %zu of %lld transferred triangles are folded against %s (listed in %s)\n",
               folded.size(), static_cast<long long>(source.F.rows()), job.onto_path.c_str(), folded_path.c_str());
  if (rounding_level > 0) {
    std::fprintf(stderr,
                 "liftmap: %d triangles are thinner than double precision shows (area below 1e-12 of their face's: "
                 "edges of the two meshes nearly coincide there)\n",
                 rounding_level);
  }
  return liftmap::kExitOk;
}

/// `liftmap transfer texture`: the overlay (a map folder or its overlay.obj), both textured meshes and the outputs.
struct TextureJob {
  std::string map_path, from_path, onto_path, texture_path, out_path;
  int size = 0;
  liftmap::BakeSettings settings;
  bool clamp = false;
};

/// The overlay OBJ of a map folder, or the path itself if it is a file.
std::string overlay_path_of(const std::string& map_path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(map_path, ec)) return map_path;
  std::string obj = (std::filesystem::path(map_path) / "overlay.obj").string();
  if (!std::filesystem::exists(obj, ec)) {
    throw liftmap::IoError(map_path + ": no overlay.obj in this folder (the output of `liftmap map`)");
  }
  return obj;
}

/// The image of A's texture: --texture, or the map_Kd of A's material.
std::string texture_path_of(const TextureJob& job, const liftmap::TexturedMesh& a) {
  if (!job.texture_path.empty()) return job.texture_path;
  if (!a.texture_path.empty()) return a.texture_path;
  const std::string why = a.material_file.empty() ? "it has no mtllib"
                          : std::filesystem::exists(a.material_file)
                              ? "its material file " + a.material_file + " has no map_Kd"
                              : "its material file " + a.material_file + " does not exist";
  throw liftmap::IoError(job.from_path + ": no texture image (" + why + "); give one with --texture");
}

/// The baked PNG, and B with its UVs at STEM.obj and STEM.mtl using it (file names relative to the OBJ's folder).
void write_baked(const std::string& png, const std::string& stem, const liftmap::Image& image,
                 const liftmap::TexturedMesh& b) {
  liftmap::write_png(png, image);
  liftmap::OutputFile mtl(stem + ".mtl");
  std::fprintf(mtl.get(), "newmtl material\nKd 1 1 1\nmap_Kd %s\n",
               std::filesystem::path(png).filename().string().c_str());
  mtl.close();
  liftmap::write_obj_with_uv(stem + ".obj", b.V, b.F, b.UV, b.FT,
                             std::filesystem::path(stem + ".mtl").filename().string());
}

int run_transfer_texture(TextureJob job) {
  std::string ext = std::filesystem::path(job.out_path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png")
    throw liftmap::UsageError(job.out_path + ": the baked texture is written as PNG: -o must end in .png");
  const std::string overlay_obj = overlay_path_of(job.map_path);
  const liftmap::TexturedMesh a = liftmap::read_obj_with_uv(job.from_path);
  const liftmap::TexturedMesh b = liftmap::read_obj_with_uv(job.onto_path);
  const std::string texture_path = texture_path_of(job, a);
  const auto tables = liftmap::overlay_table_paths(overlay_obj);
  // B's OBJ and MTL next to the PNG, named after it.
  const std::filesystem::path out(job.out_path);
  const std::string stem = (out.parent_path() / out.stem()).string();
  const std::vector<std::string> inputs{overlay_obj, tables[0], tables[1], job.from_path, job.onto_path, texture_path};
  for (const std::string& o : {job.out_path, stem + ".obj", stem + ".mtl"})
    liftmap::refuse_overwriting_inputs(o, inputs);
  const liftmap::Overlay overlay =
      liftmap::read_overlay(overlay_obj, a.V, a.F, b.V, b.F, {job.from_path, job.onto_path});
  const liftmap::Image texture = liftmap::read_image(texture_path);
  if (!out.parent_path().empty()) {
    std::error_code ec;
    std::filesystem::create_directories(out.parent_path(), ec);
    if (ec) throw liftmap::IoError(out.parent_path().string() + ": cannot create the output folder: " + ec.message());
  }
  job.settings.width = job.settings.height = job.size;
  job.settings.repeat = !job.clamp;
  const liftmap::BakeResult baked = liftmap::bake_texture(overlay, a, texture, b, job.settings);
  write_baked(job.out_path, stem, baked.image, b);
  std::fprintf(stderr, "liftmap: %d chart texels and %d gutter texels of %d x %d baked into %s (mesh %s.obj)\n",
               baked.chart_texels, baked.gutter_texels, baked.image.width, baked.image.height, job.out_path.c_str(),
               stem.c_str());
  return liftmap::kExitOk;
}

int run_eval(const std::string& map_path, const std::string& truth_path, const std::string& target_path) {
  const liftmap::TriangleMesh target = liftmap::read_mesh(target_path);
  const liftmap::MeshOfMap onto = mesh_of_map(target_path, target);
  const liftmap::MapFile map = liftmap::read_map_file(map_path, onto);
  const liftmap::MapFile truth = liftmap::read_map_file(truth_path, onto);
  // Compared per source vertex: the sources' vertices must be the same, not their faces.
  const bool sources_differ =
      map.meshes.source && truth.meshes.source && map.meshes.source->vertices != truth.meshes.source->vertices;
  if (map.images.size() != truth.images.size() || sources_differ) {
    throw liftmap::InvalidInputError(
        map_path + ": " + std::to_string(map.images.size()) + " map lines" +
        (map.meshes.source ? " from a mesh with " + to_string(*map.meshes.source) : std::string()) + ", but " +
        truth_path + " has " + std::to_string(truth.images.size()) +
        (truth.meshes.source ? " from a mesh with " + to_string(*truth.meshes.source) : std::string()) +
        ": the maps do not start from the same mesh");
  }
  const liftmap::MapDifference d = liftmap::compare_maps(target.V, target.F, map.images, truth.images);
  std::printf("mean error: %.6g\nmax error:  %.6g (source vertex %d)\n(Euclidean distance on %s / sqrt(area))\n",
              d.mean, d.max, d.worst_vertex, target_path.c_str());
  return liftmap::kExitOk;
}

int run(int argc, char** argv) {
  CLI::App app{
      "liftmap: continuous, bijective, low-distortion maps between two genus-0 triangle meshes\n"
      "(Aigerman, Poranne, Lipman: Lifted Bijections for Low Distortion Surface Mappings, 2014)"};
  app.name("liftmap");
  app.failure_message(usage_message);  // before the subcommands, which inherit it
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

  PairJob map_job;
  CLI::App* map = app.add_subcommand("map", "Compute the bijective map between A and B and write it to a folder");
  add_pair_options(map, map_job);
  add_map_arguments(map, map_job.args, false);

  PairJob cut_job;
  CLI::App* cut = app.add_subcommand("cut", "Cut A and B to disks along a common tree (inspect a cut before mapping)");
  add_pair_options(cut, cut_job);
  add_map_arguments(cut, cut_job.args, true);

  BatchJob batch_job;
  CLI::App* batch = app.add_subcommand(
      "batch", "Map every pair of a manifest into OUT/<name>/ as `map` does: resumable, sharded, several at once");
  add_batch_options(batch, batch_job);

  TransferJob transfer_job;
  CLI::App* transfer = app.add_subcommand("transfer", "Carry data from one mesh to the other through a map file");
  transfer->require_subcommand(1);
  CLI::App* transfer_attributes = transfer->add_subcommand(
      "attributes",
      "Per-vertex attributes of mesh ONTO, interpolated at every point of MAP (e.g. B_to_A.txt with "
      "--onto A gives A's attributes on B's vertices)");
  CLI::App* transfer_mesh = transfer->add_subcommand(
      "mesh",
      "Mesh transfer: the connectivity of the map's source placed on ONTO (e.g. A_to_B.txt with --onto B "
      "and --connectivity A)");
  for (CLI::App* cmd : {transfer_attributes, transfer_mesh}) {
    cmd->add_option("map", transfer_job.map_path, "Map file: 'face b0 b1 b2' per line, faces of ONTO")->required();
    cmd->add_option("--onto", transfer_job.onto_path, "The mesh the map's points lie on")->required();
    cmd->add_option("-o,--out", transfer_job.out_path, "Output file")->required();
  }
  transfer_attributes->add_option("--data", transfer_job.data_path, "One row of numbers per vertex of ONTO")
      ->required();
  transfer_mesh->add_option("--connectivity", transfer_job.connectivity_path, "The map's source mesh")->required();
  transfer_mesh->add_flag("--exact", transfer_job.exact,
                          "MAP is a map folder's overlay.obj: write the source's surface refined by the overlay, "
                          "on which the map is affine (no triangle folds)");

  TextureJob texture_job;
  CLI::App* transfer_texture = transfer->add_subcommand(
      "texture",
      "Bake A's texture into B's own UV atlas through a map: a PNG, and B's OBJ/MTL using it (FROM and ONTO: the "
      "map's A and B as OBJ with vt)");
  transfer_texture
      ->add_option("map", texture_job.map_path, "The map's output folder (its overlay.obj) or an overlay OBJ")
      ->required();
  transfer_texture->add_option("--from", texture_job.from_path, "Mesh A as OBJ with vt (its MTL's map_Kd: the texture)")
      ->required();
  transfer_texture->add_option("--onto", texture_job.onto_path, "Mesh B as OBJ with vt: the atlas baked into")
      ->required();
  transfer_texture->add_option("--texture", texture_job.texture_path, "A's texture (PNG or JPEG) instead of map_Kd");
  transfer_texture->add_option("--size", texture_job.size, "Width and height of the baked texture (default: A's)")
      ->check(CLI::Range(1, 8192));
  transfer_texture->add_option("--gutter", texture_job.settings.gutter, "Texels filled around every chart")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  transfer_texture->add_flag("--clamp", texture_job.clamp,
                             "Clamp A's texture at its edges instead of repeating it (GL_CLAMP_TO_EDGE)");
  transfer_texture->add_option("-o,--out", texture_job.out_path, "The baked PNG; OUT.obj and OUT.mtl go next to it")
      ->required();

  std::string eval_map, eval_truth, eval_target;
  CLI::App* eval = app.add_subcommand("eval", "Compare a map file with a ground-truth map file into the same mesh");
  eval->add_option("map", eval_map, "Map file")->required();
  eval->add_option("truth", eval_truth, "Ground-truth map file, same format")->required();
  eval->add_option("--target", eval_target, "The mesh both maps point into")->required();

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
  if (*transfer_attributes) return run_transfer_attributes(transfer_job);
  if (*transfer_mesh) return run_transfer_mesh(transfer_job);
  if (*transfer_texture) return run_transfer_texture(texture_job);
  if (*eval) return run_eval(eval_map, eval_truth, eval_target);
  if (*batch) return run_batch(batch_job);
  for (auto [cmd, job] : {std::pair{map, &map_job}, std::pair{cut, &cut_job}}) {
    if (!*cmd) continue;
    if (job->args.threads) omp_set_num_threads(*job->args.threads);
    return cmd == map ? run_map(*job) : run_cut(*job);
  }
  return liftmap::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  liftmap_app::run_with_passive_openmp_waits(argv);
  liftmap_app::keep_freed_memory();
  try {
    return run(argc, argv);
  } catch (...) {
    std::string message;
    const int code = liftmap::exit_code_of(std::current_exception(), message);
    std::cerr << "liftmap: " << message << '\n';
    return code;
  }
}
