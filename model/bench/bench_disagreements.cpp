#include "bench/bench_disagreements.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "exact/oracle.h"
#include "replay/functional_replayer.h"

namespace vbsim {

const char* disagreement_class_name(DisagreementClass c) {
  switch (c) {
    case DisagreementClass::Tie: return "tie";
    case DisagreementClass::EmbreeWrong: return "embree_wrong";
    case DisagreementClass::VbsimWrong: return "vbsim_wrong";
    case DisagreementClass::BothWrong: return "both_wrong";
    default: return "method";
  }
}

int64_t DisagreementReport::total() const {
  int64_t n = 0;
  for (int64_t c : counts) n += c;
  return n;
}

nlohmann::json DisagreementReport::to_json(size_t max_rays) const {
  nlohmann::json j;
  for (int k = 0; k < kDisagreementClassCount; ++k)
    j[disagreement_class_name(static_cast<DisagreementClass>(k))] = counts[static_cast<size_t>(k)];
  nlohmann::json parent;
  for (int k = 0; k < kDisagreementClassCount; ++k)
    parent[disagreement_class_name(static_cast<DisagreementClass>(k))] = at_parent[static_cast<size_t>(k)];
  j["at_parent"] = std::move(parent);
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < rays.size() && i < max_rays; ++i) {
    const BenchDisagreement& d = rays[i];
    list.push_back({{"index", d.index},
                    {"id", d.id},
                    {"vbsim", d.vbsim},
                    {"embree", d.embree == kEmbreeOccluded ? nlohmann::json("occluded") : nlohmann::json(d.embree)},
                    {"class", disagreement_class_name(d.cls)},
                    {"at_parent", d.at_parent}});
  }
  j["rays_listed"] = list.size();
  j["rays"] = std::move(list);
  return j;
}

ExactRay exact_emitted_ray(const Ray& r) {
  ExactRay x;
  x.o = to_exact(r.o);
  x.d = to_exact(r.d);
  mpq_class tmin = 0;
  if (std::isfinite(r.tmin) && r.tmin > 0.0f) {
    tmin = mpq_class(static_cast<double>(r.tmin));
    x.o.x += tmin * x.d.x;
    x.o.y += tmin * x.d.y;
    x.o.z += tmin * x.d.z;
  }
  if (std::isinf(r.tmax)) {  // +inf: no upper end; -inf: empty
    x.has_tmax = r.tmax < 0;
    x.tmax = 0;
  } else {
    x.has_tmax = true;
    x.tmax = std::isnan(r.tmax) ? mpq_class(0) : mpq_class(static_cast<double>(r.tmax)) - tmin;
    if (x.tmax < 0) x.tmax = 0;
  }
  return x;
}

bool answer_is_right(const Scene& scene, const ExactRay& r, bool any_hit, int32_t answer,
                     const std::vector<int32_t>& ties) {
  if (answer == -1) return ties.empty();
  if (answer == kEmbreeOccluded) return !ties.empty();
  if (!any_hit) return std::binary_search(ties.begin(), ties.end(), answer);
  return answer < scene.size() && exact_intersect(r, scene.triangles[static_cast<size_t>(answer)]).hit;
}

DisagreementReport classify_disagreements(const Scene& scene, const Bvh& bvh, const ReplayOptions& opt,
                                          const BenchWorkload& w, const std::vector<int32_t>& ours,
                                          const std::vector<int32_t>& theirs) {
  DisagreementReport report;
  std::unique_ptr<Oracle> oracle;  // built at the first disagreement
  const CandidateFilter filter(opt.method);
  for (size_t i = 0; i < ours.size(); ++i) {
    const bool any_hit = w.any_hit[i] != 0;
    if (bench_answers_agree(ours[i], theirs[i], any_hit)) continue;
    if (!oracle) oracle = std::make_unique<Oracle>(scene, bvh);
    BenchDisagreement d;
    d.index = static_cast<int64_t>(i);
    d.id = w.rays[i].id;
    d.vbsim = ours[i];
    d.embree = theirs[i];
    const EmittedRay& er = w.emitted[i];
    KindStats scratch;
    const RayOutcome again = replay_one_ray(w.rays[i], scene, bvh, opt, filter, w.parent(i), scratch);
    if (again.rejected > 0 || again.reversed) {
      d.cls = DisagreementClass::Method;
    } else {
      const ExactRay x = exact_emitted_ray(er.ray);
      const std::vector<int32_t> ties = oracle->closest_ties(x);
      const int32_t parent = w.rays[i].parent_prim;
      d.at_parent = parent >= 0 && (ours[i] == parent || theirs[i] == parent ||
                                    std::find(ties.begin(), ties.end(), parent) != ties.end());
      const bool ours_right = answer_is_right(scene, x, any_hit, ours[i], ties);
      const bool theirs_right = answer_is_right(scene, x, any_hit, theirs[i], ties);
      d.cls = ours_right ? (theirs_right ? DisagreementClass::Tie : DisagreementClass::EmbreeWrong)
                         : (theirs_right ? DisagreementClass::VbsimWrong : DisagreementClass::BothWrong);
    }
    ++report.counts[static_cast<size_t>(d.cls)];
    report.at_parent[static_cast<size_t>(d.cls)] += d.at_parent;
    report.rays.push_back(d);
  }
  return report;
}

}  // namespace vbsim
