#include "output_provenance.h"

#include "io/atomic_output_file.h"

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
  const std::string written = finished_output_path(vcd_path);  // its name held until stdout has arrived
  if (!std::filesystem::is_regular_file(written)) return;  // /dev/null, a FIFO: nothing to read back
  std::ifstream in(written, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot add the provenance comment", vcd_path));
  AtomicOutputFile out(vcd_path, true);
  std::string text = provenance.dump();
  // A '$' inside could read as the section's end; JSON escapes keep the meaning.
  for (size_t at; (at = text.find('$')) != std::string::npos;) text.replace(at, 1, "\\u0024");
  out.stream() << "$comment vbsim-provenance " << text << " $end\n" << in.rdbuf();
  out.commit();
}

void add_timeline_provenance(const std::string& path, const nlohmann::json& provenance) {
  const std::string written = finished_output_path(path);  // its name held until stdout has arrived
  if (!std::filesystem::is_regular_file(written)) return;  // /dev/null, a FIFO: nothing to read back
  // Copied through, never parsed: a timeline may be far larger than memory.
  std::ifstream in(written, std::ios::binary);
  if (!in || in.get() != '{') throw std::runtime_error(fmt::format("{}: cannot read the timeline back", path));
  AtomicOutputFile out(path, true);
  out.stream() << "{\"otherData\":" << nlohmann::json{{"provenance", provenance}}.dump() << ",";
  if (in.peek() != std::char_traits<char>::eof()) out.stream() << in.rdbuf();
  out.commit();
}

}  // namespace vbsim::cli
