// PLY header: the text part of a PLY file up to `end_header`, parsed strictly
// (the polygon file format of Turk and Levoy, version 1.0): magic line,
// format (ascii, binary_little_endian, binary_big_endian), comment and
// obj_info lines, elements with their counts, scalar and list properties.
// Everything else is an error naming the header line. The header must end
// within kMaxPlyHeaderBytes, so a file without `end_header` is refused at once.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vbsim {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// The scalar types of PLY 1.0 (and their sized aliases int8 ... float64).
enum class PlyType : uint8_t { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

/// Bytes of one value of `t` in a binary file.
std::size_t ply_type_bytes(PlyType t);
bool ply_type_is_integer(PlyType t);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;        ///< the value type; for a list, the items' type
  bool is_list = false;
  PlyType count_type = PlyType::Uint8;    ///< a list's count type (an integer type)
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  /// Index of the property named `name`, or -1.
  int find(std::string_view name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  ///< byte offset of the first data byte, after "end_header\n"
};

constexpr std::size_t kMaxPlyHeaderBytes = 1 << 16;

/// Parses the header at the start of `bytes`. Throws SceneError
/// "scene 'PATH': PLY header line N: what is wrong".
PlyHeader parse_ply_header(std::string_view bytes, const std::string& path);

/// True when `bytes` starts with the PLY magic line ("ply" then a line end).
bool has_ply_magic(std::string_view bytes);

}  // namespace vbsim
