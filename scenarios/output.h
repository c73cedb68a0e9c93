// Writing the program's output files: a file is written whole or not at all, and a failure
// (a folder that cannot be created, a full disk) is an OutputError naming the file.
#ifndef FOGNAV_SCENARIOS_OUTPUT_H_
#define FOGNAV_SCENARIOS_OUTPUT_H_

#include <string>

#include "perception/mapping.h"

namespace fognav::scenarios {

// An output file or folder that cannot be written; the program maps it to exit code 5.
using perception::OutputError;

// Creates `dir` and its parents if missing. Throws OutputError naming dir if it cannot.
void MakeOutputFolder(const std::string& dir);

// Writes `text` to `path` through a temporary file beside it (path + ".tmp"), flushed to the
// disk, then renamed over `path`: a reader sees the old file or the whole new one, never a
// part. Throws OutputError naming the file if it cannot; the temporary file is removed then.
void WriteFileAtomically(const std::string& path, const std::string& text);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_OUTPUT_H_
