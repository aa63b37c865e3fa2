// Stretch fabrication of the saddle (docs/theory.md §13, thesis ch. 4-5) as a case of the general
// scene (StructureBuild): the film, stress free on its initial shape, rests on the arch (friction
// contact, a rigid support) and its frame edges are drawn outward at a (X = 2000, Y = 0; in X),
// b (the corner; in X and Y), c (Y = 1000, X = 1000; in Y) and d (Y = 1000, X = 0; in Y), linearly
// in between (thesis Fig. 3.4: control points with -bc_frame_points_interpolation axis), stage by
// stage; optionally followed by an internal-pressure cycle (§5.4) on the whole film. This file
// translates the -saddle_* options into those inputs; the report and history are
// -structure_check saddle_stretch (structure_check_saddle.cpp). The same case as options only:
// options/structure/verify_dd1511_stretch.opts.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "pattern_reference.h"
#include "real_array_option.h"
#include "saddle_geometry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// What the stretch options give, defaults included: thesis Table 5.5, DD1511 (the PD schedules
// were only in lost figures: the same by default).
struct StretchInputs {
  std::vector<double> draw[4] = {{10, 20, 30, 40}, {10, 15, 20, 30}, {10, 20, 30, 40}, {10, 20, 30, 40}};  // a, b, c, d
  std::vector<double> gain = {1, 1, 1, 1}, intercept = {0, 0, 0, 0}, pressure;
  std::vector<double> part_a = {0, 0, 400, 400}, part_b = {1300, 0, 1700, 400};
  std::vector<double> elem_i = {200, 200}, elem_ii = {500, 700}, slides = {0, 250, 500, 750, 950};
  PetscInt reference = 0;  // 0: the surface, 1: the flat patterns
  std::string history;
};

// A per-stage option: read (so -help lists it and it counts as used), then replaced by the
// caller's override when there is one (the drawing planner's trial schedule).
PetscErrorCode ReadStageArray(PetscOptionItems *PetscOptionsObject, const StageValues &overrides, const char *name,
                              const char *help, std::vector<double> *v) {
  PetscFunctionBeginUser;
  PetscCall(OptionsRealArray(PetscOptionsObject, name, help, v, nullptr));
  const auto it = overrides.find(name + 1);
  if (it != overrides.end()) *v = it->second;
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStretchOptions(MPI_Comm comm, const StageValues &overrides, StretchInputs *in) {
  static const char *const points[4] = {"a (X = 2000, Y = 0; drawn in X)", "b (the frame corner; in X and Y)",
                                        "c (Y = 1000, X = 1000, the arch's end; in Y)", "d (Y = 1000, X = 0; in Y)"};
  static const char *const names[4] = {"-saddle_draw_a", "-saddle_draw_b", "-saddle_draw_c", "-saddle_draw_d"};
  const char *references[] = {"surface", "pattern"};
  char history[PETSC_MAX_PATH_LEN] = "";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Saddle stretch fabrication", "Scene");
  for (int k = 0; k < 4; ++k) {
    const std::string help = std::string("Drawing at ") + points[k] +
                             " [mm], cumulative: the frame's total drawing there at the end of each stage (stage 1 "
                             "first; 10,20 draws 10 mm in each of two stages)";
    PetscCall(ReadStageArray(PetscOptionsObject, overrides, names[k], help.c_str(), &in->draw[k]));
  }
  PetscCall(ReadStageArray(PetscOptionsObject, overrides, "-saddle_pressure_cycle",
                           "Internal pressure after drawing, one stage per value, the drawing held [kPa] (none by "
                           "default)",
                           &in->pressure));
  // The drawing map and the probes: parts A and B, elements I and II, the slide points.
  const struct {
    const char *name, *help;
    std::vector<double> *v;
  } arrays[] = {
      {"-saddle_gain", "Drawing map slope at a,b,c,d: boundary motion = max(0, gain*draw + intercept)", &in->gain},
      {"-saddle_draw_intercept",
       "Drawing map intercept at a,b,c,d [mm] (thesis Fig. 3.17's regression lines; 0: motion = gain*draw)",
       &in->intercept},
      {"-saddle_part_A",
       "Part A, box x0,y0,x1,y1 in plan [mm]: the middle part's centre (the film between the symmetry plane X = 0 "
       "and the arch); its elements' mean GL strains and PK2 Mises are reported",
       &in->part_a},
      {"-saddle_part_B",
       "Part B, box x0,y0,x1,y1 in plan [mm]: the corner part's centre (the film between the arch at X = 1000 and "
       "the frame); reported as part A",
       &in->part_b},
      {"-saddle_element_I",
       "Element I, x,y in plan [mm]: the element nearest this point (in part A by default); its minimum principal "
       "strain and stress tell whether the middle part wrinkles",
       &in->elem_i},
      {"-saddle_element_II",
       "Element II, x,y in plan [mm]: a second wrinkling probe, in the middle part towards the frame edge c-d by "
       "default",
       &in->elem_ii},
      {"-saddle_slide_points",
       "Y of the arch slide points I..V [mm]: the film nodes on the arch nearest these, whose slide in plan (X, Y) "
       "is reported",
       &in->slides},
  };
  for (const auto &a : arrays) PetscCall(OptionsRealArray(PetscOptionsObject, a.name, a.help, a.v, nullptr));
  PetscCall(PetscOptionsEList("-saddle_reference",
                              "Stress-free state: surface (the form-found shape, as the thesis's analysis) or pattern "
                              "(the flat cutting patterns of the strips, laid on during the first drawing step)",
                              "", references, 2, references[in->reference], &in->reference, nullptr));
  PetscCall(PetscOptionsString("-saddle_history", "Probe history CSV (default beside -output_file)", "", history,
                               history, sizeof history, nullptr));
  PetscOptionsEnd();
  in->history = history;
  const size_t ns = in->draw[0].size();
  PetscCheck(ns >= 1 && in->draw[1].size() == ns && in->draw[2].size() == ns && in->draw[3].size() == ns, comm,
             PETSC_ERR_ARG_SIZ, "-saddle_draw_a/b/c/d must have the same number of stages (now %zu, %zu, %zu, %zu)",
             in->draw[0].size(), in->draw[1].size(), in->draw[2].size(), in->draw[3].size());
  PetscCheck(in->gain.size() == 4 && in->intercept.size() == 4 && in->part_a.size() == 4 && in->part_b.size() == 4 &&
                 in->elem_i.size() == 2 && in->elem_ii.size() == 2,
             comm, PETSC_ERR_ARG_SIZ,
             "-saddle_gain and -saddle_draw_intercept need 4 values (a,b,c,d), -saddle_part_A/B 4 "
             "(x0,y0,x1,y1), -saddle_element_I/II 2 (x,y)");
  for (const auto *arr : {&in->draw[0], &in->draw[1], &in->draw[2], &in->draw[3], &in->gain, &in->intercept,
                          &in->pressure})
    for (double x : *arr)
      PetscCheck(std::isfinite(x), comm, PETSC_ERR_ARG_OUTOFRANGE, "saddle: drawing, gain and pressure values must be finite");
  PetscFunctionReturn(0);
}


// The drawing value is what the frame's screws are turned by; the model's boundary is the line
// of offset points, which the thesis maps from the drawing value through regression lines
// (L914, Fig. 3.17; used for the predictions, L1689-1691). The lines themselves are lost with the
// figures, so slope and intercept are options; the clamp keeps a line with a negative intercept
// (slack taken up before the film moves) from pushing the boundary inward at small drawings.
// Per stage of the whole analysis: the pressure stages hold the last drawing.
std::vector<double> BoundaryMotion(const StretchInputs &in, int k_pos) {
  const size_t ns = in.draw[0].size(), stages = ns + in.pressure.size();
  std::vector<double> out;
  for (size_t k = 0; k < stages; ++k) {
    const double draw = in.draw[k_pos][std::min(k, ns - 1)];
    const double mag = std::max(0.0, in.gain[k_pos] * std::fabs(draw) + in.intercept[k_pos]);
    out.push_back(draw == 0.0 ? 0.0 : std::copysign(mag, draw));
  }
  return out;
}

struct StretchPreset {
  SaddleGeometry g;
  const StretchInputs *in;
  std::shared_ptr<SaddleStretchProbes> probes;
};

// The stretch options as the general scene's inputs: the frame drawn in plan at a, b, c, d (per
// edge, -bc_frame_points_interpolation axis) and held in height, the symmetry planes on rollers,
// the pressure cycle on the whole film, the arch (friction contact with its nodes off the frame),
// the scene's own report.
PetscErrorCode StretchPresetApply(MPI_Comm, StructureInputs *s, void *vctx) {
  const auto *p = (const StretchPreset *)vctx;
  const StretchInputs &in = *p->in;
  const SaddleGeometry &g = p->g;
  PetscFunctionBeginUser;
  BcInput frame;
  frame.group = "frame", frame.fix = "z", frame.interpolation = "axis";
  frame.points = {g.half_length, 0, 0, g.half_length, g.half_span, 0, g.arch_x, g.half_span, 0, 0, g.half_span, 0};
  frame.point_names = {"draw_a", "draw_b", "draw_c", "draw_d"};
  // Point-major: a, b, c, d, each its values per stage. a moves in x, c and d in y, b in both.
  const std::vector<double> motion[4] = {BoundaryMotion(in, 0), BoundaryMotion(in, 1), BoundaryMotion(in, 2),
                                         BoundaryMotion(in, 3)};
  const std::vector<double> zero(motion[0].size(), 0.0);
  const bool moves[2][4] = {{true, true, false, false}, {false, true, true, true}};
  for (int c = 0; c < 2; ++c) {
    frame.move[c].option = c == 0 ? "-saddle_draw_a/b" : "-saddle_draw_b/c/d";
    for (int k = 0; k < 4; ++k) {
      const std::vector<double> &v = moves[c][k] ? motion[k] : zero;
      frame.move[c].values.insert(frame.move[c].values.end(), v.begin(), v.end());
    }
  }
  s->bcs.push_back(frame);
  for (const auto &gf : {std::make_pair("sym_x", "x"), std::make_pair("sym_y", "y")}) {
    s->bcs.push_back(BcInput());
    s->bcs.back().group = gf.first, s->bcs.back().fix = gf.second;
  }
  if (!in.pressure.empty()) {
    // In MPa per stage times 1 (the load is the schedule's value, shown in kPa).
    StageArray pr{"-saddle_pressure_cycle", std::vector<double>(in.draw[0].size(), 0.0), 1.0};
    for (double x : in.pressure) pr.values.push_back(1e-3 * x);  // kPa -> MPa
    bool found = false;
    for (FilmInput &f : s->films)
      if (f.group == "all") f.pressure = pr, f.pressure_schedule = "pressure", found = true;
    if (!found) {
      s->films.push_back(FilmInput());
      s->films.back().group = "all", s->films.back().pressure = pr, s->films.back().pressure_schedule = "pressure";
    }
  }
  // The arch: a circle in the plane X = 1000 through (Y = +-W, z = 0) and (0, H).
  RigidInput arch;
  arch.name = "arch", arch.type = "arch", arch.radius = g.ArchRadius();
  arch.centre[0] = g.arch_x, arch.centre[1] = 0.0, arch.centre[2] = g.rise - arch.radius;
  arch.axis[0] = 1.0, arch.axis[1] = 0.0, arch.axis[2] = 0.0;
  arch.nodes = {"arch"};
  s->rigids.push_back(arch);
  s->check.name = "saddle_stretch", s->check.rise = g.rise, s->check.saddle = p->probes, s->check.given = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SaddleStretchSetup(MPI_Comm comm, const SaddleGeometry &g, SceneSpec *scene, SceneObserver *observer) {
  StretchInputs in;
  PetscFunctionBeginUser;
  PetscCall(ReadStretchOptions(comm, scene->stage_overrides, &in));
  auto c = std::make_shared<SaddleStretchProbes>();
  c->g = g;
  c->part_a = {in.part_a[0], in.part_a[1], in.part_a[2], in.part_a[3]};
  c->part_b = {in.part_b[0], in.part_b[1], in.part_b[2], in.part_b[3]};
  c->elem_i_at[0] = in.elem_i[0], c->elem_i_at[1] = in.elem_i[1];
  c->elem_ii_at[0] = in.elem_ii[0], c->elem_ii_at[1] = in.elem_ii[1];
  c->slide_at = in.slides;
  c->history = in.history;
  if (in.reference == 1) {
    const PatternStrips strips{{"middle", "corner"},
                               "-saddle_reference pattern",
                               "saddle",
                               "the flat pattern needs the strips of a form-found surface (-mesh_file written by "
                               "options/saddle/ff_*.opts), not the PD start"};
    PetscCall(PatternReference(comm, scene->mesh, strips, &scene->element_reference));
  }
  StretchPreset preset{g, &in, c};
  PetscCall(StructureBuild(comm, scene, observer, true, StretchPresetApply, &preset));
  const size_t stages = in.draw[0].size() + in.pressure.size();
  // A drawing of zeros everywhere (no pressure) makes no schedule of the frame's named points:
  // one of zeros keeps the scene's stages.
  if (scene->schedules.empty()) scene->AddSchedule({"draw_a", 0.0, std::vector<double>(stages, 0.0), "mm"});
  if (in.reference == 1) {  // not element_reference.empty(): that list is on rank 0 only
    // The film is laid on in the first drawing step: the reference goes from the surface to the
    // flat pattern while the frame draws (pattern_reference.cpp says why not before it).
    const int sl = scene->AddSchedule({"lay_on", 0.0, std::vector<double>(stages, 1.0), ""});
    scene->reference_blend = {{1.0, 0.0}, {sl, -1}};
  }
  // The arch's search tolerance as this scene always had it (the general scene's: 1e-4 of the
  // structure's size).
  scene->contact.search_tol = 1e-3 * g.rise;
  scene->stage_options = {{"saddle_draw_a", in.draw[0]}, {"saddle_draw_b", in.draw[1]}, {"saddle_draw_c", in.draw[2]},
                          {"saddle_draw_d", in.draw[3]}, {"saddle_pressure_cycle", in.pressure}};
  // What the figures and reports read back from the results (defaults included).
  scene->result_attributes = {{"saddle_drawing_stages", {(double)in.draw[0].size()}},
                              {"saddle_part_A", in.part_a},
                              {"saddle_part_B", in.part_b},
                              {"saddle_arch_x", {g.arch_x}},
                              {"saddle_element_I", in.elem_i},
                              {"saddle_element_II", in.elem_ii},
                              {"saddle_slide_points", in.slides},
                              {"saddle_pressure_cycle", in.pressure}};
  PetscFunctionReturn(0);
}

} // namespace etfe
