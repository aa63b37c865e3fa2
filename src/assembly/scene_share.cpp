// See scene_share.h.
#include "scene_share.h"

#include <string>

#include "etfe/base/rank0.h"

namespace etfe {

namespace {

// Rank 0: whether the description fits its mesh (the scene builders index it by scene ids).
bool CheckDescription(const SceneSpec &s, std::string *err) {
  const MeshData &m = s.mesh;
  const int nn = m.NumNodes(), ne = m.NumElements();
  char buf[320];
  for (const DofConstraint &c : s.constraints)
    if (c.node < 0 || c.node >= nn || c.comp < 0 || c.comp >= 3) {
      std::snprintf(buf, sizeof buf, "scene %s: constraint on node %d component %d is outside the mesh (%d nodes)",
                    s.name.c_str(), c.node, c.comp, nn);
      return *err = buf, false;
    }
  for (const NodalForce &f : s.nodal_forces)
    if (f.node < 0 || f.node >= nn || f.comp < 0 || f.comp >= 3) {
      std::snprintf(buf, sizeof buf, "scene %s: nodal force on node %d component %d is outside the mesh (%d nodes)",
                    s.name.c_str(), f.node, f.comp, nn);
      return *err = buf, false;
    }
  for (const PressureSpec &p : s.pressures)
    for (int e : p.elements)
      if (e < 0 || e >= ne) {
        std::snprintf(buf, sizeof buf, "scene %s: pressure element %d is outside the mesh (%d elements)",
                      s.name.c_str(), e, ne);
        return *err = buf, false;
      }
  struct {
    const std::vector<double> &v;
    size_t per, count;
    const char *what;
  } arrays[] = {{s.initial_guess, 3, (size_t)nn, "initial displacements (3 per node)"},
                {s.element_stress_ratio, 1, (size_t)ne, "element stress ratios (1 per element)"},
                {s.element_reference, 9, (size_t)ne, "stress-free element coordinates (9 per element)"},
                {s.element_thickness, 1, (size_t)ne, "element thicknesses (1 per element)"},
                {s.element_md, 3, (size_t)ne, "element MD directions (3 per element)"}};
  for (const auto &a : arrays)
    if (!a.v.empty() && a.v.size() != a.per * a.count) {
      std::snprintf(buf, sizeof buf, "%s: %zu %s for %zu", m.source.c_str(), a.v.size(), a.what, a.count);
      return *err = buf, false;
    }
  if (!s.element_material.empty() && s.element_material.size() != (size_t)ne) {
    std::snprintf(buf, sizeof buf, "%s: %zu element materials for %d elements", m.source.c_str(),
                  s.element_material.size(), ne);
    return *err = buf, false;
  }
  for (int k : s.element_material)
    if (k < 0 || k > (int)s.material_prefixes.size()) {
      std::snprintf(buf, sizeof buf, "scene %s: element material %d is not one of the %zu laws", s.name.c_str(), k,
                    s.material_prefixes.size() + 1);
      return *err = buf, false;
    }
  return true;
}

} // namespace

PetscErrorCode SceneDistribute(MPI_Comm comm, const SceneSpec &s, LocalMesh *mesh, SceneShare *share) {
  PetscMPIInt rank;
  std::string err;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(Rank0Outcome(comm, rank == 0 ? (CheckDescription(s, &err) ? 1 : 0) : 1, err, PETSC_ERR_ARG_OUTOFRANGE));
  std::vector<std::vector<char>> loaded;  // rank 0: per pressure load, per scene element: loaded
  if (rank == 0)
    for (const PressureSpec &p : s.pressures) {
      loaded.emplace_back(s.mesh.NumElements(), p.elements.empty() ? 1 : 0);
      for (int e : p.elements) loaded.back()[e] = 1;
    }
  // The lists are packed in the order SceneShare unpacks them below.
  const ShareWriter extra = [&](const RankShare &r, ByteWriter *w) {
    std::vector<DofConstraint> cons;
    for (DofConstraint c : s.constraints)
      if (r.local_of[c.node] >= 0) c.node = (int)r.local_of[c.node], cons.push_back(c);
    std::vector<NodalForce> forces;
    for (NodalForce f : s.nodal_forces) {
      const PetscInt l = r.local_of[f.node];
      if (l >= 0 && l < r.num_owned) f.node = (int)l, forces.push_back(f);
    }
    std::vector<std::vector<PetscInt>> pressed(loaded.size());
    std::vector<double> guess, ratio, reference, thickness, md;
    std::vector<int> material;
    for (size_t k = 0; k < r.elements.size(); ++k) {
      const PetscInt e = r.elements[k];
      for (size_t p = 0; p < loaded.size(); ++p)
        if (loaded[p][e]) pressed[p].push_back((PetscInt)k);
      if (!s.element_stress_ratio.empty()) ratio.push_back(s.element_stress_ratio[e]);
      if (!s.element_reference.empty())
        reference.insert(reference.end(), s.element_reference.begin() + 9 * e, s.element_reference.begin() + 9 * e + 9);
      if (!s.element_thickness.empty()) thickness.push_back(s.element_thickness[e]);
      if (!s.element_md.empty()) md.insert(md.end(), s.element_md.begin() + 3 * e, s.element_md.begin() + 3 * e + 3);
      if (!s.element_material.empty()) material.push_back(s.element_material[e]);
    }
    if (!s.initial_guess.empty())
      for (PetscInt l = 0; l < r.num_owned; ++l)
        guess.insert(guess.end(), s.initial_guess.begin() + 3 * r.nodes[l], s.initial_guess.begin() + 3 * r.nodes[l] + 3);
    w->Put(cons), w->Put(forces), w->Put((unsigned long long)pressed.size());
    for (const auto &p : pressed) w->Put(p);
    w->Put(guess), w->Put(ratio), w->Put(reference), w->Put(thickness), w->Put(md), w->Put(material);
  };
  ByteReader rd;
  PetscCall(LocalMeshDistribute(comm, s.mesh, extra, mesh, &share->d_nnz, &share->o_nnz, &rd));
  unsigned long long loads = 0;
  rd.Get(&share->constraints), rd.Get(&share->forces), rd.Get(&loads);
  share->pressure_elements.resize(rd.ok ? (size_t)loads : 0);
  for (auto &p : share->pressure_elements) rd.Get(&p);
  rd.Get(&share->initial_guess), rd.Get(&share->element_stress_ratio), rd.Get(&share->element_reference);
  rd.Get(&share->element_thickness), rd.Get(&share->element_md), rd.Get(&share->element_material);
  PetscCheck(rd.ok && rd.AtEnd(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "rank %d: the scene share sent by rank 0 is malformed",
             rank);
  PetscFunctionReturn(0);
}

} // namespace etfe
