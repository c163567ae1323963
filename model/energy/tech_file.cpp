#include "energy/tech_file.h"

#include <algorithm>
#include <cmath>

#include "io/data_dir.h"
#include "replay/config_fields.h"

namespace vbsim {

const std::array<const char*, kOpKinds> kOpKindNames = {
    "fp32_add",     "fp32_mul",    "fp32_fma",  "fp32_div",    "fp32_sqrt",
    "fp32_compare", "fp32_select", "int32_add", "int32_shift", "fp32_int_convert"};

std::array<int, kOpKinds> op_count_array(const OpCounts& c) {
  return {c.fadd, c.fmul, c.fma, c.fdiv, c.fsqrt, c.fcmp, c.fsel, c.iadd, c.ishift, c.cvt};
}

namespace {

using config_fields::fail;
using config_fields::Fields;

/// The largest figure a technology file may give (pJ, mm2, W/mm2): a billion
/// times the figures of any real node, and small enough that a run's totals
/// (figures times counts up to 2^64) stay finite in double.
constexpr double kMaxFigure = 1e9;
/// The largest SRAM size of the table, bytes (1 TiB).
constexpr double kMaxSramBytes = 1099511627776.0;

/// A figure {"value": number in [0, kMaxFigure], "source": string}; the value is required.
double figure(Fields& parent, const std::string& key) {
  const nlohmann::json* v = parent.get(key);
  const std::string field = parent.path(key);
  if (!v) fail(parent.file(), field, "missing");
  Fields f(*v, parent.file(), field);
  double value = -1;
  if (!f.get("value")) fail(parent.file(), field + ".value", "missing");
  f.number("value", value);
  if (!(value >= 0)) fail(parent.file(), field + ".value", "must be >= 0");
  if (value > kMaxFigure)
    fail(parent.file(), field + ".value", fmt::format("{:g} is beyond {:g}: no node's figure is that large", value, kMaxFigure));
  if (const auto* s = f.get("source"); s && !s->is_string()) fail(parent.file(), field + ".source", "must be a string");
  return value;
}

}  // namespace

TechFile load_tech_file(const std::string& path) {
  const nlohmann::json j = read_config_json(path);
  TechFile t;
  t.path = path;
  {
    Fields f(j, path, "");
    if (const auto* n = f.get("name")) {
      if (!n->is_string()) fail(path, "name", "must be a string");
      t.name = n->get<std::string>();
    }
    f.get("notes");
    f.number("node_nm", t.node_nm);
    {
      const nlohmann::json* e = f.get("energy_pj");
      if (!e) fail(path, "energy_pj", "missing");
      Fields ef(*e, path, "energy_pj");
      for (int k = 0; k < kOpKinds; ++k) t.op_pj[k] = figure(ef, kOpKindNames[k]);
      t.register_bit_pj = figure(ef, "register_bit");
    }
    {
      const nlohmann::json* a = f.get("area_mm2");
      if (!a) fail(path, "area_mm2", "missing");
      Fields af(*a, path, "area_mm2");
      for (int k = 0; k < kOpKinds; ++k) t.op_mm2[k] = figure(af, kOpKindNames[k]);
      t.register_bit_mm2 = figure(af, "register_bit");
      t.sram_bit_mm2 = figure(af, "sram_bit");
    }
    const nlohmann::json* s = f.get("sram_read_64bit_pj");
    if (!s || !s->is_array() || s->empty())
      fail(path, "sram_read_64bit_pj", "must be a non-empty list of {bytes, value, source}");
    for (size_t i = 0; i < s->size(); ++i) {
      const std::string field = fmt::format("sram_read_64bit_pj[{}]", i);
      Fields pf((*s)[i], path, field);
      SramPoint p{-1, -1};
      if (!pf.get("bytes")) fail(path, field + ".bytes", "missing");
      if (!pf.get("value")) fail(path, field + ".value", "missing");
      pf.number("bytes", p.bytes);
      pf.number("value", p.pj);
      if (const auto* src = pf.get("source"); src && !src->is_string())
        fail(path, field + ".source", "must be a string");
      if (!(p.bytes >= 1 && p.bytes <= kMaxSramBytes) || p.bytes != std::floor(p.bytes))
        fail(path, field + ".bytes", fmt::format("{:g} must be a whole number of bytes from 1 to 2^40", p.bytes));
      if (!(p.pj > 0)) fail(path, field + ".value", "must be > 0");
      if (p.pj > kMaxFigure)
        fail(path, field + ".value", fmt::format("{:g} is beyond {:g}: no node's figure is that large", p.pj, kMaxFigure));
      if (!t.sram.empty() && !(p.bytes > t.sram.back().bytes))
        fail(path, field + ".bytes", "sizes must be listed in ascending order, each once");
      t.sram.push_back(p);
    }
    t.dram_64bit_pj = figure(f, "dram_64bit_pj");
    t.leakage_w_per_mm2 = figure(f, "leakage_w_per_mm2");
  }
  return t;
}

std::string default_tech_path() { return tech_dir() + "/45nm.json"; }

double TechFile::energy_pj(const OpCounts& c) const {
  const std::array<int, kOpKinds> n = op_count_array(c);
  double e = 0;
  for (int k = 0; k < kOpKinds; ++k) e += n[k] * op_pj[k];
  return e;
}

double TechFile::area_mm2(const OpCounts& c) const {
  const std::array<int, kOpKinds> n = op_count_array(c);
  double a = 0;
  for (int k = 0; k < kOpKinds; ++k) a += n[k] * op_mm2[k];
  return a;
}

double TechFile::sram_64bit_pj(double bytes, bool* extrapolated) const {
  if (extrapolated) *extrapolated = bytes < sram.front().bytes || bytes > sram.back().bytes;
  if (sram.size() == 1) return sram.front().pj;
  // The segment [i, i + 1] that holds `bytes`, or the nearest end segment.
  size_t i = 0;
  while (i + 2 < sram.size() && bytes > sram[i + 1].bytes) ++i;
  const SramPoint& a = sram[i];
  const SramPoint& b = sram[i + 1];
  const double slope = std::log(b.pj / a.pj) / std::log(b.bytes / a.bytes);
  return a.pj * std::pow(bytes / a.bytes, slope);
}

}  // namespace vbsim
