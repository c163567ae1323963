#include "scene/ply_header.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>

#include "scene/scene.h"

namespace vbsim {

namespace {

struct TypeName {
  const char* name;
  PlyType type;
};
constexpr TypeName kTypeNames[] = {
    {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
    {"uint8", PlyType::Uint8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
    {"ushort", PlyType::Uint16}, {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
    {"int32", PlyType::Int32},   {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
    {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
    {"float64", PlyType::Float64}};

bool parse_type(const std::string& word, PlyType& out) {
  for (const TypeName& t : kTypeNames)
    if (word == t.name) {
      out = t.type;
      return true;
    }
  return false;
}

/// Splits a header line at spaces and tabs.
std::vector<std::string> words(std::string_view line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.emplace_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

}  // namespace

std::size_t ply_type_bytes(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::Uint8: return 1;
    case PlyType::Int16: case PlyType::Uint16: return 2;
    case PlyType::Int32: case PlyType::Uint32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

int PlyElement::find(std::string_view wanted) const {
  for (size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == wanted) return static_cast<int>(i);
  return -1;
}

bool has_ply_magic(std::string_view bytes) {
  return bytes.size() >= 4 && bytes.substr(0, 3) == "ply" && (bytes[3] == '\n' || bytes[3] == '\r');
}

PlyHeader parse_ply_header(std::string_view bytes, const std::string& path) {
  PlyHeader h;
  int line_number = 0;
  const auto fail = [&](const std::string& why) -> void {
    throw SceneError(fmt::format("scene '{}': PLY header line {}: {}", path, line_number, why));
  };
  bool format_seen = false;
  size_t at = 0;
  while (true) {
    ++line_number;
    const size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos || end >= kMaxPlyHeaderBytes) {
      if (bytes.size() < kMaxPlyHeaderBytes && end == std::string_view::npos)
        fail("the file ends inside the header (no end_header line)");
      fail(fmt::format("no end_header within the first {} bytes", kMaxPlyHeaderBytes));
    }
    std::string_view line = bytes.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_number == 1) {
      if (line != "ply") fail("not a PLY file: the first line must be 'ply'");
      continue;
    }
    const std::vector<std::string> w = words(line);
    if (w.empty()) fail("empty line");
    const std::string& key = w[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      if (w.size() != 1) fail("text after end_header");
      if (!format_seen) fail("no format line");
      h.data_offset = at;
      return h;
    }
    if (key == "format") {
      if (format_seen) fail("a second format line");
      if (w.size() != 3 || w[2] != "1.0") fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (w[1] == "ascii") h.format = PlyFormat::Ascii;
      else if (w[1] == "binary_little_endian") h.format = PlyFormat::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian") h.format = PlyFormat::BinaryBigEndian;
      else fail(fmt::format("unknown format '{}'", w[1]));
      format_seen = true;
    } else if (key == "element") {
      if (w.size() != 3) fail("expected 'element NAME COUNT'");
      for (const PlyElement& e : h.elements)
        if (e.name == w[1]) fail(fmt::format("a second element '{}'", w[1]));
      const std::string& n = w[2];
      char* stop = nullptr;
      errno = 0;
      const unsigned long long count = std::strtoull(n.c_str(), &stop, 10);
      if (n.empty() || n[0] < '0' || n[0] > '9' || *stop != '\0' || errno == ERANGE)
        fail(fmt::format("element '{}': count '{}' is not a non-negative integer", w[1], n));
      h.elements.push_back({w[1], count, {}});
    } else if (key == "property") {
      if (h.elements.empty()) fail("a property before any element");
      PlyProperty p;
      if (w.size() == 5 && w[1] == "list") {
        p.is_list = true;
        if (!parse_type(w[2], p.count_type) || !ply_type_is_integer(p.count_type))
          fail(fmt::format("list count type '{}' is not an integer type", w[2]));
        if (!parse_type(w[3], p.type)) fail(fmt::format("unknown type '{}'", w[3]));
        p.name = w[4];
      } else if (w.size() == 3 && w[1] != "list") {
        if (!parse_type(w[1], p.type)) fail(fmt::format("unknown type '{}'", w[1]));
        p.name = w[2];
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      PlyElement& e = h.elements.back();
      if (e.find(p.name) >= 0) fail(fmt::format("element '{}': a second property '{}'", e.name, p.name));
      e.properties.push_back(std::move(p));
    } else {
      fail(fmt::format("unknown keyword '{}'", key));
    }
  }
}

}  // namespace vbsim
