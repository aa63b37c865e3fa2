// The film's stress-free state as the flat cutting pattern of its strips (-saddle_reference
// pattern, -structure_reference pattern), as in the experiments (the specimens were welded from flat strips: thesis L267,
// L692, L1666), not the form-found surface the thesis's own analysis started from (L1689).
// Each strip (an element set of the mesh: the saddle's "middle" and "corner") is flattened with the
// cutting-pattern analysis (flatten_strip.h, the thesis's boundary weight 1e12, so weld and frame
// lines keep their length); every element then takes its flat triangle as its reference while
// its nodes start on the surface, welded at the weld line. The reference is blended from the
// surface to the pattern during the first drawing step (SceneSpec::reference_blend, schedule
// "lay_on"), so the misfit is loaded gradually and under tension: the flat pattern does not fit
// the doubly curved frame (its interior links are up to ~1.3 % off their 3D lengths), and a lay-on
// without drawing compresses parts of the film, which a membrane cannot carry (measured: Newton
// finds no equilibrium even at 1/2500 of such a stage, the line search failing at |R| ~ 1e-3 N).
// A strip whose outline lies in one plane (a cushion's foil in its frame) keeps that outline in
// the pattern (FlattenOptions::hold_planar_outline): the film is cut to the frame, so the
// stress-free state is the flat planform whatever lens the mesh starts from.
#include <petscsys.h>

#include <cstdio>
#include <string>
#include <vector>

#include "etfe/analyses/cutpattern.h"
#include "etfe/analyses/flatten_strip.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "pattern_reference.h"

namespace etfe {

namespace {

// Rank 0: the flat pattern of both strips, one report line each, or a message.
bool FlattenStrips(const MeshData &m, const PatternStrips &p, std::vector<double> *element_reference, std::string *lines,
                   std::string *err) {
  std::vector<int> covered(m.NumElements(), 0);
  element_reference->assign(9 * (size_t)m.NumElements(), 0.0);
  std::string listed;
  for (const std::string &name : p.strips) listed += (listed.empty() ? "" : ", ") + name;
  for (const std::string &name : p.strips) {
    auto it = m.element_sets.find(name);
    if (it == m.element_sets.end() || it->second.empty()) {
      *err = p.option + ": " + m.source + " has no element set \"" + name + "\"; " + p.missing_hint;
      return false;
    }
    MeshData strip;
    FlattenResult r, design;
    std::string why;
    const bool compensated = p.cut && p.cut->compensation != Compensation::None;
    const bool flat = p.cut ? FlattenNamedStrip(m, name, *p.cut, nullptr, &strip, &r, &design, &why)
                            : FlattenStrip(strip = ExtractStrip(m, it->second, name), FlattenOptions(), &r, &why);
    if (!flat) {
      *err = p.option + ": flattening strip " + name + " of " + m.source + " failed: " + why;
      return false;
    }
    for (size_t k = 0; k < it->second.size(); ++k) {
      const int e = it->second[k];
      covered[e]++;
      for (int a = 0; a < 3; ++a) {
        const int n = strip.triangles[3 * k + a];
        double *Y = &(*element_reference)[9 * (size_t)e + 3 * a];
        Y[0] = r.xy[2 * n], Y[1] = r.xy[2 * n + 1], Y[2] = 0.0;
      }
    }
    char line[400];
    std::snprintf(line, sizeof line,
                  "%s: reference = flat pattern of strip %s (%zu elements, outline 3D %.3f mm, 2D %.3f mm%s, largest "
                  "link error %.2e)\n",
                  p.scene.c_str(), name.c_str(), it->second.size(), r.outline_length3d, r.outline_length2d,
                  r.outline_held ? ", the outline held in its plane: cut to the frame" : "", r.max_rel_error);
    *lines += line;
    if (compensated) {
      std::snprintf(line, sizeof line,
                    "%s: strip %s cut with compensation %s: outline 2D %.3f mm (uncompensated %.3f mm, %+.4f %%)\n",
                    p.scene.c_str(), name.c_str(), CompensationName(p.cut->compensation), r.outline_length2d,
                    design.outline_length2d,
                    100.0 * (r.outline_length2d - design.outline_length2d) / design.outline_length2d);
      *lines += line;
    }
  }
  for (int e = 0; e < m.NumElements(); ++e)
    if (covered[e] != 1) {
      *err = p.option + ": element " + std::to_string(e) + " of " + m.source + " is in " +
             std::to_string(covered[e]) + " of the strips " + listed + " (must be in one)";
      return false;
    }
  return true;
}

} // namespace

PetscErrorCode PatternReference(MPI_Comm comm, const MeshData &m, const PatternStrips &strips,
                                std::vector<double> *element_reference) {
  std::string lines, err;
  int ok = 1;
  PetscFunctionBeginUser;
  if (SceneHoldsMesh(comm)) ok = FlattenStrips(m, strips, element_reference, &lines, &err) ? 1 : 0;
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_ARG_WRONG));
  PetscCall(PetscPrintf(comm, "%s", lines.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
