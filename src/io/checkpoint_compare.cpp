// What a restart must agree on with its checkpoint (see checkpoint_compare.h).
//
// The rule: an option may change on a restart when it decides how the increments are solved or
// what is written, never what is computed. Allowed to change:
//   solvers      -snes_* -ksp_* -pc_* -mat_* (MUMPS, ...) -matis_* -sub_* -mg_* -redundant_* -fieldsplit_*
//                -etfe_lu_native_max_dof
//                -load_force_rtol -load_max_cutbacks -load_max_it -load_grow_after -load_easy_iterations
//                -load_extrapolate -load_tangent_predictor* (predictors and the cut-back policy)
//                -load_force_roundoff (the round-off floor of the force test)
//                -membrane_tangent_* (shift, adaptive shift, tension only: the Newton path only)
//                -membrane_near_null_space (what AMG is told about the tangent)
//                -etfe_pc_*, -etfe_solver, -etfe_scalable_* (the linear solver)
//   output       -output* -checkpoint_* -restart -contact_probe_nodes -saddle_history
//                -load_monitor -load_stop_after -formfind_monitor
//   diagnostics  PETSc's own (-log*, -info, -malloc*, -options_*, -help, ...), -etfe_traceback
//   signals      -etfe_signal_grace (when a stop may give up the increment under way)
//   -mesh_file   may name another path: the mesh itself is compared (MeshFingerprint)
// Everything else (-scene, -analysis, -mesh_*, -material_*, -membrane_thickness and
// _min_area_ratio, -contact_* incl. the friction law, mu and the penalties, -load_increments,
// every -<scene>_* option) must be equal, as must the mesh and the resolved physics.
//
// A branch restart (-restart_branch) starts another load history from a checkpoint taken at a
// stage end (the base state: prestressed, inflated): it may also change the scene's load options
// (every option that is not one of kModel: -structure_*, -film_*, -bc_*, -chamber_*,
// -load_increments, ...), as long as what they resolve to up to the checkpoint's load time is
// the same (LoadPathStates): the same supports and their motions, loads and chambers up to the
// base's end, the same film. The model (-scene, -analysis, -mesh_*, -material_*, -membrane_*,
// -contact_*, -layer_*) and the mesh must be equal as on any restart.
#include "checkpoint_compare.h"

#include <petscsys.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <sstream>


namespace etfe {

namespace {

const char *const kMayChange[] = {
    "snes_", "ksp_", "pc_", "mat_", "matis_", "sub_", "mg_", "redundant_", "fieldsplit_",
    "load_force_rtol", "load_max_cutbacks", "load_max_it", "load_grow_after", "load_easy_iterations", "load_extrapolate",
    "load_tangent_predictor", "membrane_tangent_", "formfind_monitor", "load_force_roundoff",
    "membrane_near_null_space", "etfe_lu_native_max_dof", "etfe_pc_", "etfe_solver", "etfe_scalable_",
    "output", "checkpoint_", "restart", "contact_probe_nodes", "saddle_history", "load_monitor", "load_stop_after",
    "log", "info", "malloc", "memory_", "options_", "help", "etfe_traceback", "etfe_signal_grace", "fp_trap", "on_error", "history",
    "viewer", "objects_", "check_pointer", "checkstack", "no_signal_handler", "debugger", "start_in_debugger",
    "stop_for_debugger", "display", "citations", "use_gpu_aware_mpi", "vecscatter_", "sf_", "skip_petscrc",
    "scene_list", "mesh_file"};

// What a branch restart may not change by name (the model, not its loads).
const char *const kModel[] = {"scene", "analysis", "mesh_", "material_", "membrane_", "contact_", "layer_",
                              "formfind_", "cutpattern_", "plan_"};

bool HasPrefix(const std::string &name, const char *const *list, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    const std::string pre = list[k];
    if (name.compare(0, pre.size(), pre) != 0) continue;
    if (name.size() == pre.size() || pre.back() == '_' || name[pre.size()] == '_') return true;
  }
  return false;
}

std::string Lower(std::string s) {
  for (char &c : s) c = (char)std::tolower((unsigned char)c);
  return s;
}

// Options as {name (lower case, no dash): value}; `text` holds "-name value" lines or PETSc's
// one-line "-a 1 -b 2" listing (a name is a dash followed by a letter).
std::map<std::string, std::string> ParseOptions(const std::string &text) {
  std::map<std::string, std::string> res;
  std::istringstream in(text);
  std::string tok, name;
  while (in >> tok) {
    if (tok.size() > 1 && tok[0] == '-' && std::isalpha((unsigned char)tok[1])) {
      name = Lower(tok.substr(1));
      res[name];
    } else if (!name.empty()) {
      std::string &v = res[name];
      v += (v.empty() ? "" : " ") + tok;
    }
  }
  return res;
}

bool ParseNumbers(const std::string &v, std::vector<double> *x) {
  std::stringstream in(v);
  std::string item;
  x->clear();
  while (std::getline(in, item, ',')) {
    char *end = nullptr;
    const double d = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0') return false;
    x->push_back(d);
  }
  return !x->empty();
}

int ParseBool(const std::string &v) {
  const std::string l = Lower(v);
  if (l.empty() || l == "1" || l == "true" || l == "yes" || l == "on") return 1;
  if (l == "0" || l == "false" || l == "no" || l == "off") return 0;
  return -1;
}

// Equal as the option readers see them: 2e3 == 2000, "1" == "true" == a bare flag.
bool SameValue(const std::string &a, const std::string &b) {
  if (a == b) return true;
  std::vector<double> x, y;
  if (ParseNumbers(a, &x) && ParseNumbers(b, &y)) return x == y;
  const int ba = ParseBool(a), bb = ParseBool(b);
  return ba >= 0 && ba == bb;
}

std::string Shown(const std::map<std::string, std::string> &m, const std::string &name) {
  auto it = m.find(name);
  if (it == m.end()) return "(not set)";
  return it->second.empty() ? "(set, no value)" : it->second;
}

// The rigid supports, the form-finding stress ratios and the initial guess: the tail of both the
// scene's physics state and each stage end's load-path state (in this order in both).
void AddSupportsAndStart(const SceneSpec &s, Fnv64 *hash) {
  Fnv64 &h = *hash;
  h.Add(s.contact.active), h.Add(s.contact.node_set), h.Add(s.contact.search_tol);
  h.Add(s.contact.supports.size());
  for (const SupportSpec &sp : s.contact.supports)
    h.Add(sp.name), h.Add(sp.type), h.Add(sp.centre), h.Add(sp.axis), h.Add(sp.radius);
  h.Add(s.element_stress_ratio);
  h.Add(s.initial_guess);
}

// A surface group's own model options, -film_<g>_material_*, _thickness, _md and _stress_ratio
// (its pressure, wind and snow are loads, which a branch may change).
bool FilmModelOption(const std::string &name) {
  if (name.compare(0, 5, "film_") != 0) return false;
  for (const std::string part : {"_material_", "_thickness", "_md", "_stress_ratio"}) {
    const size_t at = name.rfind(part);
    if (at != std::string::npos && at > 5 && (part.back() == '_' || at + part.size() == name.size())) return true;
  }
  return false;
}

} // namespace

bool CheckpointOptionMayChange(const std::string &option, bool branch) {
  const std::string name = Lower(option[0] == '-' ? option.substr(1) : option);
  if (HasPrefix(name, kMayChange, sizeof kMayChange / sizeof *kMayChange)) return true;
  return branch && !HasPrefix(name, kModel, sizeof kModel / sizeof *kModel) && !FilmModelOption(name);
}

std::uint64_t MeshFingerprint(const MeshData &m) {
  Fnv64 h;
  h.Add(m.coords);
  h.Add(m.triangles);
  for (const auto *sets : {&m.node_sets, &m.element_sets}) {
    h.Add(sets->size());
    for (const auto &kv : *sets) h.Add(kv.first), h.Add(kv.second);
  }
  return h.Value();
}

std::uint64_t ScenePhysicsState(const SceneSpec &s, double thickness, double min_area_ratio) {
  Fnv64 h;
  auto value = [&h](const ScheduledValue &v) { h.Add(v.coef), h.Add(v.schedule); };
  h.Add(s.name);
  h.Add(s.md_axis);
  h.Add(s.element_thickness), h.Add(s.element_md);
  // The surface groups' own laws (none: the hash of a film with one law, as before them).
  if (!s.material_prefixes.empty()) h.Add(s.material_prefixes.size()), h.Add(s.element_material);
  for (const std::string &p : s.material_prefixes) h.Add(p);
  h.Add(thickness);
  h.Add(min_area_ratio);
  h.Add(s.schedules.size());
  for (const Schedule &sc : s.schedules) h.Add(sc.name), h.Add(sc.initial), h.Add(sc.values);
  h.Add(s.constraints.size());
  for (const DofConstraint &c : s.constraints) h.Add(c.node), h.Add(c.comp), value(c.value);
  h.Add(s.pressures.size());
  for (const PressureSpec &p : s.pressures) h.Add(p.elements), value(p.value), h.Add(p.chamber), h.Add(p.sign);
  h.Add(s.chambers.size());
  for (const ChamberSpec &c : s.chambers) {
    h.Add(c.name), h.Add(c.origin), value(c.supplied), h.Add(c.sealed_from_stage), h.Add(c.kappa), h.Add(c.extra_volume);
    if (!c.sealed_stages.empty()) h.Add(c.sealed_stages);
  }
  if (!s.chambers.empty()) h.Add(s.atmosphere);
  h.Add(s.nodal_forces.size());
  for (const NodalForce &f : s.nodal_forces) h.Add(f.node), h.Add(f.comp), value(f.value);
  AddSupportsAndStart(s, &h);
  return h.Value();
}

std::vector<std::uint64_t> LoadPathStates(const SceneSpec &s, double thickness, double min_area_ratio,
                                          const StageClock &clock) {
  const int stages = s.NumStages();
  std::vector<std::uint64_t> states;
  for (int end = 0; end <= stages; ++end) {
    Fnv64 h;
    // The values of a scheduled quantity at the stage ends 0..end (linear between them), and
    // whether any is non-zero: a load that is zero up to `end` (a wind the base does not have)
    // adds nothing, so the base and its branches hash the same.
    auto values = [&](const ScheduledValue &v, std::vector<double> *x) {
      x->clear();
      bool any = false;
      for (int k = 0; k <= end; ++k) x->push_back(v.At(s.schedules, k)), any |= x->back() != 0.0;
      return any;
    };
    std::vector<double> x;
    h.Add(s.name);
    h.Add(s.md_axis);
    h.Add(s.element_thickness), h.Add(s.element_md), h.Add(s.element_reference);
    if (!s.material_prefixes.empty()) h.Add(s.material_prefixes.size()), h.Add(s.element_material);
    for (const std::string &p : s.material_prefixes) h.Add(p);
    h.Add(thickness), h.Add(min_area_ratio);
    values(s.reference_blend, &x), h.Add(x);
    h.Add(s.constraints.size());
    for (const DofConstraint &c : s.constraints) h.Add(c.node), h.Add(c.comp), values(c.value, &x), h.Add(x);
    for (const PressureSpec &p : s.pressures)
      if (p.chamber >= 0 || values(p.value, &x))
        h.Add(p.elements), h.Add(p.chamber), h.Add(p.sign), h.Add(p.chamber >= 0 ? std::vector<double>() : x);
    h.Add(s.chambers.size());
    for (const ChamberSpec &c : s.chambers) {
      h.Add(c.name), h.Add(c.origin), h.Add(c.kappa), h.Add(c.extra_volume);
      values(c.supplied, &x), h.Add(x);
      for (int k = 1; k <= end; ++k) h.Add(c.SealedIn(k));
    }
    if (!s.chambers.empty()) h.Add(s.atmosphere);
    for (const NodalForce &f : s.nodal_forces)
      if (values(f.value, &x)) h.Add(f.node), h.Add(f.comp), h.Add(x);
    AddSupportsAndStart(s, &h);
    if (clock.Active()) {  // the physical time of stages 1..end (time-dependent materials)
      h.Add(clock.hold_first);
      for (int k = 0; k < end && k < (int)clock.duration.size(); ++k) h.Add(clock.duration[k]), h.Add(clock.hold[k]);
    }
    states.push_back(h.Value());
  }
  return states;
}

std::uint64_t PhysicsFingerprint(const Problem *P) { return PhysicsFingerprintFrom(P, P->scene_physics_state); }

std::uint64_t PhysicsFingerprintFrom(const Problem *P, std::uint64_t scene_state) {
  Fnv64 h(scene_state);
  for (const auto &term : P->terms) term->Fingerprint(h);  // contact's parameters
  // The film's law, then the surface groups' own (none: the hash of a film with one law).
  for (const Material *law : P->Materials()) {
    double young = 0.0, nu = 0.0;
    law->ElasticConstants(&young, &nu);
    h.Add(std::string(law->Name())), h.Add(young), h.Add(nu), h.Add(law->HistorySize());
  }
  return h.Value();
}

PetscErrorCode OptionsAsLines(std::string *lines) {
  char *all = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const auto opts = ParseOptions(all ? all : "");
  PetscCall(PetscFree(all));
  lines->clear();
  for (const auto &kv : opts) *lines += "-" + kv.first + (kv.second.empty() ? "" : " " + kv.second) + "\n";
  PetscFunctionReturn(0);
}

std::string OptionDifferences(const std::string &checkpoint_lines, const std::string &current_lines, bool branch) {
  const auto a = ParseOptions(checkpoint_lines), b = ParseOptions(current_lines);
  std::vector<std::string> names;
  for (const auto *m : {&a, &b})
    for (const auto &kv : *m)
      if (!CheckpointOptionMayChange(kv.first, branch)) names.push_back(kv.first);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::string table;
  int shown = 0, hidden = 0;
  for (const std::string &n : names) {
    auto ia = a.find(n), ib = b.find(n);
    if (ia != a.end() && ib != b.end() && SameValue(ia->second, ib->second)) continue;
    if (shown == 12) {  // a PETSc message holds about 2 kB
      ++hidden;
      continue;
    }
    char line[256];
    std::snprintf(line, sizeof line, "\n    -%-28s checkpoint: %-18s this run: %s", n.c_str(), Shown(a, n).c_str(),
                  Shown(b, n).c_str());
    table += line;
    ++shown;
  }
  if (hidden) table += "\n    ... and " + std::to_string(hidden) + " more";
  return table;
}

} // namespace etfe
