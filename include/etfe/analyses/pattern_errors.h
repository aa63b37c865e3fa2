// Fabrication errors of a cutting pattern: how far the plane pattern is from the 3D strip it
// becomes. Per edge (the outline from corner to corner, as named on the drawing: A-B, ...) the
// length error against the length the pattern should have there (its 3D length, or with
// compensation the compensated target) and the largest error of one link along it; per strip
// the area strain (plane against 3D area, compensation included) and the largest and rms errors
// of the interior links (the strain the film takes when drawn onto the surface, compensation
// aside). Errors are fractions (0.01 = 1 %).
#pragma once
#include <string>
#include <vector>

#include "etfe/analyses/flatten_strip.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct PatternEdgeError {
  std::string name;                          // "A-B"
  double length3d = 0, target = 0, length2d = 0;  // mm
  double compensation = 0;    // (target - length3d) / length3d: the shortening the compensation asked for
  double error = 0;           // (length2d - target) / target
  double max_link_error = 0;  // largest |l - L| / L of a link along the edge
};
struct PatternStripErrors {
  std::string strip;
  std::vector<PatternEdgeError> edges;
  double area3d = 0, area2d = 0, area_strain = 0;  // mm^2; (area2d - area3d) / area3d
  double max_interior_error = 0, rms_interior_error = 0, max_link_error = 0;
};

// strip: the 3D strip flattened into r (same node ids).
PatternStripErrors PatternErrors(const MeshData &strip, const FlattenResult &r, const std::string &name);
// CSV strip,kind,name,value3d,target,value2d,compensation,error,max_link_error,exceeds_first_yield:
// kind "edge" (lengths in mm), "area" (mm^2; error = the area strain) and "interior" (links not on
// the outline: error = their rms, max_link_error their largest). exceeds_first_yield (edge and
// interior rows) is 1 when |error| or max_link_error is above first_yield_strain (> 0).
// The printed lines of one strip ("cutpattern: strip S edge A-B: ...") and a warning per edge, and
// for the interior, whose error is above first_yield_strain (> 0; `source` says where it came from).
std::string PatternErrorReport(const PatternStripErrors &e, double first_yield_strain, const std::string &source);
bool WritePatternErrors(const std::string &path, const std::vector<PatternStripErrors> &strips,
                        double first_yield_strain, std::string *err);

} // namespace etfe
