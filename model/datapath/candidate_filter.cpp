#include "datapath/candidate_filter.h"

namespace vbsim {

void CandidateCounters::add(const CandidateCounters& o) {
  candidates += o.candidates;
  suspects += o.suspects;
  rejected += o.rejected;
  rejected_mask += o.rejected_mask;
  rejected_primid += o.rejected_primid;
  rejected_sign_only += o.rejected_sign_only;
  invalid_normal += o.invalid_normal;
  invalid_ray += o.invalid_ray;
  invalid_component += o.invalid_component;
}

}  // namespace vbsim
