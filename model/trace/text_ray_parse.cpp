#include "trace/text_ray_parse.h"

#include <fmt/format.h>

#include "trace/incomplete_reasons.h"
#include "trace/trace_header_json.h"
#include "trace/trace_json_values.h"
#include "trace/trace_validation.h"

namespace vbsim {

using json = nlohmann::json;

namespace {

const json* find_field(const json& object, const char* key) {
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const json& required_field(const json& object, const char* key) {
  const json* v = find_field(object, key);
  if (!v) throw TraceFieldProblem{key, "missing (required)"};
  return *v;
}

/// Reads the fields of one ray object into `out`; type and range of each
/// field only (the cross-field rules are check_trace_ray's). Throws TraceFieldProblem.
void parse_trace_ray(const json& object, TraceRay& out) {
  out = TraceRay{};
  out.id = json_int64(required_field(object, "id"), "id");
  if (const json* v = find_field(object, "parent")) out.parent = json_int64(*v, "parent");
  if (const json* v = find_field(object, "kind")) {
    std::string name = json_string(*v, "kind");
    if (!parse_ray_kind(name.c_str(), out.kind))
      throw TraceFieldProblem{"kind", fmt::format("unknown kind {} (expected primary, reflect, "
                                                  "refract, diffuse or shadow)",
                                                  v->dump())};
  }
  out.o = json_vec3(required_field(object, "o"), "o");
  out.d = json_vec3(required_field(object, "d"), "d");
  if (const json* v = find_field(object, "tmin")) out.tmin = json_float32(*v, "tmin");
  if (const json* v = find_field(object, "tmax"); v && !v->is_null())
    out.tmax = json_float32(*v, "tmax");
  if (const json* v = find_field(object, "parent_prim"))
    out.parent_prim = json_int32(*v, "parent_prim");
  if (const json* v = find_field(object, "parent_t")) {
    out.has_parent_t = true;
    out.parent_t = json_float32(*v, "parent_t");
  }
  if (const json* v = find_field(object, "parent_uv")) {
    float uv[2];
    json_float32_array(*v, "parent_uv", uv, 2);
    out.has_parent_uv = true;
    out.parent_u = uv[0];
    out.parent_v = uv[1];
  }
  if (const json* v = find_field(object, "parent_ns")) {
    out.has_parent_ns = true;
    out.parent_ns = json_vec3(*v, "parent_ns");
  }
  if (const json* v = find_field(object, "sign")) {
    int64_t sign = json_int64(*v, "sign");
    if (sign != 0 && sign != 1)
      throw TraceFieldProblem{"sign", fmt::format("must be 0 or 1, got {}", sign)};
    out.sign = static_cast<int8_t>(sign);
  }
  if (const json* v = find_field(object, "expect")) {
    if (!v->is_object())
      throw TraceFieldProblem{"expect", fmt::format("expected an object {{\"prim\": k, \"t\": t}}, "
                                                    "got {}", v->dump())};
    const json* prim = find_field(*v, "prim");
    if (!prim) throw TraceFieldProblem{"expect.prim", "missing (required in expect)"};
    out.has_expect = true;
    out.expect_prim = json_int32(*prim, "expect.prim");
    if (const json* t = find_field(*v, "t"); t && !t->is_null()) {
      out.has_expect_t = true;
      out.expect_t = json_double(*t, "expect.t");
    }
  }
  if (const json* v = find_field(object, "reference")) {
    if (!v->is_object())
      throw TraceFieldProblem{"reference", fmt::format("expected an object {{\"prim\": k, \"t\": t}} or "
                                                       "{{\"occluded\": true|false}}, got {}", v->dump())};
    out.has_reference = true;
    if (const json* occ = find_field(*v, "occluded")) {
      if (!occ->is_boolean()) throw TraceFieldProblem{"reference.occluded", "expected true or false"};
      out.reference_prim = occ->get<bool>() ? kReferenceOccluded : -1;
    } else {
      const json* prim = find_field(*v, "prim");
      if (!prim) throw TraceFieldProblem{"reference.prim", "missing (required in reference, unless occluded)"};
      out.reference_prim = json_int32(*prim, "reference.prim");
      if (const json* t = find_field(*v, "t"); t && !t->is_null()) {
        out.has_reference_t = true;
        out.reference_t = json_float32(*t, "reference.t");
      }
    }
  }
  if (const json* v = find_field(object, "mask")) out.mask = parse_ray_mask(*v);
  if (const json* v = find_field(object, "incomplete")) {
    if (!v->is_array())
      throw TraceFieldProblem{"incomplete", fmt::format("expected an array of reasons ({}), got {}",
                                                        incomplete_reason_names(), v->dump())};
    for (const json& name : *v) {
      uint32_t bit = 0;
      if (!name.is_string() || !parse_incomplete_reason(name.get<std::string>(), bit))
        throw TraceFieldProblem{"incomplete", fmt::format("unknown reason {} (expected one of {})", name.dump(),
                                                          incomplete_reason_names())};
      out.incomplete |= bit;
    }
  }
}

}  // namespace

void parse_trace_ray_line(std::string_view line, TraceRay& out) { parse_trace_ray(parse_json_object_line(line), out); }

}  // namespace vbsim
