#include "io/output_paths.h"

#include <filesystem>

#include <fmt/format.h>

namespace vbsim {

namespace fs = std::filesystem;

namespace {

/// The path `path` leads to once every symbolic link is followed, also a
/// dangling one (whose target a write would create), normalised.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) break;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return fs::weakly_canonical(p, ec);
}

/// Whether `a` and `b` name the same file: the same inode when both exist,
/// else the same resolved path (an output not created yet).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  return resolved(a) == resolved(b);
}

/// Outputs written in place (devices, FIFOs) may be shared: nothing is replaced.
bool is_special(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  return !ec && fs::exists(st) && !fs::is_regular_file(st);
}

}  // namespace

void check_output_paths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty() || is_special(out.path)) continue;
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && same_file(out.path, in.path))
        throw OutputPathError(fmt::format("{}: {} is also the {} this run reads; refusing to overwrite it", out.role,
                                          out.path, in.role));
    for (size_t k = 0; k < i; ++k)
      if (!outputs[k].path.empty() && same_file(out.path, outputs[k].path))
        throw OutputPathError(
            fmt::format("{}: {} is also the output of {}; give each output its own file", out.role, out.path,
                        outputs[k].role));
  }
}

}  // namespace vbsim
