// Internal to the flattening of a cutting strip (flatten*.cpp): the strip's link topology,
// the least-squares problem and its linear system, shared by the files of the pipeline:
// flatten_topology.cpp (links, triangles, folds), flatten_initial_guess.cpp (projection and
// unfolding), flatten_gauss_newton.cpp (objective, residual, K, its KSP, line search, weight
// stages), flatten_lines.cpp (outline, named lines, final report), flatten.cpp (FlattenStrip).
#pragma once
#include <petscksp.h>

#include <string>
#include <vector>

#include "etfe/analyses/flatten_strip.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {
namespace flatten {

std::string Format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

// Links (unique mesh edges) with their one or two triangles and the nodes opposite them.
struct Topology {
  std::vector<int> links;  // 2 per link, smaller id first
  std::vector<int> tri;    // 2 per link: adjacent triangles, -1 for none
  std::vector<int> opp;    // 2 per link: the third node of those triangles
  std::vector<int> tri_links;  // 3 per triangle
  int NumLinks() const { return (int)(links.size() / 2); }
  bool Boundary(int i) const { return tri[2 * i + 1] < 0; }
};

// The flattening problem: links, their 3D lengths and weights, and the free equations.
struct Problem {
  const Topology *topo;
  std::vector<double> L, w;
  std::vector<PetscInt> eq;  // 2 per node: equation number or -1 for a fixed coordinate
  PetscInt nfree = 0;
  double min_len2d = 0.0;  // plane links at or below this length count as collapsed
  bool outline_held = false;  // the outline nodes are fixed (FlattenOptions::hold_planar_outline)
};

struct LinearSystem {
  Mat K = nullptr;
  Vec r = nullptr, dx = nullptr;
  KSP ksp = nullptr;
  // After the first assembly: 16 per link, where each entry of its 4x4 block (row-major) lies in
  // K's value array (-1: a fixed coordinate), so later assemblies add there directly.
  std::vector<PetscInt> slot;
  PetscInt nnz = 0;
};

// flatten_topology.cpp
bool Fail(const MeshData &m, std::string *err, const std::string &msg);
bool BuildTopology(const MeshData &m, Topology *t, std::string *err);
double Dist3(const double *a, const double *b);
double Cross2(const double *o, const double *a, const double *b);
void TriangleBfs(const MeshData &m, const Topology &t, int start, std::vector<int> *order,
                 std::vector<int> *via);
int CountFolds(const Topology &t, const std::vector<double> &x, int *first);

// flatten_initial_guess.cpp
void SymEigen3(const double Ain[9], double vals[3], double vecs[9]);
void AlignPrincipal(std::vector<double> *xy);
void ProjectionGuess(const MeshData &m, std::vector<double> *xy);
void UnfoldGuess(const MeshData &m, const Topology &t, std::vector<double> *xy);
bool OutlinePlaneLayout(const MeshData &m, const Topology &t, double rtol, std::vector<double> *xy,
                        std::vector<char> *on_outline);

// flatten_gauss_newton.cpp
int Objective(const Problem &p, const std::vector<double> &x, double *S, int *bad);
PetscErrorCode CreateSystem(const MeshData &m, const Problem &p, LinearSystem *ls);
PetscErrorCode DestroySystem(LinearSystem *ls);
int Residual(const Problem &p, const std::vector<double> &x, std::vector<double> *R, int *bad);
PetscErrorCode AssembleK(const Problem &p, LinearSystem *ls, const std::vector<double> &x,
                         int order, int *status, int *bad);
PetscErrorCode SolveK(const Problem &p, LinearSystem *ls, const std::vector<double> &R,
                      std::vector<double> *d, bool *ok);
std::string LinkName(const Topology &t, int i);
PetscErrorCode IterateStage(const FlattenOptions &opt, const Problem &p, LinearSystem *ls,
                            double sw, double step_tol, int max_it, std::vector<double> *x,
                            FlattenResult *out, bool *converged, std::string *msg);
PetscErrorCode Iterate(const MeshData &m, const FlattenOptions &opt, Problem *p, double lmean,
                       std::vector<double> *x, FlattenResult *out, std::string *msg);

// flatten_lines.cpp
void OutlineLoops(const Topology &t, const std::vector<double> &x, int nn,
                  std::vector<std::vector<int>> *loops);
bool MeasureLine(const MeshData &m, const Topology &t, const std::vector<double> &x,
                 const std::string &name, const std::vector<int> &set, PatternLine *line,
                 std::string *err);
bool Report(const MeshData &m, const Topology &t, const FlattenOptions &opt, const Problem &p,
            std::vector<double> x, FlattenResult *out, std::string *err);

} // namespace flatten
} // namespace etfe
