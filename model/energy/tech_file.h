// TechFile: the technology figures the energy and area model prices the
// datapath's operations with (docs/energy.md): energy per operation of each
// kind (op_counts.h) and per register bit, SRAM energy per 64-bit access by
// array size, DRAM energy per 64 bits, area per operator, per register bit and
// per SRAM bit, leakage per mm². A JSON file, every figure {"value", "source"};
// the shipped default is model/energy/tech/45nm.json.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "datapath/op_counts.h"

namespace vbsim {

/// The operator kinds of OpCounts, in the order of OpCounts' members.
constexpr int kOpKinds = 10;
/// Their names in a technology file: fp32_add, fp32_mul, ... (energy_pj and area_mm2).
extern const std::array<const char*, kOpKinds> kOpKindNames;
/// OpCounts as an array in the order of kOpKindNames.
std::array<int, kOpKinds> op_count_array(const OpCounts& c);

/// One tabulated SRAM array: energy of a 64-bit read of an array of `bytes`.
struct SramPoint {
  double bytes = 0, pj = 0;
};

struct TechFile {
  std::string path;  ///< the file it was read from
  std::string name;
  double node_nm = 0;
  std::array<double, kOpKinds> op_pj{};    ///< energy per operation
  std::array<double, kOpKinds> op_mm2{};   ///< area per operator
  double register_bit_pj = 0, register_bit_mm2 = 0;
  std::vector<SramPoint> sram;  ///< ascending sizes, at least one
  double sram_bit_mm2 = 0;
  double dram_64bit_pj = 0;
  double leakage_w_per_mm2 = 0;

  /// Energy of the operations `c`.
  double energy_pj(const OpCounts& c) const;
  /// Area of one operator per operation of `c` (a fully pipelined unit).
  double area_mm2(const OpCounts& c) const;
  /// Energy of a 64-bit access of an SRAM of `bytes`: between two tabulated
  /// sizes linear in log(energy) against log(size) (a power law through both);
  /// beyond the table the nearest segment's power law, `extrapolated` set (one
  /// tabulated size: that energy for every size).
  double sram_64bit_pj(double bytes, bool* extrapolated = nullptr) const;
};

/// Reads a technology file; ConfigError "FILE: field 'energy_pj.fp32_add.value': reason"
/// for a missing, unknown, negative or non-finite figure.
TechFile load_tech_file(const std::string& path);
/// The shipped default, model/energy/tech/45nm.json.
std::string default_tech_path();

}  // namespace vbsim
