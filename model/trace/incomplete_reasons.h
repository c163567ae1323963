// Why a ray's answer in the renderer that traced it depends on something its
// trace does not hold (docs/trace-format.md, field `incomplete`): geometry
// that is not in the trace's scene (instances, quads, curves, ...), or a
// filter function of the application that may have changed the answer. Such a
// ray cannot be expected to replay to its renderer's answer, and replays do
// not score it unless asked. The bits are the binary form's `incomplete` word;
// the names are the text form's.
#pragma once
#include <cstdint>
#include <string>

namespace vbsim {

enum IncompleteReason : uint32_t {
  kIncompleteInstance = 1u << 0,       ///< geometry inside an instance
  kIncompleteQuad = 1u << 1,           ///< a quad mesh
  kIncompleteGrid = 1u << 2,           ///< a grid mesh
  kIncompleteSubdivision = 1u << 3,    ///< a subdivision surface
  kIncompleteCurve = 1u << 4,          ///< curves (flat, round, normal-oriented)
  kIncompletePoint = 1u << 5,          ///< points (spheres, discs)
  kIncompleteUser = 1u << 6,           ///< user geometry (the application's own intersector)
  kIncompleteMotionBlur = 1u << 7,     ///< a mesh with more than one time step
  kIncompleteOtherGeometry = 1u << 8,  ///< any other geometry the trace does not hold
  kIncompleteFilter = 1u << 9,         ///< a filter function rejected or changed a candidate hit, or may have
  kIncompleteMask = 1u << 10,          ///< a geometry the ray's mask hides from it (rtcSetGeometryMask)
  /// A ray that starts on a surface of the scene but whose parent the capture
  /// could not find: scored as a camera ray its exact answer would be wrong.
  kIncompleteUnlinked = 1u << 11,
};
constexpr int kIncompleteReasonCount = 12;
constexpr uint32_t kIncompleteKnownBits = (1u << kIncompleteReasonCount) - 1;

/// Name of reason bit `index` (0 .. kIncompleteReasonCount-1): "instance", "quad", ...
const char* incomplete_reason_name(int index);
/// The bit named `name`; false when the name is not a reason.
bool parse_incomplete_reason(const std::string& name, uint32_t& bit);
/// "instance, filter": the names of the bits set, in bit order.
std::string incomplete_reasons_text(uint32_t bits);
/// Every reason name, comma-separated (for error messages).
std::string incomplete_reason_names();

}  // namespace vbsim
