// The provenance (provenance/provenance.h) embedded in the output formats that
// are not plain JSON objects: the hits file's first line, a VCD $comment, the
// timeline's otherData, a markdown HTML comment. JSON outputs carry it as a
// top-level "provenance" member; traces, PLY scenes and PNG images through
// their writers' options.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace vbsim::cli {

/// Line 1 of a hits file: {"format":"vbsim-hits","version":1,"provenance":{...}}.
std::string hits_header_line(const nlohmann::json& provenance);

/// "<!-- vbsim-provenance {...} -->", the last line of a generated markdown page.
std::string markdown_provenance(const nlohmann::json& provenance);

/// Puts "$comment vbsim-provenance {...} $end" before the VCD's first section.
/// Rewrites the file through a temporary next to it.
void add_vcd_provenance(const std::string& vcd_path, const nlohmann::json& provenance);

/// Adds "otherData": {"provenance": ...} to a Chrome trace-event JSON file (an
/// object: its first member), copying the file through a temporary next to it.
void add_timeline_provenance(const std::string& path, const nlohmann::json& provenance);

}  // namespace vbsim::cli
