// The general scene's cables (-cable_<group>_*, docs/cables.md): a cable runs along a 1-D physical
// group of the mesh whose line elements join film nodes into one open chain. This file reads the
// options, checks each group is a chain, and hands the chains to the scene (SceneSpec::cables);
// the physics is the cable term (src/assembly/cable_term.cpp).
#include <petscsys.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>

#include "etfe/base/rank0.h"
#include "etfe/scenes/scene_registry.h"
#include "real_array_option.h"
#include "structure_inputs.h"

namespace etfe {

namespace {

PetscErrorCode ReadCable(MPI_Comm comm, const std::string &group, bool form_finding, CableInput *c, bool *any) {
  const std::string prefix = "cable_" + group + "_";
  PetscBool ea_set = PETSC_FALSE, len_set = PETSC_FALSE, pre_set = PETSC_FALSE, sl_set = PETSC_FALSE, w_set = PETSC_FALSE;
  PetscBool sliding = PETSC_FALSE, cl_set = PETSC_FALSE, mu_set = PETSC_FALSE, fd_set = PETSC_FALSE, sag_set = PETSC_FALSE;
  char *clamps[64];
  PetscInt nclamps = 64;
  PetscFunctionBeginUser;
  c->group = group;
  PetscOptionsBegin(comm, prefix.c_str(), ("Cable along the 1-D group " + group).c_str(), "Scene");
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-EA", "Axial stiffness EA of the cable [N] (steel strand: E A)", "N",
                              &c->EA, &ea_set));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-length",
                              "Stress-free (cut) length of the whole cable [mm] (default: its length in the mesh, or "
                              "from -cable_<group>_prestress)",
                              "mm", &c->length, &len_set));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-prestress",
                              "Force [N] the cable carries at the mesh's geometry (sets its stress-free length); form "
                              "finding: the cable's prescribed force",
                              "N", &c->prestress, &pre_set));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-force_density",
                              "Form finding: the cable's force density q [N/mm], each segment's force q times its "
                              "current length (instead of -cable_<group>_prestress)",
                              "N/mm", &c->force_density, &fd_set));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-sag",
                              "Form finding: an edge cable's target sag [mm] from the chord between its held ends; its "
                              "force T = n R follows from the film's stress n and the circle's radius R",
                              "mm", &c->sag, &sag_set));
  PetscCall(PetscOptionsBool("-sliding", "One force along the whole cable (a frictionless pocket) instead of a force per segment",
                             "", sliding, &sliding, &sl_set));
  c->weight.option = "-" + prefix + "weight";
  PetscCall(OptionsRealArray(PetscOptionsObject, "-weight",
                             "Self-weight [N/m of stress-free length] at the end of each stage, acting along -z", &c->weight.values,
                             &w_set));
  PetscCall(PetscOptionsStringArray("-clamps",
                                     "Clamps of a sliding cable: node groups (or node tags of the mesh file) of interior "
                                     "nodes where the cable passes with capstan friction (-cable_<group>_mu)",
                                     "", clamps, &nclamps, &cl_set));
  PetscCall(OptionsRealFinite(PetscOptionsObject, "-mu",
                              "Friction coefficient of the cable over its clamps and saddles (the interior nodes held in "
                              "x, y and z): T_high / T_low <= exp(mu theta)",
                              "1", &c->mu, &mu_set));
  PetscOptionsEnd();
  c->sliding = sliding;
  c->mu_set = mu_set;
  if (!cl_set) nclamps = 0;
  for (PetscInt i = 0; i < nclamps; ++i) {
    c->clamps.push_back(clamps[i]);
    PetscCall(PetscFree(clamps[i]));
  }
  *any = ea_set || len_set || pre_set || sl_set || w_set || cl_set || mu_set || fd_set || sag_set;
  if (!*any) PetscFunctionReturn(0);
  PetscCheck(ea_set, comm, PETSC_ERR_ARG_WRONG,
             "cable %s: give its axial stiffness -%sEA <N> (a cable option was given for the group)", group.c_str(),
             prefix.c_str());
  PetscCheck(c->EA > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%sEA %s: a cable's axial stiffness must be positive (E A in N, e.g. 2e7 for a 12 mm strand)",
             prefix.c_str(), OptionNum(c->EA).c_str());
  PetscCheck(!(len_set && pre_set), comm, PETSC_ERR_ARG_INCOMP,
             "cable %s: give its stress-free length (-%slength) or its prestress (-%sprestress), not both", group.c_str(),
             prefix.c_str(), prefix.c_str());
  PetscCheck(!len_set || c->length > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%slength %s: a length must be positive (mm)",
             prefix.c_str(), OptionNum(c->length).c_str());
  PetscCheck(c->prestress >= 0 && c->prestress < c->EA, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%sprestress %s: a cable carries tension only; give a force between 0 and EA (%s N)", prefix.c_str(),
             OptionNum(c->prestress).c_str(), OptionNum(c->EA).c_str());
  // Form finding: the cable's force from exactly one of its force, its force density or its sag.
  const std::pair<bool, const char *> force_from[3] = {
      {pre_set == PETSC_TRUE, "prestress"}, {fd_set == PETSC_TRUE, "force_density"}, {sag_set == PETSC_TRUE, "sag"}};
  for (const auto &[given, name] : {force_from[1], force_from[2]}) {
    PetscCheck(!given || form_finding, comm, PETSC_ERR_ARG_WRONG,
               "-%s%s: a form-finding input (-analysis formfind); a static run's cable takes its stress-free length "
               "(-%slength) or its force at the mesh's geometry (-%sprestress)",
               prefix.c_str(), name, prefix.c_str(), prefix.c_str());
    PetscCheck(!(given && len_set), comm, PETSC_ERR_ARG_INCOMP,
               "cable %s: -%s%s sets the cable's force and its cut length follows; drop -%slength", group.c_str(),
               prefix.c_str(), name, prefix.c_str());
  }
  if (form_finding && pre_set + fd_set + sag_set > 1) {
    std::string list;
    for (const auto &[given, name] : force_from)
      if (given) list += (list.empty() ? "-" : " and -") + prefix + name;
    SETERRQ(comm, PETSC_ERR_ARG_INCOMP,
            "cable %s: %s both set the cable's force in form finding; give one of -%sprestress (a force), "
            "-%sforce_density (a force per length) or -%ssag (an edge cable's target sag)",
            group.c_str(), list.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  }
  PetscCheck(!form_finding || c->prestress > 0 || fd_set || sag_set, comm, PETSC_ERR_ARG_WRONG,
             "cable %s: form finding needs the cable's force: -%sprestress <N>, -%sforce_density <N/mm> or -%ssag <mm> "
             "(the film's stress and each cable's force give the shape)",
             group.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  PetscCheck(!fd_set || c->force_density > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%sforce_density %s: a cable's force density is positive (N/mm: its force per mm of its length)",
             prefix.c_str(), OptionNum(c->force_density).c_str());
  PetscCheck(!(fd_set && sliding), comm, PETSC_ERR_ARG_INCOMP,
             "cable %s: -%ssliding with -%sforce_density: a pocket carries one force along the cable, a force "
             "density one per segment (q l); give the pocket's force with -%sprestress",
             group.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  PetscCheck(!sag_set || c->sag > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%ssag %s: an edge cable's sag is positive (mm, from the chord between its ends into the film)",
             prefix.c_str(), OptionNum(c->sag).c_str());
  PetscCheck(c->sliding || !(cl_set || mu_set), comm, PETSC_ERR_ARG_INCOMP,
             "cable %s: clamps and friction (-%sclamps, -%smu) act on a sliding cable; add -%ssliding (a fixed "
             "cable's segments each carry their own force already)",
             group.c_str(), prefix.c_str(), prefix.c_str(), prefix.c_str());
  PetscCheck(c->mu >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%smu %s: a friction coefficient is not negative (0: frictionless clamps)", prefix.c_str(),
             OptionNum(c->mu).c_str());
  PetscCheck(!cl_set || nclamps > 0, comm, PETSC_ERR_ARG_WRONG,
             "-%sclamps: give the clamps' node groups (or node tags), comma separated", prefix.c_str());
  for (double w : c->weight.values)
    PetscCheck(w >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sweight %s: a self-weight is not negative (N/m)", prefix.c_str(),
               OptionNum(w).c_str());
  PetscFunctionReturn(0);
}

// A -cable_ option no 1-D group took: its group does not exist (or is not a line group).
PetscErrorCode CheckUnknownCables(MPI_Comm comm, const std::vector<std::string> &groups) {
  PetscInt n;
  char **names, **values;
  std::string bad;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  for (PetscInt i = 0; i < n && bad.empty(); ++i)
    if (std::strncmp(names[i], "cable_", 6) == 0) bad = names[i];
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  if (bad.empty()) PetscFunctionReturn(0);
  std::string list;
  for (const std::string &g : groups) list += (list.empty() ? "" : ", ") + g;
  SETERRQ(comm, PETSC_ERR_ARG_WRONG,
          "-%s: no such cable option or 1-D group. -cable_<group>_* takes a 1-D physical group (line elements) of the "
          "mesh (%s) and EA, length, prestress, force_density, sag, weight, sliding, clamps or mu",
          bad.c_str(), list.empty() ? "the mesh has none" : list.c_str());
}

std::string NodeName(const MeshData &m, int n) {
  char buf[160];
  if ((size_t)n < m.node_tags.size())
    std::snprintf(buf, sizeof buf, "node %d (tag %lld in the file, at %g, %g, %g)", n, m.node_tags[n], m.coords[3 * n],
                  m.coords[3 * n + 1], m.coords[3 * n + 2]);
  else
    std::snprintf(buf, sizeof buf, "node %d (at %g, %g, %g)", n, m.coords[3 * n], m.coords[3 * n + 1], m.coords[3 * n + 2]);
  return buf;
}

// Rank 0: the group's line elements as one open chain from one end to the other (the end with the
// lower node id first), or a message why they are not one.
std::string Chain(const MeshData &m, const std::string &group, std::vector<int> *chain) {
  const auto it = m.line_sets.find(group);
  const std::vector<int> &lines = it->second;
  if (lines.empty()) return "cable " + group + ": its group has no line elements";
  std::map<int, std::vector<int>> adj;
  std::set<std::pair<int, int>> seen;
  for (size_t k = 0; k + 1 < lines.size(); k += 2) {
    const int a = lines[k], b = lines[k + 1];
    if (a < 0 || b < 0)
      return "cable " + group + ": a line element of the group has a node on no triangle of the film; a cable runs "
             "through the film's nodes (along an edge of it, or a line of its mesh)";
    if (a == b) return "cable " + group + ": a line element joins " + NodeName(m, a) + " to itself";
    if (!seen.insert({std::min(a, b), std::max(a, b)}).second)
      return "cable " + group + ": the segment from " + NodeName(m, a) + " to " + NodeName(m, b) + " is listed twice";
    adj[a].push_back(b), adj[b].push_back(a);
  }
  int start = -1;
  for (const auto &kv : adj) {
    if (kv.second.size() > 2)
      return "cable " + group + " is not one chain: " + NodeName(m, kv.first) + " joins " +
             std::to_string(kv.second.size()) + " of its segments (a branch); give each branch its own group";
    if (kv.second.size() == 1 && start < 0) start = kv.first;
  }
  if (start < 0) return "cable " + group + " is a closed loop; a cable has two ends (split the loop into two groups)";
  chain->assign(1, start);
  for (int prev = -1, cur = start;;) {
    int next = -1;
    for (int v : adj[cur])
      if (v != prev) next = v;
    if (next < 0) break;
    chain->push_back(next), prev = cur, cur = next;
  }
  if (chain->size() != adj.size())
    return "cable " + group + " is not one connected chain: its line elements form separate pieces (" +
           std::to_string(chain->size()) + " of its " + std::to_string(adj.size()) + " nodes follow from " +
           NodeName(m, start) + "); give each piece its own group";
  return "";
}

// Rank 0: a sliding cable's clamps (chain indices into s->clamps as scene node ids, in chain
// order): the nodes of -cable_<group>_clamps (node groups, or node tags of the file) and, with
// -cable_<group>_mu, the interior nodes held in x, y and z (saddles); or a message why not.
std::string Clamps(const SceneSpec &scene, const CableInput &c, CableSpec *s) {
  const MeshData &m = scene.mesh;
  const std::string opt = "-cable_" + c.group + "_clamps";
  std::map<int, int> index;  // node -> chain index
  for (size_t k = 0; k < s->nodes.size(); ++k) index[s->nodes[k]] = (int)k;
  std::set<int> chosen;  // chain indices
  for (const std::string &name : c.clamps) {
    std::vector<int> nodes;
    const auto it = m.node_sets.find(name);
    if (it != m.node_sets.end()) {
      nodes = it->second;
    } else if (!name.empty() && name.find_first_not_of("0123456789") == std::string::npos) {
      const long long tag = std::atoll(name.c_str());
      for (size_t n = 0; n < m.node_tags.size(); ++n)
        if (m.node_tags[n] == tag) nodes.push_back((int)n);
      if (nodes.empty()) return opt + " " + name + ": the mesh file has no node of tag " + name;
    } else {
      std::string list;
      for (const auto &kv : m.node_sets) list += (list.empty() ? "" : ", ") + kv.first;
      return opt + " " + name + ": no node group " + name + " in the mesh (" + list +
             "); give node groups or node tags of the file";
    }
    for (int n : nodes) {
      const auto at = index.find(n);
      if (at == index.end())
        return opt + " " + name + ": " + NodeName(m, n) + " is not on cable " + c.group +
               "; a clamp is an interior node of the cable's chain";
      if (at->second == 0 || at->second + 1 == (int)s->nodes.size())
        return opt + " " + name + ": " + NodeName(m, n) + " is an end of cable " + c.group +
               "; a clamp sits between two of its segments (hold an end with -bc_<group>_fix instead)";
      chosen.insert(at->second);
    }
  }
  if (c.mu_set) {  // saddles: interior nodes held in all three directions
    const std::vector<int> held = StructureHeldMask(scene);
    for (size_t k = 1; k + 1 < s->nodes.size(); ++k)
      if (held[s->nodes[k]] == 7) chosen.insert((int)k);
    if (chosen.empty())
      return "-cable_" + c.group + "_mu: cable " + c.group + " has no clamp and no saddle (an interior node held in x, "
             "y and z) for the friction to act at; give -cable_" + c.group + "_clamps <node group>";
  }
  for (int k : chosen) s->clamps.push_back(s->nodes[k]);
  return "";
}

// Rank 0, form finding: every boundary edge of the film (an edge of one triangle) is a cable
// segment or has both nodes held; else the message naming the first free one.
std::string FreeEdge(const SceneSpec &scene) {
  const MeshData &m = scene.mesh;
  std::map<std::pair<int, int>, int> count;
  for (int e = 0; e < m.NumElements(); ++e)
    for (int a = 0; a < 3; ++a) {
      const int p = m.triangles[3 * e + a], q = m.triangles[3 * e + (a + 1) % 3];
      count[{std::min(p, q), std::max(p, q)}]++;
    }
  std::set<std::pair<int, int>> cable;
  for (const CableSpec &c : scene.cables)
    for (size_t k = 0; k + 1 < c.nodes.size(); ++k)
      cable.insert({std::min(c.nodes[k], c.nodes[k + 1]), std::max(c.nodes[k], c.nodes[k + 1])});
  const std::vector<int> held = StructureHeldMask(scene);  // nonzero: some component held
  for (const auto &kv : count) {
    if (kv.second != 1 || cable.count(kv.first)) continue;
    if (held[kv.first.first] && held[kv.first.second]) continue;
    return "form finding: the film's edge from " + NodeName(m, kv.first.first) + " to " + NodeName(m, kv.first.second) +
           " is free (no cable, no support); a free edge under a prescribed stress has no equilibrium shape: run a "
           "cable along it (a 1-D group with -cable_<group>_EA and _prestress, _force_density or _sag) or hold it with -bc_<group>_fix";
  }
  return "";
}

// The film's form-finding stress, as the run will prescribe it: -formfind_stress S [MPa] (TD) and
// -formfind_ratio (MD:TD; a scene's per-element ratios replace it, src/analyses/formfind.cpp), and
// -membrane_thickness where no film group gives its own (the defaults: analyses/formfind.h and
// the scene's thickness, read here before the analysis and the membrane read them).
struct FilmStress {
  double S = 1.0, ratio = 1.0, h = 0.25;
};

// Rank 0, form finding: the force T = n R of an edge cable given its target sag s (docs/theory.md
// §14): its segments each border one triangle, its ends are held (the chord c between them stays),
// the triangles along it have one thickness h and an isotropic stress S (ratio 1), n = S h, and
// R = (c^2/4 + s^2) / (2 s) for 0 < s < c/2. Else the message why not; *note says what was taken.
std::string SagForce(const SceneSpec &scene, const CableInput &c, const CableSpec &s, const FilmStress &film, double *T,
                     std::string *note) {
  const MeshData &m = scene.mesh;
  const std::string opt = "-cable_" + c.group + "_sag";
  const std::vector<int> held = StructureHeldMask(scene);
  for (int end : {s.nodes.front(), s.nodes.back()})
    if (held[end] != 7)
      return opt + ": cable " + c.group + "'s end " + NodeName(m, end) + " is not held in x, y and z; the sag is "
             "measured from the chord between its held ends (hold it with -bc_<group>_fix xyz, or give the cable's "
             "force with -cable_" + c.group + "_prestress)";
  std::map<std::pair<int, int>, std::vector<int>> sides;
  for (int e = 0; e < m.NumElements(); ++e)
    for (int a = 0; a < 3; ++a) {
      const int p = m.triangles[3 * e + a], q = m.triangles[3 * e + (a + 1) % 3];
      sides[{std::min(p, q), std::max(p, q)}].push_back(e);
    }
  double h = -1.0;
  for (size_t k = 0; k + 1 < s.nodes.size(); ++k) {
    const int a = s.nodes[k], b = s.nodes[k + 1];
    const auto it = sides.find({std::min(a, b), std::max(a, b)});
    if (it == sides.end() || it->second.size() != 1)
      return opt + ": the segment from " + NodeName(m, a) + " to " + NodeName(m, b) + " of cable " + c.group +
             " is not on the film's edge (" + std::to_string(it == sides.end() ? 0 : it->second.size()) +
             " triangles share it); a target sag sets the force of an edge cable: give -cable_" + c.group +
             "_prestress or _force_density";
    const int e = it->second[0];
    const double ratio = scene.element_stress_ratio.empty() ? film.ratio : scene.element_stress_ratio[e];
    const double he = scene.element_thickness.empty() || scene.element_thickness[e] == 0 ? film.h : scene.element_thickness[e];
    char buf[256];
    if (ratio != 1.0) {
      std::snprintf(buf, sizeof buf, "the film beside cable %s has the stress ratio MD:TD = %g (element %d, "
                    "-formfind_ratio or -film_<group>_stress_ratio)", c.group.c_str(), ratio, e);
      return opt + ": " + buf + "; the edge's circle T = n R needs an isotropic film stress (ratio 1): give the "
             "cable's force with -cable_" + c.group + "_prestress";
    }
    if (h >= 0 && he != h) {
      std::snprintf(buf, sizeof buf, "the film beside cable %s is %g mm thick at one segment and %g mm at another "
                    "(element %d)", c.group.c_str(), h, he, e);
      return opt + ": " + buf + "; the edge is a circle where n = S h is one value along it: give the cable's force "
             "with -cable_" + c.group + "_prestress";
    }
    h = he;
  }
  const double *A = &m.coords[3 * s.nodes.front()], *B = &m.coords[3 * s.nodes.back()];
  const double chord = std::sqrt((B[0] - A[0]) * (B[0] - A[0]) + (B[1] - A[1]) * (B[1] - A[1]) + (B[2] - A[2]) * (B[2] - A[2]));
  char buf[512];
  if (!(c.sag < 0.5 * chord)) {
    std::snprintf(buf, sizeof buf, "%s %s: the sag of a circular edge is below half its chord (%.6f mm between its "
                  "held ends): a smaller sag, or the cable's force with -cable_%s_prestress", opt.c_str(),
                  OptionNum(c.sag).c_str(), chord, c.group.c_str());
    return buf;
  }
  const double R = (0.25 * chord * chord + c.sag * c.sag) / (2.0 * c.sag), n = film.S * h;
  *T = n * R;
  std::snprintf(buf, sizeof buf, "cable %s: target sag %.9g mm over the chord %.6f mm: edge radius R = (c^2/4 + s^2) / "
                "(2 s) = %.9e mm, film stress n = %g MPa x %g mm = %.9e N/mm, cable force T = n R = %.9e N",
                c.group.c_str(), c.sag, chord, R, film.S, h, n, *T);
  *note = buf;
  return "";
}

} // namespace

PetscErrorCode StructureCablesRead(MPI_Comm comm, const MeshData &mesh, bool form_finding, StructureInputs *in) {
  std::vector<std::string> groups;
  PetscFunctionBeginUser;
  for (const auto &kv : mesh.line_sets) groups.push_back(kv.first);  // rank 0's mesh
  PetscCall(BroadcastNames(comm, &groups));
  for (const std::string &g : groups) {
    CableInput c;
    bool any = false;
    PetscCall(ReadCable(comm, g, form_finding, &c, &any));
    if (any) in->cables.push_back(c);
  }
  PetscCall(CheckUnknownCables(comm, groups));
  PetscFunctionReturn(0);
}

PetscErrorCode StructureAddCables(MPI_Comm comm, const StructureInputs &in, int stages, SceneSpec *scene) {
  PetscFunctionBeginUser;
  std::string err;
  FilmStress film;
  film.h = scene->thickness;
  if (std::any_of(in.cables.begin(), in.cables.end(), [](const CableInput &c) { return c.sag > 0; })) {
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-formfind_stress", &film.S, nullptr));
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-formfind_ratio", &film.ratio, nullptr));
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-membrane_thickness", &film.h, nullptr));
  }
  std::vector<std::string> sag_notes;  // rank 0: each sag cable's circle and force
  for (const CableInput &c : in.cables) {
    CableSpec s;
    s.name = c.group, s.EA = c.EA, s.length = c.length, s.prestress = c.prestress, s.sliding = c.sliding;
    s.mu = c.mu, s.force_density = c.force_density;
    if (SceneHoldsMesh(comm) && err.empty()) err = Chain(scene->mesh, c.group, &s.nodes);
    if (SceneHoldsMesh(comm) && err.empty() && c.sag > 0) {
      std::string note;
      err = SagForce(*scene, c, s, film, &s.prestress, &note);
      sag_notes.push_back(note);
    }
    if (SceneHoldsMesh(comm) && err.empty() && (!c.clamps.empty() || c.mu_set)) err = Clamps(*scene, c, &s);
    if (c.weight.Given() && !scene->form_finding) {
      std::vector<double> v;
      for (double w : c.weight.values) v.push_back(w * 1e-3);  // N/m -> N/mm
      const int id = StructureAddSchedule(scene, "cable." + c.group + ".weight", v, stages, "N/m", 1e3);
      s.weighted = true;
      s.weight.coef[0] = 1.0, s.weight.schedule[0] = id;
    }
    scene->cables.push_back(s);
  }
  // A node on two sliding cables would be pulled by both pockets' single forces: ambiguous.
  if (SceneHoldsMesh(comm) && err.empty()) {
    std::map<int, std::string> sliding;
    for (const CableSpec &c : scene->cables) {
      if (!c.sliding) continue;
      for (int n : c.nodes) {
        auto r = sliding.emplace(n, c.name);
        if (!r.second && err.empty())
          err = "sliding cables " + r.first->second + " and " + c.name + " share " + NodeName(scene->mesh, n) +
                "; a node runs in one sliding cable's pocket only (make one of them a fixed cable, or end them apart)";
      }
    }
  }
  if (SceneHoldsMesh(comm) && err.empty() && scene->form_finding) err = FreeEdge(*scene);
  PetscCall(Rank0Outcome(comm, err.empty() ? 1 : 0, err, PETSC_ERR_ARG_WRONG));
  for (size_t k = 0; k < scene->cables.size(); ++k) {
    CableSpec &s = scene->cables[k];
    if (in.cables[k].sag > 0) {  // the force found from the sag on rank 0
      PetscCallMPI(MPI_Bcast(&s.prestress, 1, MPI_DOUBLE, 0, comm));
      PetscCheck(s.prestress < s.EA, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-cable_%s_sag %s: the force it needs, %s N, is not below the cable's EA (%s N): a larger sag or a "
                 "stiffer cable", s.name.c_str(), OptionNum(in.cables[k].sag).c_str(), OptionNum(s.prestress).c_str(),
                 OptionNum(s.EA).c_str());
    }
    for (std::vector<int> *v : {&s.nodes, &s.clamps}) {
      int n = (int)v->size();
      PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm));
      v->resize(n);
      PetscCallMPI(MPI_Bcast(v->data(), n, MPI_INT, 0, comm));
    }
  }
  for (const std::string &note : sag_notes) PetscCall(PetscPrintf(comm, "structure: %s\n", note.c_str()));
  PetscFunctionReturn(0);
}

} // namespace etfe
