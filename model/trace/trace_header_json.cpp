#include "trace/trace_header_json.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "trace/trace_json_values.h"

namespace vbsim {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const json* find_field(const json& object, const char* key) {
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

/// A mask: an integer 0 .. 2^32 - 1.
uint32_t json_mask(const json& v, const char* field) {
  const int64_t m = json_int64(v, field);
  if (m < 0 || m > int64_t{kAllMaskBits})
    throw TraceFieldProblem{field, fmt::format("a mask is an integer from 0 to 4294967295, got {}", m)};
  return static_cast<uint32_t>(m);
}

/// `triangle_masks`: [[first, count, mask], ...], ranges ascending and disjoint.
std::vector<TriangleMaskRange> parse_triangle_masks(const json& v) {
  const char* field = "triangle_masks";
  if (!v.is_array())
    throw TraceFieldProblem{field, fmt::format("expected an array of [first, count, mask], got {}", v.dump())};
  std::vector<TriangleMaskRange> out;
  uint64_t end = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const json& e = v[i];
    if (!e.is_array() || e.size() != 3)
      throw TraceFieldProblem{field, fmt::format("entry {}: expected [first, count, mask], got {}", i, e.dump())};
    const int64_t first = json_int64(e[0], field), count = json_int64(e[1], field);
    if (first < 0 || first > INT32_MAX || count < 1 || count > INT32_MAX)
      throw TraceFieldProblem{field, fmt::format("entry {}: first must be a triangle index and count at least 1, "
                                                 "got [{}, {}]", i, first, count)};
    if (static_cast<uint64_t>(first) < end)
      throw TraceFieldProblem{field, fmt::format("entry {}: starts at triangle {}, inside or before the range "
                                                 "before it (ranges ascend and do not overlap)", i, first)};
    end = static_cast<uint64_t>(first) + static_cast<uint64_t>(count);
    out.push_back({static_cast<uint32_t>(first), static_cast<uint32_t>(count), json_mask(e[2], field)});
  }
  return out;
}

}  // namespace

uint32_t parse_ray_mask(const json& v) { return json_mask(v, "mask"); }

TraceHeader parse_trace_header(const json& object, const std::string& trace_path) {
  const json* format = find_field(object, "format");
  if (!format)
    throw TraceFieldProblem{"format",
                            fmt::format("missing: a trace starts with a header such as "
                                        "{{\"format\": \"{}\", \"version\": {}, \"scene\": ...}}",
                                        kTraceFormatName, kTraceFormatVersion)};
  if (json_string(*format, "format") != kTraceFormatName)
    throw TraceFieldProblem{"format", fmt::format("expected \"{}\", got {}", kTraceFormatName,
                                                  format->dump())};
  TraceHeader header;
  const json* version = find_field(object, "version");
  if (!version) throw TraceFieldProblem{"version", "missing"};
  int64_t v = json_int64(*version, "version");
  if (v != kTraceFormatVersion)
    throw TraceFieldProblem{"version", fmt::format("unsupported version {} (this reader reads {})",
                                                   v, kTraceFormatVersion)};
  header.version = kTraceFormatVersion;

  const json* scene = find_field(object, "scene");
  if (!scene) throw TraceFieldProblem{"scene", "missing"};
  header.scene = json_string(*scene, "scene");
  if (header.scene.empty()) throw TraceFieldProblem{"scene", "is empty"};
  header.scene_path = resolve_scene_path(header.scene, trace_path);

  if (const json* light = find_field(object, "light")) header.light = json_vec3(*light, "light");
  if (const json* generator = find_field(object, "generator"))
    header.generator = json_string(*generator, "generator");
  if (const json* description = find_field(object, "description"))
    header.description = json_string(*description, "description");
  if (const json* reference = find_field(object, "reference")) {
    header.reference = json_string(*reference, "reference");
    if (header.reference.empty()) throw TraceFieldProblem{"reference", "empty (leave it out when the rays carry none)"};
  }
  if (const json* transform = find_field(object, "transform")) {
    std::array<float, 16> m;
    json_float32_array(*transform, "transform", m.data(), m.size());
    header.transform = m;
  }
  if (const json* masks = find_field(object, "triangle_masks")) header.triangle_masks = parse_triangle_masks(*masks);
  if (const json* provenance = find_field(object, "provenance")) {
    if (!provenance->is_object()) throw TraceFieldProblem{"provenance", "must be an object"};
    header.provenance = provenance->dump(-1, ' ', false, json::error_handler_t::replace);
  }
  return header;
}

std::string trace_header_json(const TraceHeader& header) {
  fmt::memory_buffer out;
  auto text = [&out](const char* s) { out.append(s, s + std::char_traits<char>::length(s)); };
  text("{\"format\":");
  append_json_string(out, kTraceFormatName, "format");
  fmt::format_to(std::back_inserter(out), ",\"version\":{},\"scene\":", kTraceFormatVersion);
  append_json_string(out, header.scene, "scene");
  if (header.light) {
    if (!is_finite(*header.light)) throw TraceFieldProblem{"light", "is not finite"};
    text(",\"light\":");
    append_json_vec3(out, *header.light);
  }
  if (!header.generator.empty()) {
    text(",\"generator\":");
    append_json_string(out, header.generator, "generator");
  }
  if (!header.description.empty()) {
    text(",\"description\":");
    append_json_string(out, header.description, "description");
  }
  if (!header.reference.empty()) {
    text(",\"reference\":");
    append_json_string(out, header.reference, "reference");
  }
  if (header.transform) {
    text(",\"transform\":[");
    for (std::size_t i = 0; i < header.transform->size(); ++i) {
      float x = (*header.transform)[i];
      if (!std::isfinite(x)) throw TraceFieldProblem{"transform", "is not finite"};
      if (i > 0) out.push_back(',');
      append_json_float(out, x);
    }
    out.push_back(']');
  }
  if (header.triangle_masks) {
    text(",\"triangle_masks\":[");
    bool first = true;
    for (const TriangleMaskRange& r : *header.triangle_masks) {
      fmt::format_to(std::back_inserter(out), "{}[{},{},{}]", first ? "" : ",", r.first, r.count, r.mask);
      first = false;
    }
    out.push_back(']');
  }
  if (!header.provenance.empty()) {
    if (!json::accept(header.provenance) || header.provenance.front() != '{')
      throw TraceFieldProblem{"provenance", "is not a JSON object"};
    text(",\"provenance\":");
    out.append(header.provenance.data(), header.provenance.data() + header.provenance.size());
  }
  out.push_back('}');
  return fmt::to_string(out);
}

std::string resolve_scene_path(const std::string& scene, const std::string& trace_path) {
  fs::path scene_file(scene);
  if (scene_file.is_absolute()) return scene;
  fs::path dir = fs::path(trace_path).parent_path();
  return dir.empty() ? scene : (dir / scene_file).string();
}

std::string scene_relative_to(const std::string& scene_path, const std::string& trace_path) {
  fs::path scene_abs = fs::absolute(scene_path).lexically_normal();
  fs::path dir_abs = fs::absolute(trace_path).parent_path().lexically_normal();
  fs::path relative = scene_abs.lexically_relative(dir_abs);
  return relative.empty() ? scene_abs.string() : relative.string();
}

}  // namespace vbsim
