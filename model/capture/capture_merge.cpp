#include "capture/capture_merge.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "capture/capture_trees.h"
#include "capture/captured_scene.h"
#include "capture/incomplete_rays.h"
#include "capture/raw_capture_files.h"
#include "datapath/hit_point.h"
#include "io/atomic_output_file.h"
#include "scene/ply_scene_writer.h"
#include "scene/triangle_masks.h"
#include "trace/incomplete_reasons.h"
#include "trace/trace_file.h"
#include "trace/trace_validation.h"

namespace vbsim::capture {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

using SceneKey = std::pair<uint32_t, uint32_t>;  // (scene ordinal, commit)

bool occluded(const RawRay& r) { return r.op == static_cast<uint16_t>(RawOp::Occluded); }

/// The ray as a trace ray without parent data: origin, direction and interval as passed to Embree.
TraceRay base_ray(const RawRay& r) {
  TraceRay t;
  t.o = {r.org[0], r.org[1], r.org[2]};
  t.d = {r.dir[0], r.dir[1], r.dir[2]};
  t.tmin = r.tnear;
  t.tmax = r.tfar;
  return t;
}

struct Tally {
  std::map<ProcessImage, int64_t> rays_by_process;
  std::map<std::pair<ProcessImage, SceneKey>, int64_t> rays_by_scene;
  /// Process images that ran with a shared libembree3 loaded (-> "N scenes, M commits").
  std::map<ProcessImage, std::string> embree_processes;
};

/// "process 123" for a process's first image, "process 123 (exec'd program 2)" for a later one.
std::string describe_image(const ProcessImage& id) {
  return id.image == 0 ? fmt::format("process {}", id.pid)
                       : fmt::format("process {} (the program it exec'd as image {})", id.pid, id.image);
}

/// The process images that traced rays, checked to have finished, and how many rays each traced where.
Tally tally(const std::map<ProcessImage, ProcessFiles>& processes) {
  Tally t;
  for (const auto& [id, p] : processes) {
    if (p.ray_files.empty()) {
      if (p.summary.empty()) continue;
      const auto values = read_process_summary(p.summary);
      auto value = [&](const char* k) { return values.count(k) ? values.at(k) : 0; };
      if (value("embree_loaded") != 0)
        t.embree_processes[id] = fmt::format("{} scene{}, {} commit{}", value("scenes"),
                                             value("scenes") == 1 ? "" : "s", value("commits"),
                                             value("commits") == 1 ? "" : "s");
      continue;
    }
    const auto values = p.summary.empty() ? std::map<std::string, uint64_t>{} : read_process_summary(p.summary);
    if (!values.count("complete"))
      throw std::runtime_error(fmt::format(
          "{} traced rays but did not exit normally (no complete process-{}.txt): the capture is incomplete",
          describe_image(id), id.name()));
    if (values.count("write_failed") && values.at("write_failed") != 0)
      throw std::runtime_error(fmt::format("{}: the capture shim could not write all its files", describe_image(id)));
    for (const auto& [k, path] : p.ray_files) {
      const MappedRays rays(path);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        ++t.rays_by_process[id];
        ++t.rays_by_scene[{id, {rays[i].scene, rays[i].commit}}];
      }
    }
  }
  return t;
}

std::string join(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : " ") + w;
  return s;
}

/// What the application's filter functions rejected for `r`: `"filter_rejected"`
/// with Embree's ids, how often, and whether it was the parent's primitive.
std::string rejected_fields(const RawRay& r, bool self_excluded) {
  if (!(r.flags & kRawFilterRejected)) return "";
  std::string s = fmt::format(",\"filter_rejected\":{{\"geom\":{},\"geom_prim\":{}", r.rejected_geom, r.rejected_prim);
  if (r.rejected_inst != kInvalidId) s += fmt::format(",\"inst\":{}", r.rejected_inst);
  return s + fmt::format(",\"times\":{},\"parent\":{}}}", r.rejections, self_excluded);
}

/// Embree's answer to ray `id` as one line of embree_hits.jsonl; an
/// intersect query the trace kinds a shadow ray also says whether it was occluded.
std::string hit_line(int64_t id, const RawRay& r, int64_t triangle, bool self_excluded, RayKind kind) {
  std::string extra = rejected_fields(r, self_excluded);  // the fields after Embree's answer
  if (kind == RayKind::Shadow && !occluded(r))
    extra = fmt::format(",\"occluded\":{}", r.geom != kInvalidId) + extra;
  if (occluded(r))
    return fmt::format("{{\"id\":{},\"occluded\":{}{}}}\n", id, std::isinf(r.hit_t) && r.hit_t < 0, extra);
  if (r.geom == kInvalidId) return fmt::format("{{\"id\":{},\"prim\":-1{}}}\n", id, extra);
  std::string s = fmt::format("{{\"id\":{},\"prim\":{},\"t\":{},\"u\":{},\"v\":{},\"geom\":{},\"geom_prim\":{}", id,
                              triangle, r.hit_t, r.u, r.v, r.geom, r.prim);
  if (r.inst != kInvalidId) s += fmt::format(",\"inst\":{}", r.inst);
  if (triangle < 0) s += ",\"not_captured\":true";
  return s + extra + "}\n";
}

/// Embree's answer as the trace's `reference`: occluded or not, a miss, or a
/// hit on a trace triangle; none for a hit on geometry the trace does not hold.
void set_reference(TraceRay& tr, const RawRay& r, int64_t triangle) {
  if (occluded(r)) {
    tr.has_reference = true;
    tr.reference_prim = std::isinf(r.hit_t) && r.hit_t < 0 ? kReferenceOccluded : -1;
  } else if (r.geom == kInvalidId) {
    tr.has_reference = true;
    tr.reference_prim = -1;
  } else if (triangle >= 0) {
    tr.has_reference = tr.has_reference_t = true;
    tr.reference_prim = static_cast<int32_t>(triangle);
    tr.reference_t = r.hit_t;
  }
}

}  // namespace

MergeResult merge_capture(const std::string& raw_dir, const std::string& out_dir, const MergeOptions& opt) {
  const auto processes = find_capture_files(raw_dir);
  const Tally tally_ = tally(processes);
  if (tally_.rays_by_scene.empty()) {
    if (!tally_.embree_processes.empty()) {
      std::string which;
      for (const auto& [p, what] : tally_.embree_processes)
        which += fmt::format("{}{} ({})", which.empty() ? "" : ", ", describe_image(p), what);
      throw std::runtime_error(fmt::format(
          "no Embree ray queries were captured: the application ran with a shared libembree3 ({}) but called no "
          "rtcIntersect or rtcOccluded function, so there are no rays to trace (it may build BVHs or run point "
          "queries only)", which));
    }
    throw std::runtime_error(
        "no Embree ray queries were captured: no process of the application loaded a shared libembree3 (a "
        "statically linked Embree cannot be interposed: its calls never leave the program)");
  }
  // The trace is the (process, scene, commit) that traced the most rays; ties go to the lowest scene and commit.
  auto best = tally_.rays_by_scene.begin();
  for (auto it = tally_.rays_by_scene.begin(); it != tally_.rays_by_scene.end(); ++it)
    if (it->second > best->second) best = it;
  const ProcessImage traced = best->first.first;
  const SceneKey key = best->first.second;
  const ProcessFiles& files = processes.at(traced);
  if (key.second == 0 || !files.scenes.count(key))
    throw std::runtime_error(
        fmt::format("{} traced rays against scene {} before committing it", describe_image(traced), key.first));
  const CapturedScene scene = CapturedScene::read(files.scenes.at(key), [&files](uint32_t s, uint32_t c) {
    const auto it = files.scenes.find({s, c});
    return it == files.scenes.end() ? std::string() : it->second;
  });
  if (scene.triangles().empty())
    throw std::runtime_error(fmt::format(
        "the traced scene (scene {}, commit {}) has no triangle geometry that could be captured, so there is no "
        "trace to write; its geometries: {}", key.first, key.second, describe_geometries(scene.geometries(), true)));
  const auto values = read_process_summary(files.summary);
  const bool unwatched_filters = values.count("unwatched_filter_functions") && values.at("unwatched_filter_functions") > 0;
  // A summary without the key (the process made no scene through the shim) keeps masks honoured.
  const bool ray_masks = !values.count("ray_mask_supported") || values.at("ray_mask_supported") != 0;
  IncompleteRayJudge judge(scene, unwatched_filters, opt.rules.on_surface_ulps, ray_masks);

  // Per thread: eligibility, links, trees.
  std::vector<ThreadRays> threads;
  std::vector<TreeRef> trees;
  const ParentLinker linker(scene, opt.rules);
  LinkCounts links;
  int64_t other_scene = 0, invalid = 0, outside_hits = 0, rays_with_masks = 0;
  std::map<std::string, int64_t> invalid_by_field;
  std::string first_invalid;
  for (const auto& [index, path] : files.ray_files) {
    ThreadRays& t = threads.emplace_back(MappedRays(path));
    t.eligible.assign(t.rays.size(), false);
    for (std::size_t i = 0; i < t.rays.size(); ++i) {
      const RawRay& r = t.rays[i];
      if (r.scene != key.first || r.commit != key.second) {
        ++other_scene;
        continue;
      }
      TraceFieldProblem problem;
      if (!check_trace_ray(base_ray(r), -1, problem)) {
        ++invalid;
        ++invalid_by_field[problem.field];
        if (first_invalid.empty()) first_invalid = fmt::format("field '{}': {}", problem.field, problem.message);
        continue;
      }
      t.eligible[i] = true;
      rays_with_masks += judge.ray_mask(r) != kAllMaskBits;
      outside_hits += !occluded(r) && r.geom != kInvalidId && scene.triangle_hit(r).triangle < 0;
    }
    LinkCounts c;
    t.links = linker.link(t.rays.data(), t.rays.size(), t.eligible, c);
    links.add(c);
    group_trees(static_cast<uint32_t>(threads.size() - 1), t, trees);
  }
  sort_trees(threads, trees);
  // Whether the application excludes parents' primitives (Cycles does): seen on any linked ray.
  bool excludes_parents = false;
  for (const ThreadRays& t : threads)
    for (std::size_t i = 0; i < t.rays.size() && !excludes_parents; ++i)
      excludes_parents = t.links[i].parent >= 0 &&
                         IncompleteRayJudge::self_excluded(t.rays[i], &t.rays[static_cast<std::size_t>(t.links[i].parent)]);
  judge.set_renderer_excludes_parents(excludes_parents);

  // Outputs, under temporary names of this run's own (AtomicOutputFile:
  // NAME.partial-PID-N) until everything is written; then scene, hits, trace
  // and capture.json take their names, in that order.
  fs::create_directories(out_dir);
  const fs::path dir(out_dir);
  const std::string ext = opt.binary ? ".vbt" : ".jsonl";
  const fs::path trace_path = dir / ("trace" + ext);
  const fs::path scene_path = dir / "scene.ply";
  const fs::path hits_path = dir / "embree_hits.jsonl";
  AtomicOutputFile scene_file(scene_path.string(), true);
  {
    const std::string bytes = ply_scene_bytes(scene_path.string(), scene.triangles(), {},
                                              opt.provenance.empty() ? "" : "vbsim-provenance " + opt.provenance);
    scene_file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    scene_file.check();
  }
  TraceHeader header;
  header.scene = "scene.ply";
  header.scene_path = scene_path.string();
  header.generator = "vbsim capture";
  header.provenance = opt.provenance;
  header.reference = "Embree in the capturing application (each ray's own answer, as in embree_hits.jsonl)";
  header.description = fmt::format(
      "Embree ray queries of `{}` ({} thread{}): {}; parents linked by origin (capture.json)", join(opt.command),
      threads.size(), threads.size() == 1 ? "" : "s",
      opt.strip_offsets ? "children start at their parent's hit point with tmin 0, the application's offsets removed"
                        : "origins, tmin and tmax as the application passed them");
  // Ray masks, where Embree honours them and the application used them: the
  // trace declares the triangles' masks and every ray carries its own.
  if (rays_with_masks > 0 || !judge.triangle_masks().empty())
    header.triangle_masks = triangle_mask_ranges(judge.triangle_masks());
  std::unique_ptr<TraceSink> sink = create_trace_writer(trace_path.string(), header);
  AtomicOutputFile hits_file(hits_path.string(), true);
  std::ostream& hits = hits_file.stream();
  std::vector<std::vector<int64_t>> ids(threads.size());
  for (std::size_t k = 0; k < threads.size(); ++k) ids[k].assign(threads[k].rays.size(), -1);
  int64_t next_id = 0, moved_origins = 0, cleared_tmin = 0, incomplete = 0;
  int64_t incomplete_by_reason[kIncompleteReasonCount] = {};
  for (const TreeRef& tree : trees) {
    const ThreadRays& t = threads[tree.thread];
    for (uint32_t k = 0; k < tree.count; ++k) {
      const uint32_t i = t.order[tree.first + k];
      const RawRay& r = t.rays[i];
      const RayLink& l = t.links[i];
      const RawRay* parent = l.parent >= 0 ? &t.rays[static_cast<std::size_t>(l.parent)] : nullptr;
      TraceRay tr = base_ray(r);
      tr.id = ids[tree.thread][i] = next_id++;
      tr.mask = judge.ray_mask(r);
      tr.kind = l.kind;
      if (l.parent >= 0) {
        const RawRay& p = t.rays[static_cast<std::size_t>(l.parent)];
        const TriangleHit ph = scene.triangle_hit(p);
        const int64_t tri = ph.triangle;
        tr.parent = ids[tree.thread][static_cast<std::size_t>(l.parent)];
        tr.set_parent_hit(static_cast<int32_t>(tri), p.hit_t, ph.u, ph.v);
        tr.sign = dot(tr.d, geometric_normal(scene.triangles()[static_cast<std::size_t>(tri)])) < 0.0f ? 1 : 0;
        if (opt.strip_offsets) {
          const Vec3f hit = hit_point_ray({p.org[0], p.org[1], p.org[2]}, {p.dir[0], p.dir[1], p.dir[2]}, p.hit_t);
          moved_origins += hit != tr.o;
          cleared_tmin += tr.tmin != 0.0f;
          tr.o = hit;
          tr.tmin = 0.0f;
        }
      }
      tr.incomplete = judge.reasons(r, parent);
      set_reference(tr, r, scene.triangle_hit(r).triangle);
      if (tr.incomplete != 0) {
        ++incomplete;
        for (int b = 0; b < kIncompleteReasonCount; ++b) incomplete_by_reason[b] += (tr.incomplete >> b) & 1u;
      }
      sink->write(tr);
      hits << hit_line(tr.id, r, scene.triangle_hit(r).triangle, IncompleteRayJudge::self_excluded(r, parent), l.kind);
    }
  }
  hits_file.check();

  // The report.
  json calls = json::object(), rays = json::object();
  for (const auto& [k, v] : values) {
    if (k.rfind("calls.", 0) == 0 && v > 0) calls[k.substr(6)] = v;
    if (k.rfind("rays.", 0) == 0 && v > 0) rays[k.substr(5)] = v;
  }
  json geometries = json::array();
  for (const CapturedGeometry& g : scene.geometries()) {
    json e = {{"geomID", g.geom_id}, {"type", embree_geometry_type_name(g.type)},
              {"status", raw_geometry_status_name(g.status)}};
    if (g.status == RawGeometryStatus::Captured)
      e.update({{"first_triangle", g.first_triangle}, {"triangles", g.triangles}, {"vertices", g.vertices}});
    if (g.filters & kRawIntersectFilter) e["intersect_filter"] = true;
    if (g.filters & kRawOccludedFilter) e["occluded_filter"] = true;
    if (g.mask != kAllMaskBits) e["mask"] = g.mask;  // rtcSetGeometryMask: the trace's triangle_masks hold it
    geometries.push_back(e);
  }
  json other_processes = json::array();
  int64_t other_process_rays = 0;
  for (const auto& [p, n] : tally_.rays_by_process)
    if (!(p == traced)) {
      other_processes.push_back({{"pid", p.pid}, {"image", p.image}, {"rays", n}});
      other_process_rays += n;
    }
  json kinds = json::object();
  for (int k = 0; k < kRayKindCount; ++k) kinds[ray_kind_name(static_cast<RayKind>(k))] = links.by_kind[k];
  json by_reason = json::object();
  std::string reasons_text;
  for (int b = 0; b < kIncompleteReasonCount; ++b)
    if (incomplete_by_reason[b] > 0) {
      by_reason[incomplete_reason_name(b)] = incomplete_by_reason[b];
      reasons_text += fmt::format("{}{} {}", reasons_text.empty() ? "" : ", ", incomplete_reason_name(b),
                                  incomplete_by_reason[b]);
    }
  MergeResult out;
  out.trace_path = trace_path.string();
  out.incomplete_rays = incomplete;
  out.report = {
      {"command", opt.command},
      {"pid", traced.pid},
      {"image", traced.image},
      {"threads", threads.size()},
      {"calls", calls},
      {"rays_by_function", rays},
      {"rays_in_trace", next_id},
      {"scene", {{"ordinal", key.first}, {"commit", key.second}, {"triangles", scene.triangles().size()},
                 {"geometries", geometries}}},
      {"not_captured", {{"other_processes", other_processes}, {"other_process_rays", other_process_rays},
                        {"other_scene_or_commit", other_scene}, {"invalid", invalid},
                        {"invalid_by_field", invalid_by_field}, {"first_invalid", first_invalid}}},
      {"hits_outside_captured_triangles", outside_hits},
      {"incomplete", {{"rays", incomplete}, {"by_reason", by_reason},
                      {"unwatched_filter_functions", unwatched_filters}, {"embree_ray_masks", ray_masks}}},
      {"masks", {{"declared", header.triangle_masks.has_value()},
                 {"triangle_ranges", header.triangle_masks ? header.triangle_masks->size() : 0},
                 {"rays_with_masks", rays_with_masks}}},
      {"self_excluded", judge.self_excluded_rays()},
      {"renderer_excludes_parents", excludes_parents},
      {"instances", {{"flattened", scene.has_instances()}, {"rays_checked", judge.flattened_checked()},
                     {"flattened_answer_differs", judge.flattened_differs()}}},
      {"links", {{"at_hit_point", links.at_hit_point}, {"normal_offset", links.normal_offset},
                 {"rejected_primitive", links.rejected_primitive},
                 {"max_normal_offset", links.max_offset}, {"unlinked_intersect", links.unlinked_intersect},
                 {"unlinked_occluded", links.unlinked_occluded}}},
      {"kinds", kinds},
      {"strip_offsets", {{"on", opt.strip_offsets}, {"origins_moved", moved_origins}, {"tmin_cleared", cleared_tmin}}},
      {"rules", {{"link_ulps", opt.rules.ulps}, {"link_rejected_ulps", opt.rules.rejected_ulps},
                 {"on_surface_ulps", opt.rules.on_surface_ulps}, {"link_normal_offset", opt.rules.normal_offset},
                 {"history", opt.rules.history}, {"mirror_radians", opt.rules.mirror_radians}}},
  };
  scene_file.commit();
  hits_file.commit();
  sink->close();
  write_output_file((dir / "capture.json").string(), out.report.dump(2) + "\n", "capture report");
  std::string by_function;
  for (const auto& [name, n] : rays.items()) by_function += fmt::format("{}{} {}", by_function.empty() ? "" : ", ", name, n.get<int64_t>());
  out.summary = fmt::format(
      "vbsim capture: {} rays from {} thread{} ({}) -> {}\n"
      "  scene: {} triangles -> {}\n"
      "  links: {} at the hit point, {} offset along the normal (up to {:.3g} of the hit point's size), {} by the "
      "primitive their filter rejected; unlinked: {} intersect, {} occluded\n"
      "  not captured: {} rays of other processes (or programs they exec'd), {} of other scenes or commits, {} invalid; "
      "{} hits outside the captured triangles\n"
      "  geometries not in the trace: {}\n"
      "  self-exclusion: {} rays whose filter functions rejected their parent's primitive only (scored: primid "
      "reproduces it)\n",
      next_id, threads.size(), threads.size() == 1 ? "" : "s", by_function, trace_path.string(),
      scene.triangles().size(), scene_path.string(), links.at_hit_point, links.normal_offset, links.max_offset,
      links.rejected_primitive, links.unlinked_intersect, links.unlinked_occluded, other_process_rays, other_scene, invalid, outside_hits,
      describe_geometries(scene.geometries(), false), judge.self_excluded_rays());
  if (header.triangle_masks)
    out.summary += fmt::format(
        "  ray masks: carried into the trace ({} triangle range{} with a mask other than all bits, {} rays with "
        "one); replays and the oracle honour them\n",
        header.triangle_masks->size(), header.triangle_masks->size() == 1 ? "" : "s", rays_with_masks);
  if (scene.has_instances())
    out.summary += fmt::format(
        "  instances: flattened into world-space triangles; {} of {} rays answered otherwise on them than by Embree's "
        "instance-space test (marked instance)\n", judge.flattened_differs(), judge.flattened_checked());
  if (incomplete > 0)
    out.summary += fmt::format(
        "  incomplete: {} of {} rays ({}): the trace cannot reproduce Embree's answer (geometry or filter "
        "functions it does not hold, or an origin on a surface with no parent found); they are marked "
        "`incomplete` in the trace and replays do not score them\n",
        incomplete, next_id, reasons_text);
  else
    out.summary += "  incomplete: 0 rays (no answer involves geometry outside the trace or a filter function)\n";
  return out;
}

}  // namespace vbsim::capture
