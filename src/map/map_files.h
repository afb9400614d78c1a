#pragma once
/// `liftmap map` on files: read the pair, prepare the output folder, map, write every output file. The CLI's `map`
/// and every pair of `liftmap batch` (CLI and Python) go through it, so that they write the same files.

#include <functional>
#include <string>

#include "map/map_arguments.h"
#include "map/map_meshes.h"
#include "map/write_map.h"

namespace liftmap {

/// Called with one line of text (a warning, without the "liftmap: " prefix); empty: dropped.
using MessageSink = std::function<void(const std::string&)>;

/// Reads the inputs of `liftmap map` or `liftmap cut` and prepares `out_dir` for the files of `map` (which include
/// those of `cut`: a `cut` into a map's folder removes the map's files too, so the folder never mixes two runs).
/// The meshes are validated later, once, by map_meshes (or by the caller).
/// \param fix_orientation reverse the faces of an inside-out mesh (negative signed volume), reported to `warning`,
///        instead of leaving it to the validation to reject
/// \return the inputs, named by their paths as given
/// \throw IoError if a file cannot be read or the folder cannot be written; InvalidInputError for an invalid
///        landmark file; UsageError if an output would overwrite an input (prepare_output_folder)
MapInputs read_map_inputs(const std::string& path_a, const std::string& path_b, const std::string& landmarks_path,
                          const std::string& out_dir, bool fix_orientation, const MessageSink& warning = {});

/// What `liftmap map A B -l LANDMARKS -o OUT` computes and writes: reads the pair (read_map_inputs), maps it with
/// the options `args` (map_options; the meshes named by their paths), and writes every file of map_output_names()
/// into `out_dir`, report.json last, also when the verification fails (the caller decides: the CLI exits with 5).
/// \param progress as MapOptions::progress (empty: silent)
/// \return the map, its verification included
/// \throw UsageError for an option out of its range or an output that would overwrite an input; IoError,
///        InvalidInputError as read_map_inputs and map_meshes; PipelineError if a stage fails
MapResult map_files(const std::string& path_a, const std::string& path_b, const std::string& landmarks_path,
                    const std::string& out_dir, const MapArguments& args,
                    const std::function<void(const std::string&, const std::string&)>& progress = {},
                    const MessageSink& warning = {});

}  // namespace liftmap
