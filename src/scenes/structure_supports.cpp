// The general scene's stages and supports (structure_inputs.h).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

// Values per stage of an array given at `points` control points (1: no points).
size_t StagesOf(const StageArray &a, size_t points) { return a.values.size() / std::max<size_t>(points, 1); }

// Where a point projects onto the polyline through `pts` (3 per point): segment k and the
// fraction s along it (the nearest segment in 3D; the first of equals); returns the distance.
double ProjectOnPolyline(const std::vector<double> &pts, const double *x, int *k, double *s) {
  double best = INFINITY;
  const int n = (int)pts.size() / 3;
  for (int i = 0; i + 1 < n; ++i) {
    const double *a = &pts[3 * i], *b = &pts[3 * i + 3];
    double ab[3], ax[3], dot = 0, len2 = 0;
    for (int c = 0; c < 3; ++c) ab[c] = b[c] - a[c], ax[c] = x[c] - a[c], dot += ab[c] * ax[c], len2 += ab[c] * ab[c];
    const double t = len2 > 0 ? std::min(1.0, std::max(0.0, dot / len2)) : 0.0;
    double d2 = 0;
    for (int c = 0; c < 3; ++c) d2 += (ax[c] - t * ab[c]) * (ax[c] - t * ab[c]);
    if (d2 < best) best = d2, *k = i, *s = t;
  }
  return std::sqrt(best);
}

// -bc_<group>_points_interpolation axis: segment k runs along plan axis *axis (0 x, 1 y); the
// node's fraction s = (X - lo) / (hi - lo) along it from its lower end, which is point k + *low
// (0 or 1). Written as the saddle's frame always interpolated its drawing (Y/W, X/A,
// (X - A)/(L - A)), so the same nodes get the same bits; not clamped, as there (a node a
// round-off past an end is extrapolated by that much).
void AxisFraction(const std::vector<double> &pts, int k, const double *x, int *axis, int *low, double *s) {
  const double *a = &pts[3 * k], *b = &pts[3 * k + 3];
  *axis = std::fabs(b[0] - a[0]) >= std::fabs(b[1] - a[1]) ? 0 : 1;
  *low = a[*axis] <= b[*axis] ? 0 : 1;
  const double lo = *low == 0 ? a[*axis] : b[*axis], hi = *low == 0 ? b[*axis] : a[*axis];
  *s = (x[*axis] - lo) / (hi - lo);
}

// Axis interpolation's segment of a node: the first (in the points' order) whose axis range
// holds the node's coordinate and whose line it lies on in plan, within 1e-6 of the points'
// largest plan coordinate (the saddle's frame: the edge X = 2000 first, corner included, then
// Y = 1000 by X); false when none does (then the nearest, as for projection).
bool AxisSegment(const std::vector<double> &pts, const double *x, int *k) {
  double scale = 0.0;
  for (size_t i = 0; i < pts.size(); i += 3) scale = std::max({scale, std::fabs(pts[i]), std::fabs(pts[i + 1])});
  const double tol = 1e-6 * scale;
  for (int i = 0; 3 * (size_t)i + 3 < pts.size(); ++i) {
    const double *a = &pts[3 * i], *b = &pts[3 * i + 3];
    const int axis = std::fabs(b[0] - a[0]) >= std::fabs(b[1] - a[1]) ? 0 : 1, across = 1 - axis;
    const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
    if (std::fabs(x[across] - a[across]) < tol && x[axis] >= lo && x[axis] <= hi) return *k = i, true;
  }
  return false;
}

double PolylineLength(const std::vector<double> &pts) {
  double len = 0.0;
  for (size_t i = 3; i < pts.size(); i += 3)
    len += std::hypot(pts[i] - pts[i - 3], pts[i + 1] - pts[i - 2], pts[i + 2] - pts[i - 1]);
  return len;
}

// A node farther than this fraction of the polyline's length from it takes values meant for
// somewhere else: an open polyline drawn round a closed loop (its last edge then interpolated
// along the other three), or points given off the group (in plan, away from its heights).
constexpr double kPolylineFar = 0.1;

// Component c of the displacement that turns the stretched position x = (I + G) X about the z
// axis by the group's rotation: (R - I) x. An isotropic stretch (a pretensioned hub) is written
// (1 + g) (R - I) X, as the annulus scene always wrote it.
double RotationCoefficient(const BcInput &bc, const double *X, int c) {
  const double cs = std::cos(bc.rotation), sn = std::sin(bc.rotation);
  const std::vector<double> &G = bc.gradient;
  if (G.empty() || (G[1] == 0.0 && G[2] == 0.0 && G[0] == G[3])) {
    const double k = G.empty() ? 1.0 : 1 + G[0];
    return c == 0 ? k * ((cs - 1) * X[0] - sn * X[1]) : k * (sn * X[0] + (cs - 1) * X[1]);
  }
  const double x = (1 + G[0]) * X[0] + G[1] * X[1], y = G[2] * X[0] + (1 + G[3]) * X[1];
  return c == 0 ? (cs - 1) * x - sn * y : sn * x + (cs - 1) * y;
}

struct Held {
  ScheduledValue value;
  std::string group;
};

// Rank 0: adds (node, comp) = value unless the DOF is held already; a second value must agree
// with the first at every stage end (the schedules are piecewise linear in between).
bool AddConstraint(SceneSpec *scene, std::map<long, Held> *held, int node, int comp, const ScheduledValue &v,
                   const std::string &group, int stages, std::string *err) {
  const long key = 3L * node + comp;
  auto it = held->find(key);
  if (it == held->end()) {
    (*held)[key] = {v, group};
    scene->constraints.push_back({node, comp, v});
    return true;
  }
  for (int t = 0; t <= stages; ++t) {
    const double a = it->second.value.At(scene->schedules, t), b = v.At(scene->schedules, t);
    if (std::fabs(a - b) > 1e-9 * std::max(1.0, std::max(std::fabs(a), std::fabs(b)))) {
      const MeshData &m = scene->mesh;
      const long long tag = m.node_tags.empty() ? node : m.node_tags[node];
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "node %lld (at %g, %g, %g) of %s is in the node groups %s and %s, which prescribe its %c "
                    "displacement differently (%g and %g mm at the end of stage %d): give it the same value in both, "
                    "or take it out of one group",
                    tag, m.coords[3 * node], m.coords[3 * node + 1], m.coords[3 * node + 2], m.source.c_str(),
                    it->second.group.c_str(), group.c_str(), "xyz"[comp], a, b, t);
      return *err = buf, false;
    }
  }
  return true;
}

} // namespace

PetscErrorCode StructureStageCount(MPI_Comm comm, const StructureInputs &in, int *stages) {
  size_t longest = 0;
  std::string which;
  auto see = [&](const StageArray &a, size_t n) {
    if (n > longest) longest = n, which = a.option;
  };
  PetscFunctionBeginUser;
  for (const BcInput &bc : in.bcs) {
    for (const StageArray &a : bc.move) see(a, StagesOf(a, bc.points.size() / 3));
    see(bc.force, bc.force.values.size() / 3);
    see(bc.gradient_stages, bc.gradient_stages.values.size());
    see(bc.rotation_stages, bc.rotation_stages.values.size());
  }
  for (const FilmInput &f : in.films) see(f.pressure, f.pressure.values.size()), see(f.snow, f.snow.values.size());
  see(in.wind, in.wind.values.size());
  for (const ChamberInput &c : in.chambers) see(c.pressure, c.pressure.values.size());
  see(in.self_weight, in.self_weight.values.size());
  for (const CableInput &c : in.cables) see(c.weight, c.weight.values.size());
  PetscCheck(in.stages <= 0 || (size_t)in.stages >= longest, comm, PETSC_ERR_ARG_SIZ,
             "-structure_stages %d: %s gives %zu stages; raise -structure_stages or shorten the option",
             (int)in.stages, which.c_str(), longest);
  *stages = in.stages > 0 ? (int)in.stages : std::max<int>(1, (int)longest);
  PetscFunctionReturn(0);
}

int StructureAddSchedule(SceneSpec *scene, const std::string &name, const std::vector<double> &values, int stages,
                         const std::string &unit, double display_scale) {
  std::vector<double> v(values.begin(), values.begin() + std::min<size_t>(values.size(), stages));
  while ((int)v.size() < stages) v.push_back(v.empty() ? 0.0 : v.back());
  return scene->AddSchedule({name, 0.0, v, unit, display_scale});
}

PetscErrorCode StructureAddSupports(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  static const char *const comp_name[3] = {"ux", "uy", "uz"};
  std::map<long, Held> held;
  std::string err;
  PetscFunctionBeginUser;
  for (const BcInput &bc : in.bcs) {
    const size_t npts = bc.points.size() / 3;
    // Schedules on every rank (small); per component one per control point, or one.
    std::vector<int> ids[3];
    for (int c = 0; c < 3; ++c) {
      const StageArray &a = bc.move[c];
      if (!a.Given()) continue;
      PetscCheck(bc.fix.find("xyz"[c]) == std::string::npos, comm, PETSC_ERR_ARG_WRONG,
                 "node group %s: -bc_%s_fix holds %c and %s moves it; give one of them", bc.group.c_str(),
                 bc.group.c_str(), "xyz"[c], a.option.c_str());
      PetscCheck(npts == 0 || a.values.size() % npts == 0, comm, PETSC_ERR_ARG_SIZ,
                 "%s: %zu values for %zu control points (-bc_%s_points): give the same number of stages at each point",
                 a.option.c_str(), a.values.size(), npts, bc.group.c_str());
      const size_t per = StagesOf(a, npts);
      for (size_t p = 0; p < std::max<size_t>(npts, 1); ++p) {
        const std::vector<double> v(a.values.begin() + p * per, a.values.begin() + (p + 1) * per);
        std::string name = bc.group + "." + comp_name[c];
        if (npts) name += "@" + std::to_string(p + 1);
        if (!bc.point_names.empty() && npts && !scene->form_finding) {
          // A named point: no schedule for zeros (coefficient on none: the same 0), one schedule
          // for the components that move it alike (the saddle's corner b, drawn in x and y).
          int id = -1;
          bool zero = true;
          for (double x : v) zero &= x == 0.0;
          for (int e = 0; e < c && !zero && id < 0; ++e)
            if (ids[e].size() > p && ids[e][p] >= 0 && StagesOf(bc.move[e], npts) == per &&
                std::equal(v.begin(), v.end(), bc.move[e].values.begin() + p * per))
              id = ids[e][p];
          if (!zero && id < 0) id = StructureAddSchedule(scene, bc.point_names[p], v, stages, "mm", 1.0);
          ids[c].push_back(id);
          continue;
        }
        ids[c].push_back(StructureAddSchedule(scene, name, scene->form_finding ? std::vector<double>() : v, stages,
                                              "mm", a.coef != 0.0 ? a.coef : 1.0));
      }
    }
    int gradient = -1, rotation = -1;
    if (!bc.gradient.empty() || bc.rotation != 0.0)
      PetscCheck(!bc.move[0].Given() && !bc.move[1].Given(), comm, PETSC_ERR_ARG_WRONG,
                 "node group %s: -bc_%s_gradient / -bc_%s_rotation prescribe x and y and -bc_%s_ux/-bc_%s_uy move "
                 "them; give one of them",
                 bc.group.c_str(), bc.group.c_str(), bc.group.c_str(), bc.group.c_str(), bc.group.c_str());
    if (bc.rotation != 0.0)
      rotation = StructureAddSchedule(scene, bc.group + ".rotation",
                                      scene->form_finding ? std::vector<double>() : bc.rotation_stages.values, stages,
                                      "rad", bc.rotation);
    if (!bc.gradient.empty()) {
      gradient = StructureAddSchedule(scene, bc.group + ".gradient",
                                      scene->form_finding ? std::vector<double>() : bc.gradient_stages.values, stages,
                                      "", 1.0);
    }
    if (!SceneHoldsMesh(comm) || !err.empty()) continue;
    const auto it = scene->mesh.node_sets.find(bc.group);
    if (it == scene->mesh.node_sets.end() || it->second.empty()) {
      err = "-bc_" + bc.group + "_*: node group " + bc.group + " of " + scene->mesh.source + " has no nodes";
      continue;
    }
    if (npts) {
      // The group's node farthest from the control points' polyline, against its length.
      const MeshData &m = scene->mesh;
      int far = -1, k = 0;
      double worst = 0.0, s = 0.0;
      for (int n : it->second) {
        const double d = ProjectOnPolyline(bc.points, &m.coords[3 * n], &k, &s);
        if (d > worst) worst = d, far = n;
      }
      const double length = PolylineLength(bc.points);
      if (far >= 0 && worst > kPolylineFar * length) {
        const double *x = &m.coords[3 * far];
        const double *a = &bc.points[0], *b = &bc.points[3 * (npts - 1)];
        const bool open = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) > 0;
        char buf[900];
        std::snprintf(buf, sizeof buf,
                      "-bc_%s_points: node %lld of group %s (at %g, %g, %g) lies %g mm from the polyline through the "
                      "%zu control points (%g mm long), so it would take the values of the nearest point of a part "
                      "it is not on. The points are matched in 3D (give them with the nodes' heights)%s",
                      bc.group.c_str(), m.node_tags.empty() ? (long long)far : m.node_tags[far], bc.group.c_str(),
                      x[0] + 0.0, x[1] + 0.0, x[2] + 0.0, worst, npts, length,  // + 0.0: no "-0"
                      open ? "; a closed loop (a frame's four corners) repeats its first point as its last, "
                             "with its values"
                           : "");
        err = buf;
        continue;
      }
    }
    for (int n : it->second) {
      for (int c = 0; c < 3 && err.empty(); ++c) {
        ScheduledValue v;
        const double *X = &scene->mesh.coords[3 * n];
        if ((gradient >= 0 || rotation >= 0) && c < 2) {
          if (gradient >= 0) v = {{bc.gradient[2 * c] * X[0] + bc.gradient[2 * c + 1] * X[1], 0.0}, {gradient, -1}};
          if (rotation >= 0) {
            const double turn = RotationCoefficient(bc, X, c);
            v = gradient >= 0 ? ScheduledValue{{v.coef[0], turn}, {gradient, rotation}}
                              : ScheduledValue{{turn, 0.0}, {rotation, -1}};
          }
          AddConstraint(scene, &held, n, c, v, bc.group, stages, &err);
          continue;
        }
        if (ids[c].empty() && bc.fix.find("xyz"[c]) == std::string::npos) continue;
        if (ids[c].size() == 1) {
          v = {{bc.move[c].coef != 0.0 ? bc.move[c].coef : 1.0, 0.0}, {ids[c][0], -1}};
        } else if (!ids[c].empty()) {
          int k = 0;
          double s = 0.0;
          ProjectOnPolyline(bc.points, &scene->mesh.coords[3 * n], &k, &s);
          v = {{1.0 - s, s}, {ids[c][k], ids[c][k + 1]}};
          if (bc.interpolation == "axis") {
            int axis, low;
            AxisSegment(bc.points, &scene->mesh.coords[3 * n], &k);
            AxisFraction(bc.points, k, &scene->mesh.coords[3 * n], &axis, &low, &s);
            v = {{1.0 - s, s}, {ids[c][k + low], ids[c][k + 1 - low]}};
          }
        }
        AddConstraint(scene, &held, n, c, v, bc.group, stages, &err);
      }
    }
  }
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  PetscFunctionReturn(0);
}

} // namespace etfe
