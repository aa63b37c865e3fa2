// Frictionless contact between film layers (a cushion's top foil resting on the foil below it)
// as a component of the problem (assembly layer, src/assembly/layer_contact.cpp; kernel
// kernels/layer_contact.h). Exists only with -layer_contact slave:master,...; without it nothing
// here is allocated or run.
//
// Each owned node of a slave layer (not on the master layer, not held) is paired with the master
// triangle under it by the plan position (x, y): for layers that are graphs over the plan, as a
// cushion's foils. The side it starts on is kept; a penalty (-layer_contact_penalty, pressure per
// unit penetration, times the node's tributary area) pushes it back when it passes through the
// triangle's plane. Pairs are found again after every converged increment (and after a restart),
// fixed within one. Every rank holds the master layers' reference geometry and, at each
// evaluation, their displacements (one scatter): memory O(master layers) per rank.
#pragma once
#include <petscmat.h>

#include <string>
#include <vector>

#include "etfe/assembly/physics_term.h"

namespace etfe {

struct Problem;

struct LayerContactSet : PhysicsTerm {
  double penalty = 0.01;                 // N/mm^3 (MPa per mm of penetration)
  std::vector<std::string> slaves, masters;
  std::vector<PetscInt> master_ids;      // PETSc ids of all master nodes (ascending)
  std::vector<double> master_X;          // their reference coordinates (3 each)
  std::vector<char> master_held;         // per master DOF: prescribed
  std::vector<int> master_tri;           // 3 indices into master_ids per master triangle
  std::vector<int> tri_layer;            // per master triangle: index into masters
  std::vector<PetscInt> tri_natural;     // per master triangle: its scene element id
  struct Node {
    PetscInt local;                      // owned local node
    int layer;                           // index into slaves / masters
    double side;                         // +1 / -1: the side of the master layer it started on
    double k;                            // penalty times tributary area [N/mm]
    int tri = -1;                        // current master triangle (-1: none under it)
  };
  std::vector<Node> nodes;
  Vec master_u = nullptr;                // sequential: the master nodes' displacements
  VecScatter scatter = nullptr;
  PetscInt active = 0, paired = 0;       // global counts at the last evaluation / pairing
  double deepest = 0.0;                  // largest penetration at the last evaluation [mm]

  // As a physics term (layer_contact_term.cpp): forces after the ghost sum, stiffness, pairs
  // found again at each commit and restart, the checkpoint's layer_pairs.
  const char *Name() const override { return "layer_contact"; }
  PetscErrorCode AddGlobalForces(Problem &, Vec U, Vec F) override;
  PetscErrorCode AddTangent(Problem &, Vec U, const PetscScalar *u, Mat A) override;
  PetscErrorCode Commit(Problem &, double t) override;
  PetscErrorCode Restarted(Problem &) override;
  // The block State writes (TermCheckpointDatasets).
  static const TermDatasetInfo kCheckpoint;
  PetscErrorCode State(const Problem &, std::vector<TermData> *blocks) const override;
  PetscErrorCode Restore(Problem &, const std::vector<TermData> &blocks) override;
  PetscErrorCode Destroy(Problem &) override;
};

// Reads -layer_contact and adds the term (does nothing without it); collective.
PetscErrorCode AddLayerContactTerm(Problem *P);
// Pairs every slave node with the master triangle under it at the state U. Collective.
PetscErrorCode LayerContactPair(Problem *P, Vec U);
// Adds the contact forces to F (global, before the constrained rows are replaced). Collective.
PetscErrorCode LayerContactResidual(Problem *P, Vec U, Vec F);
// Adds the contact stiffness to the (not yet assembled) matrix. Collective.
PetscErrorCode LayerContactJacobian(Problem *P, Vec U, Mat A);
// Whether the pairs of c (nullptr: none) keep a chamber's surface groups apart: two or more
// groups, each joined to the others by pairs between groups of the list (either way round). Only
// then may a supplied chamber empty, its foils resting on each other. Otherwise *missing is a pair
// of the list's groups not joined ("top:middle"), empty for a single group.
bool LayerContactKeepsApart(const LayerContactSet *c, const std::vector<std::string> &groups, std::string *missing);
// The pairs a checkpoint keeps (which triangle a node keeps while it stays near it): per owned
// node the scene id of its master triangle, -1 for none.
void LayerContactStateGet(const Problem *P, std::vector<double> *per_owned_node);
void LayerContactStateSet(Problem *P, const std::vector<double> &per_owned_node);

} // namespace etfe
