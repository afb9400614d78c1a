#include "map/map_files.h"

#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "check/check_mesh.h"
#include "core/errors.h"
#include "core/thread_count_scope.h"
#include "io/landmarks.h"
#include "io/output_folder.h"
#include "io/read_mesh.h"

namespace liftmap {

namespace {

/// Reverses the faces of a mesh whose signed volume is negative and says so. Whether the mesh is mappable otherwise
/// is left to the one validation that follows.
bool fix_orientation(TriangleMesh& mesh, const std::string& path, const MessageSink& warning) {
  const std::optional<double> volume = reverse_if_inside_out(mesh.V, mesh.F);
  if (!volume) return false;
  if (warning) {
    warning(path + " is inside-out (signed volume " + figure(*volume) +
            "): its faces are reversed (--fix-orientation); map files into it keep the vertex order of its file");
  }
  return true;
}

}  // namespace

MapInputs read_map_inputs(const std::string& path_a, const std::string& path_b, const std::string& landmarks_path,
                          const std::string& out_dir, bool fix, const MessageSink& warning) {
  MapInputs in{path_a, path_b, {}, {}, {}, false, false};
  in.a = read_mesh(path_a);
  in.b = read_mesh(path_b);
  in.landmarks = read_landmarks(landmarks_path, in.a.V, in.a.F, in.b.V, in.b.F);
  if (warning) {
    for (const std::string& w : in.landmarks.warnings) warning(w);
  }
  if (fix) {
    in.reversed_a = fix_orientation(in.a, path_a, warning);
    in.reversed_b = fix_orientation(in.b, path_b, warning);
    in.landmarks = landmarks_across_reversal(std::move(in.landmarks), in.reversed_a, in.reversed_b);
  }
  prepare_output_folder(out_dir, map_output_names(), {path_a, path_b, landmarks_path});
  return in;
}

MapResult map_files(const std::string& path_a, const std::string& path_b, const std::string& landmarks_path,
                    const std::string& out_dir, const MapArguments& args,
                    const std::function<void(const std::string&, const std::string&)>& progress,
                    const MessageSink& warning) {
  MapOptions options = map_options(args);
  options.name_a = path_a;
  options.name_b = path_b;
  options.progress = progress;
  const MapInputs in = read_map_inputs(path_a, path_b, landmarks_path, out_dir, args.fix_orientation, warning);
  MapResult map = map_meshes(in.a.V, in.a.F, in.b.V, in.b.F, in.landmarks.a, in.landmarks.b, options);
  const ThreadCountScope threads(options.threads);  // the files and the pictures' rasteriser use the map's threads too
  write_map_folder(out_dir, map, in, map_report(map, in, options), args.pictures, options.progress);
  return map;
}

}  // namespace liftmap
