#include "capture/raw_capture_files.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

#include <fmt/format.h>

namespace vbsim::capture {

namespace fs = std::filesystem;

std::map<ProcessImage, ProcessFiles> find_capture_files(const std::string& dir) {
  static const std::regex rays_name(R"(rays-(\d+)\.(\d+)-(\d+)\.bin)");
  static const std::regex scene_name(R"(scene-(\d+)\.(\d+)-(\d+)-(\d+)\.bin)");
  static const std::regex summary_name(R"(process-(\d+)\.(\d+)\.txt)");
  static const std::regex refusal_name(R"(refused-(\d+)\.(\d+)\.txt)");
  std::map<ProcessImage, ProcessFiles> out;
  auto image_of = [](const std::smatch& m) {
    return ProcessImage{std::stol(m[1]), static_cast<unsigned>(std::stoul(m[2]))};
  };
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string(), path = entry.path().string();
    std::smatch m;
    if (std::regex_match(name, m, rays_name)) {
      out[image_of(m)].ray_files[std::stoi(m[3])] = path;
    } else if (std::regex_match(name, m, scene_name)) {
      out[image_of(m)].scenes[{static_cast<uint32_t>(std::stoul(m[3])), static_cast<uint32_t>(std::stoul(m[4]))}] =
          path;
    } else if (std::regex_match(name, m, summary_name)) {
      out[image_of(m)].summary = path;
    } else if (std::regex_match(name, m, refusal_name)) {
      out[image_of(m)].refusal = path;
    }
  }
  if (ec) throw std::runtime_error(fmt::format("{}: cannot read the capture directory: {}", dir, ec.message()));
  for (auto& [id, p] : out) p.id = id;
  return out;
}

std::string read_refusals(const std::string& dir) {
  constexpr std::size_t kMaxReason = 2000;  // a reason is one line; more is not the shim's
  std::string all;
  for (const auto& [id, p] : find_capture_files(dir)) {
    if (p.refusal.empty()) continue;
    std::ifstream in(p.refusal);
    std::string reason;
    std::getline(in, reason);
    if (reason.size() > kMaxReason) reason.resize(kMaxReason);
    if (reason.empty()) reason = "(no reason given)";
    all += fmt::format("{}process {}: {}", all.empty() ? "" : "; ", id.pid, reason);
  }
  return all;
}

std::map<std::string, uint64_t> read_process_summary(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the process summary", path));
  std::map<std::string, uint64_t> values;
  std::string key;
  uint64_t value;
  while (in >> key >> value) values[key] = value;
  return values;
}

MappedRays::MappedRays(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    throw std::runtime_error(fmt::format("{}: cannot stat: {}", path, std::strerror(errno)));
  }
  bytes_ = static_cast<std::size_t>(st.st_size);
  if (bytes_ % sizeof(RawRay) != 0) {
    ::close(fd);
    throw std::runtime_error(fmt::format("{}: {} bytes is not a whole number of {}-byte ray records (a truncated capture)",
                                         path, bytes_, sizeof(RawRay)));
  }
  if (bytes_ > 0) {
    map_ = ::mmap(nullptr, bytes_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (map_ == MAP_FAILED) {
      map_ = nullptr;
      ::close(fd);
      throw std::runtime_error(fmt::format("{}: cannot map: {}", path, std::strerror(errno)));
    }
  }
  ::close(fd);
  rays_ = static_cast<const RawRay*>(map_);
  count_ = bytes_ / sizeof(RawRay);
}

MappedRays::MappedRays(MappedRays&& o) noexcept
    : rays_(o.rays_), count_(o.count_), map_(o.map_), bytes_(o.bytes_) {
  o.map_ = nullptr;
  o.rays_ = nullptr;
  o.count_ = o.bytes_ = 0;
}

MappedRays::~MappedRays() {
  if (map_) ::munmap(map_, bytes_);
}

}  // namespace vbsim::capture
