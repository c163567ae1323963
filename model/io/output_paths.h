// Output paths checked before any long work starts: an output that names an
// input (the same file by any path, hard link or symbolic link) or another
// output of the same run is refused, so that a run never destroys what it
// reads. Outputs that are not regular files (/dev/null, a FIFO) are not compared.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace vbsim {

struct OutputPathError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A file a run reads or writes, and how the user named it ("--hits", "trace").
struct NamedPath {
  std::string role;
  std::string path;  ///< empty: not given, skipped
};

/// Throws OutputPathError "option '--hits': FILE is also the trace ..." when
/// an output is the same file as an input or as an earlier output.
void check_output_paths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace vbsim
