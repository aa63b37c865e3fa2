// The general scene's loads and rigid supports (structure_inputs.h). Pressure and wind follow the
// film (follower pressure on the elements of a surface group); snow, self-weight and group forces
// are dead nodal forces, each node taking its share (plan area, area, length along the group).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "etfe/kernels/circle_fit.h"
#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "structure_inputs.h"

namespace etfe {

void StructureTriangleNormal(const MeshData &m, int e, double n[3]) {
  const int *t = &m.triangles[3 * e];
  const double *a = &m.coords[3 * t[0]], *b = &m.coords[3 * t[1]], *c = &m.coords[3 * t[2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
}

std::vector<int> StructureHeldMask(const SceneSpec &scene) {
  std::vector<int> held(scene.mesh.NumNodes(), 0);
  for (const DofConstraint &d : scene.constraints) held[d.node] |= 1 << d.comp;
  return held;
}

namespace {

const double kPaToMPa = 1e-3;


const std::vector<int> *ElementGroup(const MeshData &m, const std::string &g) {
  const auto it = m.element_sets.find(g);
  return it == m.element_sets.end() ? nullptr : &it->second;
}

// Rank 0: per node of a surface group, its share of the group's plan area.
std::map<int, double> PlanAreaShares(const MeshData &m, const std::vector<int> &elements) {
  std::map<int, double> share;
  for (int e : elements) {
    double n[3];
    StructureTriangleNormal(m, e, n);
    const double area = 0.5 * std::fabs(n[2]);
    for (int a = 0; a < 3; ++a) share[m.triangles[3 * e + a]] += area / 3.0;
  }
  return share;
}

// Rank 0: per node of a node group, its fraction of the group's length (the mesh edges joining
// two of its nodes, half to each end); a group without such edges (points) shares equally.
std::map<int, double> LengthFractions(const MeshData &m, const std::vector<int> &nodes) {
  const std::set<int> in(nodes.begin(), nodes.end());
  std::set<std::pair<int, int>> edges;
  for (int e = 0; e < m.NumElements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[3 * e + k], b = m.triangles[3 * e + (k + 1) % 3];
      if (in.count(a) && in.count(b)) edges.insert({std::min(a, b), std::max(a, b)});
    }
  std::map<int, double> share;
  double total = 0.0;
  for (const auto &ed : edges) {
    const double *x = &m.coords[3 * ed.first], *y = &m.coords[3 * ed.second];
    const double len = std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
    share[ed.first] += 0.5 * len, share[ed.second] += 0.5 * len, total += len;
  }
  if (edges.empty())
    for (int n : nodes) share[n] = 1.0, total += 1.0;
  for (auto &kv : share) kv.second /= total;
  return share;
}

// A load value outside what a 0.05-0.5 mm foil carries is most likely in the wrong unit: said
// before the run (kPa given as Pa: 300 instead of 0.3), refused where nothing could carry it.
PetscErrorCode CheckLoadScale(MPI_Comm comm, const StageArray &a) {
  double peak = 0.0;
  char value[32];  // snprintf: PETSc's %g would print 5000 as "5000."
  PetscFunctionBeginUser;
  for (double x : a.values) peak = std::max(peak, std::fabs(x));
  std::snprintf(value, sizeof value, "%g", peak);
  PetscCheck(peak <= 1000.0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%s reaches %s kPa: no foil carries that (ETFE cushions run at 0.2-0.8 kPa, snow and wind reach a few "
             "kPa); the option is in kPa, so 300 Pa is 0.3",
             a.option.c_str(), value);
  if (peak > 20.0)
    PetscCall(PetscPrintf(comm,
                          "warning: %s reaches %s kPa, far above what a 0.05-0.5 mm foil carries (a few kPa); the option "
                          "is in kPa: was it given in Pa?\n",
                          a.option.c_str(), value));
  PetscFunctionReturn(0);
}

// Dead nodal forces: value(t) = coef x schedule(t) along comp, per node.
void AddDeadForces(const std::map<int, double> &coef, int comp, int schedule, SceneSpec *scene) {
  for (const auto &kv : coef)
    if (kv.second != 0.0) scene->nodal_forces.push_back({kv.first, comp, {{kv.second, 0.0}, {schedule, -1}}});
}

PetscErrorCode AddFilmLoads(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  const bool mesh = SceneHoldsMesh(comm);
  int wind = -1;
  bool any_cp = false;
  PetscFunctionBeginUser;
  for (const FilmInput &f : in.films) any_cp |= f.wind_given;
  PetscCheck(any_cp == in.wind.Given(), comm, PETSC_ERR_ARG_WRONG,
             any_cp ? "-film_<group>_wind_cp given but no -structure_wind (the velocity pressure per stage, kPa)"
                    : "-structure_wind given but no surface group has -film_<group>_wind_cp (its pressure coefficient)");
  if (in.wind.Given()) {
    PetscCall(CheckLoadScale(comm, in.wind));
    std::vector<double> q;
    for (double x : in.wind.values) q.push_back(kPaToMPa * x);
    wind = StructureAddSchedule(scene, "wind", q, stages, "kPa", 1e3);
  }
  for (const FilmInput &f : in.films) {
    const std::vector<int> *els = mesh ? ElementGroup(m, f.group) : nullptr;
    if (f.pressure.Given()) {
      // A built-in scene's pressure (coef, MPa, times multipliers) was checked by that scene.
      const double coef = f.pressure.coef != 0.0 ? f.pressure.coef : 1.0;
      if (f.pressure.coef == 0.0) PetscCall(CheckLoadScale(comm, f.pressure));
      std::vector<double> p;
      for (double x : f.pressure.values) p.push_back(f.pressure.coef != 0.0 ? x : kPaToMPa * x);
      const std::string name = f.pressure_schedule.empty() ? f.group + ".pressure" : f.pressure_schedule;
      const int s = StructureAddSchedule(scene, name, p, stages, "kPa", 1e3 * coef);
      scene->pressures.push_back({els ? *els : std::vector<int>(), {{coef, 0.0}, {s, -1}}});
    }
    // cp > 0 pushes onto the face the normal points to: a pressure against the normal.
    if (f.wind_given) scene->pressures.push_back({els ? *els : std::vector<int>(), {{-f.wind_cp, 0.0}, {wind, -1}}});
    if (f.snow.Given()) {
      PetscCall(CheckLoadScale(comm, f.snow));
      std::vector<double> s;
      for (double x : f.snow.values) s.push_back(-kPaToMPa * x);  // downward
      const int id = StructureAddSchedule(scene, f.group + ".snow", s, stages, "kPa", -1e3);
      if (els) AddDeadForces(PlanAreaShares(m, *els), 2, id, scene);
    }
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode StructureAddLoads(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  const MeshData &m = scene->mesh;
  const bool mesh = SceneHoldsMesh(comm);
  PetscFunctionBeginUser;
  scene->loads_checked = true;  // each load option against its scale (CheckLoadScale), by name
  PetscCall(AddFilmLoads(comm, in, stages, scene));
  if (in.self_weight.Given()) {
    // Weight per area rho g h [N/mm^2], with the thickness the membrane will take.
    PetscReal h = scene->thickness;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-membrane_thickness", &h, nullptr));
    const double w = in.density * 9.81 * h * 1e-9;
    std::vector<double> v;
    for (double x : in.self_weight.values) v.push_back(-w * x);
    const int id = StructureAddSchedule(scene, "self_weight", v, stages, "", -1.0 / w);
    if (mesh) {
      // Per node a third of its elements' areas, each in proportion to its thickness (-film_<group>_thickness).
      std::map<int, double> share;
      for (int e = 0; e < m.NumElements(); ++e) {
        const double he = scene->element_thickness.empty() || scene->element_thickness[e] == 0 ? h
                                                                                                : scene->element_thickness[e];
        double n[3];
        StructureTriangleNormal(m, e, n);
        const double third = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 3.0 * he / h;
        for (int a = 0; a < 3; ++a) share[m.triangles[3 * e + a]] += third;
      }
      AddDeadForces(share, 2, id, scene);
    }
  }
  for (const BcInput &bc : in.bcs) {
    if (!bc.force.Given()) continue;
    std::map<int, double> share;
    if (mesh) share = LengthFractions(m, m.node_sets.at(bc.group));
    for (int c = 0; c < 3; ++c) {
      std::vector<double> v;
      for (size_t k = c; k < bc.force.values.size(); k += 3) v.push_back(bc.force.values[k]);
      const int id = StructureAddSchedule(scene, bc.group + ".f" + "xyz"[c], v, stages, "N", 1.0);
      if (std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; })) AddDeadForces(share, c, id, scene);
    }
  }
  PetscFunctionReturn(0);
}

namespace {

// type curve: the circle through the group's nodes, fitted on rank 0 and sent to every rank.
PetscErrorCode FitRigidCurve(MPI_Comm comm, const MeshData &m, const RigidInput &r, SupportSpec *s) {
  double v[8] = {0};
  int ok = 1;
  std::string err;
  PetscFunctionBeginUser;
  if (SceneHoldsMesh(comm)) {
    std::vector<double> pts;
    for (int n : m.node_sets.at(r.curve)) pts.insert(pts.end(), &m.coords[3 * n], &m.coords[3 * n] + 3);
    CircleFit fit;
    if (!FitCircle(pts.data(), (int)pts.size() / 3, &fit)) {
      ok = 0, err = "-rigid_" + r.name + "_curve " + r.curve + ": its nodes fix no circle (fewer than 3, or on a line)";
    } else if (fit.max_deviation > 1e-3 * fit.radius) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "-rigid_%s_curve %s: the nodes are no circular arc (the best circle, radius %g mm, misses one by "
                    "%g mm); give the support as -rigid_%s_type cylinder with its centre, axis and radius",
                    r.name.c_str(), r.curve.c_str(), fit.radius, fit.max_deviation, r.name.c_str());
      ok = 0, err = buf;
    } else {
      for (int i = 0; i < 3; ++i) v[i] = fit.centre[i], v[3 + i] = fit.axis[i];
      v[6] = fit.radius, v[7] = fit.max_deviation;
    }
  }
  PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_ARG_WRONG));
  PetscCallMPI(MPI_Bcast(v, 8, MPI_DOUBLE, 0, comm));
  for (int i = 0; i < 3; ++i) s->centre[i] = v[i], s->axis[i] = v[3 + i];
  s->radius = v[6];
  s->type = "arch";
  PetscCall(PetscPrintf(comm,
                        "structure: rigid support %s = the circle through node group %s: centre (%.4f, %.4f, %.4f) mm, "
                        "axis (%.6f, %.6f, %.6f), radius %.4f mm (largest deviation %.2e mm)\n",
                        r.name.c_str(), r.curve.c_str(), v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]));
  PetscFunctionReturn(0);
}

} // namespace

// How many of a chamber's triangles share each edge (node pair, smaller first): 1 on its open edges.
static std::map<std::pair<int, int>, int> ChamberEdgeUses(const MeshData &m, const ChamberInput &c) {
  std::map<std::pair<int, int>, int> uses;
  for (const std::string &g : c.groups)
    for (int e : m.element_sets.at(g))
      for (int k = 0; k < 3; ++k) {
        const int a = m.triangles[3 * e + k], b = m.triangles[3 * e + (k + 1) % 3];
        uses[{std::min(a, b), std::max(a, b)}]++;
      }
  return uses;
}

// Rank 0: a chamber's volume is exact only if it is closed: every edge of its boundary surface that
// only one of its triangles has must stay on a plane through the origin (a clamped rim, a symmetry
// plane). Returns "" or a message naming the first edge that can move off it.
std::string ChamberOpenEdge(const MeshData &m, const ChamberInput &c, const std::vector<int> &held_mask) {
  const std::map<std::pair<int, int>, int> uses = ChamberEdgeUses(m, c);
  for (const auto &kv : uses) {
    if (kv.second != 1) continue;
    const double *a = &m.coords[3 * kv.first.first], *b = &m.coords[3 * kv.first.second];
    double u[3], v[3], n[3];
    for (int i = 0; i < 3; ++i) u[i] = a[i] - c.origin[i], v[i] = b[i] - c.origin[i];
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
    const double len = std::hypot(n[0], n[1], n[2]);
    if (len == 0) continue;  // the edge runs through the origin
    for (int node : {kv.first.first, kv.first.second}) {
      double off = 0.0;  // the part of the plane's normal the node may move along
      for (int i = 0; i < 3; ++i)
        if (!(held_mask[node] & (1 << i))) off += n[i] * n[i];
      if (std::sqrt(off) > 1e-6 * len) {
        const long long tag = m.node_tags.empty() ? node : m.node_tags[node];
        return "chamber " + c.name + " is not closed: node " + std::to_string(tag) + " at (" + std::to_string(a[0]) +
               ", " + std::to_string(a[1]) + ", " + std::to_string(a[2]) +
               ") lies on an edge of its surfaces that no other of its triangles shares, and it may move off the "
               "plane through -chamber_" + c.name + "_origin that closes it: add the surface that closes it to "
               "-chamber_" + c.name + "_groups, clamp that edge (-bc_<group>_fix xyz), or put the origin on the "
               "symmetry planes that close it";
      }
    }
  }
  return "";
}

// Rank 0: where a chamber's open edges all lie in one plane (a rim clamped in a flat frame, a flat
// base), that plane closes it, so the origin must lie on it: off it, the volume is closed by a
// cone from the origin to the rim instead, which the start then finds negative or too large (and
// "flip the signs" would not be the way out). Returns "" or the message; a rim that is not flat
// (symmetry planes meeting, a warped clamped edge) is left to the other checks.
std::string ChamberOriginOffRim(const MeshData &m, const ChamberInput &c) {
  const std::map<std::pair<int, int>, int> uses = ChamberEdgeUses(m, c);
  std::set<int> rim;
  for (const auto &kv : uses)
    if (kv.second == 1) rim.insert(kv.first.first), rim.insert(kv.first.second);
  if (rim.size() < 3) return "";
  auto x = [&](int n) { return &m.coords[3 * n]; };
  auto dist = [](const double *p, const double *q) { return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]); };
  // The plane through three rim nodes far apart: a, the node farthest from it, the node farthest
  // from the line through both.
  const int a = *rim.begin();
  int b = a, c3 = a;
  for (int n : rim)
    if (dist(x(n), x(a)) > dist(x(b), x(a))) b = n;
  const double extent = dist(x(a), x(b));
  double ab[3], nrm[3] = {0, 0, 0}, best = 0.0;
  for (int i = 0; i < 3; ++i) ab[i] = x(b)[i] - x(a)[i];
  for (int n : rim) {
    const double an[3] = {x(n)[0] - x(a)[0], x(n)[1] - x(a)[1], x(n)[2] - x(a)[2]};
    const double cr[3] = {ab[1] * an[2] - ab[2] * an[1], ab[2] * an[0] - ab[0] * an[2], ab[0] * an[1] - ab[1] * an[0]};
    const double len = std::hypot(cr[0], cr[1], cr[2]);
    if (len > best) best = len, c3 = n, nrm[0] = cr[0] / len, nrm[1] = cr[1] / len, nrm[2] = cr[2] / len;
  }
  if (!(extent > 0) || !(best > 1e-6 * extent * extent) || c3 == a) return "";  // the rim is a line
  auto off = [&](const double *p) {
    return std::fabs((p[0] - x(a)[0]) * nrm[0] + (p[1] - x(a)[1]) * nrm[1] + (p[2] - x(a)[2]) * nrm[2]);
  };
  for (int n : rim)
    if (off(x(n)) > 1e-6 * extent) return "";  // not flat
  const double d = off(c.origin.data());
  if (d <= 1e-3 * extent) return "";
  double centre[3] = {0, 0, 0};
  for (int n : rim)
    for (int i = 0; i < 3; ++i) centre[i] += x(n)[i] / rim.size();
  // Round-off (1e-14 of a coordinate) printed as 0.
  auto tidy = [](double v, double scale) { return std::fabs(v) < 1e-9 * scale ? 0.0 : v; };
  const double p0[3] = {tidy(x(a)[0], extent), tidy(x(a)[1], extent), tidy(x(a)[2], extent)};
  for (int i = 0; i < 3; ++i) nrm[i] = tidy(nrm[i], 1.0), centre[i] = tidy(centre[i], extent);
  char buf[700];
  std::snprintf(buf, sizeof buf,
                "chamber %s: -chamber_%s_origin (%g, %g, %g) lies %g mm off the plane of its open rim (the %zu nodes "
                "on edges that no other of its triangles shares lie in the plane through (%g, %g, %g) with normal "
                "(%g, %g, %g)): that plane closes the chamber, and the volume is measured from the origin, so the "
                "origin must lie on it. Give a point of that plane as -chamber_%s_origin (e.g. %g,%g,%g, the rim's "
                "centre)",
                c.name.c_str(), c.name.c_str(), c.origin[0], c.origin[1], c.origin[2], d, rim.size(), p0[0], p0[1],
                p0[2], nrm[0], nrm[1], nrm[2], c.name.c_str(), centre[0], centre[1], centre[2]);
  return buf;
}

// Rank 0: the chamber's triangles, each turned by its group's sign, must all face the same way
// (outward), or the divergence theorem adds volumes of opposite sign: two of them sharing an edge
// then run along it in the same direction. Returns "" or a message naming the edge and groups.
std::string ChamberMisorientedEdge(const MeshData &m, const ChamberInput &c) {
  std::map<std::pair<int, int>, size_t> first;  // directed edge -> group index of its triangle
  for (size_t g = 0; g < c.groups.size(); ++g)
    for (int e : m.element_sets.at(c.groups[g]))
      for (int k = 0; k < 3; ++k) {
        int a = m.triangles[3 * e + k], b = m.triangles[3 * e + (k + 1) % 3];
        if (c.signs[g] < 0) std::swap(a, b);
        const auto seen = first.emplace(std::make_pair(a, b), g);
        if (seen.second) continue;
        auto tag = [&](int n) { return std::to_string(m.node_tags.empty() ? n : m.node_tags[n]); };
        const std::string &g0 = c.groups[seen.first->second];
        return "chamber " + c.name + ": its surfaces are not oriented consistently: two of its triangles (groups " +
               g0 + " and " + c.groups[g] + ") run along the edge from node " + tag(a) + " to node " + tag(b) +
               " in the same direction, so one faces into the chamber and one out of it. " +
               (g0 == c.groups[g] ? "Number group " + g0 + "'s triangles all one way round (counter-clockwise seen from one side)"
                                  : "Flip the sign of one of them in -chamber_" + c.name + "_signs");
      }
  return "";
}

PetscErrorCode StructureAddChambers(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  std::vector<int> held_mask;  // rank 0: per node, bit i set where component i is prescribed
  std::string err;
  PetscFunctionBeginUser;
  if (SceneHoldsMesh(comm) && !in.chambers.empty()) {
    held_mask = StructureHeldMask(*scene);
    for (const ChamberInput &c : in.chambers)
      if (err.empty()) err = ChamberOpenEdge(scene->mesh, c, held_mask);
    for (const ChamberInput &c : in.chambers)
      if (err.empty()) err = ChamberMisorientedEdge(scene->mesh, c);
    for (const ChamberInput &c : in.chambers)
      if (err.empty()) err = ChamberOriginOffRim(scene->mesh, c);
  }
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  scene->atmosphere = kPaToMPa * in.atmosphere;
  for (size_t k = 0; k < in.chambers.size(); ++k) {
    const ChamberInput &c = in.chambers[k];
    ChamberSpec spec;
    spec.name = c.name, spec.groups = c.groups, spec.signs = c.signs;
    for (int i = 0; i < 3; ++i) spec.origin[i] = c.origin[i];
    std::vector<double> p;
    for (double x : c.pressure.values) p.push_back(kPaToMPa * x);
    for (double x : c.pressure.values)
      PetscCheck(x > -in.atmosphere, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "%s: a gauge pressure of %g kPa is below minus the atmosphere (%g kPa): no gas is that thin",
                 c.pressure.option.c_str(), x, in.atmosphere);
    if (c.pressure.Given()) PetscCall(CheckLoadScale(comm, c.pressure));
    const int id = StructureAddSchedule(scene, c.name + ".p", p, stages, "kPa", 1e3);
    spec.supplied = {{1.0, 0.0}, {id, -1}};
    PetscCheck(c.sealed_from_stage <= stages, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-chamber_%s_sealed_from_stage %d: the analysis has %d stages", c.name.c_str(), (int)c.sealed_from_stage,
               stages);
    spec.sealed_from_stage = (int)c.sealed_from_stage;
    PetscCheck(c.sealed.empty() || (int)c.sealed.size() == stages, comm, PETSC_ERR_ARG_SIZ,
               "-chamber_%s_sealed: one flag per stage (%d given, the analysis has %d stages)", c.name.c_str(),
               (int)c.sealed.size(), stages);
    for (double f : c.sealed) spec.sealed_stages.push_back(f != 0.0);
    spec.kappa = c.kappa;
    spec.extra_volume = 1e9 * c.extra_volume;  // m^3 -> mm^3
    scene->chambers.push_back(spec);
    for (size_t g = 0; g < c.groups.size(); ++g) {
      PressureSpec load;
      if (SceneHoldsMesh(comm)) load.elements = scene->mesh.element_sets.at(c.groups[g]);
      load.chamber = (int)k, load.sign = c.signs[g];
      scene->pressures.push_back(load);
    }
  }
  PetscFunctionReturn(0);
}

namespace {

// Rank 0: each element's thickness, MD and law from the surface groups that set them; "" or the
// message naming an element two groups give different values.
PetscErrorCode FillFilmParts(const StructureInputs &in, bool any_h, bool any_md, SceneSpec *scene, std::string *err) {
  MeshData &m = scene->mesh;
  PetscFunctionBeginUser;
  // Each element takes a group's value; two groups giving it different values is an error.
  std::vector<std::string> h_from(m.NumElements()), md_from(m.NumElements()), law_from(m.NumElements());
  if (any_h) scene->element_thickness.assign(m.NumElements(), 0.0);  // 0: the default, filled in by the problem
  if (!scene->material_prefixes.empty()) scene->element_material.assign(m.NumElements(), 0);  // 0: the film's law
  int law = 0;  // the group's law among material_prefixes (1-based, as element_material)
  if (any_md)
    for (int e = 0; e < m.NumElements(); ++e) scene->element_md.insert(scene->element_md.end(), in.md, in.md + 3);
  for (const FilmInput &f : in.films) {
    const std::vector<int> &els = m.element_sets.at(f.group);
    double axis[3] = {0, 0, 0};
    if (f.md_strip) {
      std::vector<double> pts;
      for (int e : els)
        for (int a = 0; a < 3; ++a) pts.insert(pts.end(), &m.coords[3 * m.triangles[3 * e + a]], &m.coords[3 * m.triangles[3 * e + a]] + 3);
      LongAxis(pts.data(), (int)pts.size() / 3, axis);
      char line[200];
      std::snprintf(line, sizeof line, "structure: film group %s: MD along its long axis (%.4f, %.4f, %.4f)\n",
                    f.group.c_str(), axis[0], axis[1], axis[2]);
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s", line));
    } else if (!f.md.empty()) {
      for (int i = 0; i < 3; ++i) axis[i] = f.md[i];
    }
    const bool md = f.md_strip || !f.md.empty();
    if (f.own_material) ++law;
    for (int e : els) {
      if (f.own_material) {
        // Two laws are not compared (a law is many options): an element may take one group's only.
        if (!law_from[e].empty())
          *err = "element " + std::to_string(e) + " is in the surface groups " + law_from[e] + " and " + f.group +
                 ", which both give it a law of their own (-film_<group>_material_*): give the law to one of them";
        scene->element_material[e] = law, law_from[e] = f.group;
      }
      if (f.thickness > 0) {
        if (!h_from[e].empty() && scene->element_thickness[e] != f.thickness)
          *err = "element " + std::to_string(e) + " is in the surface groups " + h_from[e] + " and " + f.group +
                 ", which give it different thicknesses (-film_<group>_thickness): give one of them";
        scene->element_thickness[e] = f.thickness, h_from[e] = f.group;
      }
      if (md) {
        double *d = &scene->element_md[3 * (size_t)e];
        if (!md_from[e].empty() && (d[0] != axis[0] || d[1] != axis[1] || d[2] != axis[2]))
          *err = "element " + std::to_string(e) + " is in the surface groups " + md_from[e] + " and " + f.group +
                 ", which give it different MD directions (-film_<group>_md): give one of them";
        for (int i = 0; i < 3; ++i) d[i] = axis[i];
        md_from[e] = f.group;
      }
    }
  }
  PetscFunctionReturn(0);
}

// An MD direction within this angle's sine of the element's plane normal has no direction in the
// film: the element's frame then falls back to its first edge (MembraneReferenceBuild).
constexpr double kMdNormalSin = 0.1;  // 5.7 degrees

// Rank 0: the MD direction against the film: refused where it is normal to every element (the
// MD would be each element's first edge), a warning where it is normal to some.
std::string CheckMdAcrossFilm(const StructureInputs &in, const SceneSpec &scene, std::string *warning) {
  const MeshData &m = scene.mesh;
  int count = 0, first = -1;
  for (int e = 0; e < m.NumElements(); ++e) {
    const double *md = scene.element_md.empty() ? in.md : &scene.element_md[3 * (size_t)e];
    double n[3];
    StructureTriangleNormal(m, e, n);
    const double nn = std::hypot(n[0], n[1], n[2]), mm = std::hypot(md[0], md[1], md[2]);
    if (!(nn > 0) || !(mm > 0)) continue;
    const double along = (md[0] * n[0] + md[1] * n[1] + md[2] * n[2]) / (nn * mm);  // cosine to the normal
    if (std::sqrt(std::max(0.0, 1.0 - along * along)) < kMdNormalSin) count++, first = first < 0 ? e : first;
  }
  if (count == 0) return "";
  const double *md = scene.element_md.empty() ? in.md : &scene.element_md[3 * (size_t)first];
  const char *option = scene.element_md.empty() ? "-structure_md" : "-structure_md or -film_<group>_md";
  char buf[700];
  std::snprintf(buf, sizeof buf,
                "the MD (roll) direction (%g, %g, %g) of %s is within %.1f degrees of the normal of %d of the film's %d "
                "elements (the first: element %d): those take its projection onto their plane as MD, which their "
                "slightest tilt turns any way (exactly normal: the element's first edge). Give a direction along the "
                "film (a flat roof in plan: x or y; -film_<group>_md strip: a strip's long axis)",
                md[0], md[1], md[2], option, std::asin(kMdNormalSin) * 180.0 / M_PI, count, m.NumElements(), first);
  if (count == m.NumElements()) return buf;
  *warning = buf;
  return "";
}

} // namespace

PetscErrorCode StructureFilmParts(MPI_Comm comm, const StructureInputs &in, SceneSpec *scene) {
  bool any_h = false, any_md = false;
  std::string err, warning;
  PetscFunctionBeginUser;
  for (const FilmInput &f : in.films) any_h |= f.thickness > 0, any_md |= f.md_strip || !f.md.empty();
  // The groups with a law of their own, in the films' order (every rank: the laws are made on each).
  for (const FilmInput &f : in.films)
    if (f.own_material) scene->material_prefixes.push_back("film_" + f.group + "_");
  // Rank 0 holds the mesh; every rank takes its outcome (Rank0Outcome is collective).
  if (SceneHoldsMesh(comm)) {
    if (any_h || any_md || !scene->material_prefixes.empty()) PetscCall(FillFilmParts(in, any_h, any_md, scene, &err));
    if (err.empty()) err = CheckMdAcrossFilm(in, *scene, &warning);
  }
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  if (!warning.empty()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "etfe: warning: %s\n", warning.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode StructureAddRigid(MPI_Comm comm, const StructureInputs &in, SceneSpec *scene) {
  MeshData &m = scene->mesh;
  PetscFunctionBeginUser;
  if (in.rigids.empty()) PetscFunctionReturn(0);
  for (const RigidInput &r : in.rigids) {
    SupportSpec s;
    s.name = r.name;
    s.type = r.type;
    // Its own candidates where it names node groups (with two supports in reach of a node, the
    // node pairs with the one whose groups hold it).
    if (!r.nodes.empty() && in.rigids.size() > 1) s.node_set = "structure_contact_" + r.name;
    if (r.type == "curve") {
      PetscCall(FitRigidCurve(comm, m, r, &s));
    } else {
      for (int i = 0; i < 3; ++i) s.centre[i] = r.centre[i], s.axis[i] = r.axis[i];
      s.radius = r.radius;
    }
    scene->contact.supports.push_back(s);
  }
  scene->contact.active = true;
  scene->contact.node_set = "structure_contact";
  double diag = 0.0;
  if (SceneHoldsMesh(comm)) {
    // Candidates: each support's node groups (or every node), without the nodes whose three
    // displacements are prescribed unless the support grips them.
    std::vector<int> held(m.NumNodes(), 0);
    for (const DofConstraint &c : scene->constraints) held[c.node]++;
    std::vector<char> cand(m.NumNodes(), 0);
    for (size_t k = 0; k < in.rigids.size(); ++k) {
      const RigidInput &r = in.rigids[k];
      std::vector<char> mine(m.NumNodes(), r.nodes.empty() ? 1 : 0);
      for (const std::string &g : r.nodes)
        for (int n : m.node_sets.at(g)) mine[n] = 1;
      for (int n = 0; n < m.NumNodes(); ++n) mine[n] = mine[n] && (r.fixed_nodes || held[n] < 3), cand[n] |= mine[n];
      const std::string &own = scene->contact.supports[scene->contact.supports.size() - in.rigids.size() + k].node_set;
      if (!own.empty()) {
        std::vector<int> &set = m.node_sets[own];
        for (int n = 0; n < m.NumNodes(); ++n)
          if (mine[n]) set.push_back(n);
      }
    }
    std::vector<int> &set = m.node_sets["structure_contact"];
    for (int n = 0; n < m.NumNodes(); ++n)
      if (cand[n]) set.push_back(n);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int n = 0; n < m.NumNodes(); ++n)
      for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], m.coords[3 * n + i]), hi[i] = std::max(hi[i], m.coords[3 * n + i]);
    diag = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  }
  PetscCallMPI(MPI_Bcast(&diag, 1, MPI_DOUBLE, 0, comm));
  // A film node within 1e-4 of the structure's size of a support starts on it (-contact_search_tol).
  scene->contact.search_tol = 1e-4 * diag;
  PetscFunctionReturn(0);
}

} // namespace etfe
