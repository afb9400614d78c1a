#pragma once
/// The folder a run writes its files into, prepared so that it never mixes two runs.

#include <string>
#include <vector>

namespace liftmap {

/// Prepares folder `dir` for a run that writes the files named `outputs` into it, before any computation:
/// creates it if missing, checks that a file can be created in it, refuses an input that an output would
/// overwrite, and removes the files of `outputs` a previous run left (a symlink among them is removed, never
/// the file it points to), so that a run that fails leaves none of the previous run's results.
/// \param outputs file names (no folder) the run may write
/// \param inputs paths of the run's input files
/// \throw IoError (exit 3) if the folder cannot be created, is not a folder, cannot be written, or an old
///        output cannot be removed; UsageError (exit 2) naming the input and the output if an input is one of
///        the outputs (the same path, through a symlink or a hard link)
void prepare_output_folder(const std::string& dir, const std::vector<std::string>& outputs,
                           const std::vector<std::string>& inputs);

/// Refuses an output file that is one of the inputs (the same path, through a symlink or a hard link).
/// \throw UsageError naming both
void refuse_overwriting_inputs(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace liftmap
