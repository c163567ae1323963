#include "output_provenance.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace vbsim::cli {

std::string hits_header_line(const nlohmann::json& provenance) {
  const nlohmann::json j = {{"format", "vbsim-hits"}, {"version", 1}, {"provenance", provenance}};
  return j.dump() + "\n";
}

std::string markdown_provenance(const nlohmann::json& provenance) {
  std::string text = provenance.dump();
  // "--" cannot appear inside an HTML comment; JSON escapes keep the meaning.
  for (size_t at; (at = text.find("--")) != std::string::npos;) text.replace(at, 2, "-\\u002d");
  return "<!-- vbsim-provenance " + text + " -->\n";
}

void add_vcd_provenance(const std::string& vcd_path, const nlohmann::json& provenance) {
  const std::string tmp = vcd_path + ".provenance.tmp";
  {
    std::ifstream in(vcd_path, std::ios::binary);
    std::ofstream out(tmp, std::ios::binary);
    if (!in || !out) throw std::runtime_error(fmt::format("{}: cannot add the provenance comment", vcd_path));
    std::string text = provenance.dump();
    // A '$' inside could read as the section's end; JSON escapes keep the meaning.
    for (size_t at; (at = text.find('$')) != std::string::npos;) text.replace(at, 1, "\\u0024");
    out << "$comment vbsim-provenance " << text << " $end\n" << in.rdbuf();
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw std::runtime_error(fmt::format("{}: cannot write the provenance comment", vcd_path));
    }
  }
  std::filesystem::rename(tmp, vcd_path);
}

void add_timeline_provenance(const std::string& path, const nlohmann::json& provenance) {
  nlohmann::json j;
  {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(fmt::format("{}: cannot read the timeline back", path));
    j = nlohmann::json::parse(in);
  }
  j["otherData"] = {{"provenance", provenance}};
  std::ofstream out(path);
  if (!out || !(out << j.dump() << "\n") || !out.flush())
    throw std::runtime_error(fmt::format("{}: cannot write timeline", path));
}

}  // namespace vbsim::cli
