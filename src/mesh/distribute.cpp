// From the scene's global mesh, held by rank 0 only (the reader), to each rank's part of it
// (local_mesh.h). Rank 0 partitions the elements with METIS, numbers the nodes (a node belongs to
// the lowest rank among its elements; PETSc ids rank by rank, the scene's order inside a rank)
// and then, one rank at a time, packs that rank's elements, nodes, sets, preallocation and the
// caller's extra data into one buffer and sends it. No other rank ever holds O(global) data.
#include <petscsys.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <numeric>
#include <string>

#include "etfe/kernels/status.h"
#include "etfe/mesh/local_mesh.h"
#include "etfe/mesh/partition.h"
#include "etfe/base/rank0.h"

namespace etfe {

namespace {

// What rank 0 knows of the whole partition.
struct Plan {
  std::vector<int> part, owner;            // per element, per node
  std::vector<PetscInt> petsc_id;          // per node
  std::vector<PetscInt> elem_ptr, elems;   // elements of each rank, ascending (CSR)
  std::vector<PetscInt> own_ptr, owned;    // owned nodes of each rank, ascending = PETSc order, so
                                           // own_ptr[r] is rank r's first PETSc id
  std::vector<PetscInt> ne_ptr, node_elems;  // elements of each node (CSR)
};

// Counting sort of ids 0..n-1 by key in [0, nkeys): ptr (nkeys + 1) and the ids, each bucket ascending.
void Bucket(const std::vector<int> &key, int nkeys, std::vector<PetscInt> *ptr, std::vector<PetscInt> *ids) {
  ptr->assign(nkeys + 1, 0);
  for (int k : key) (*ptr)[k + 1]++;
  std::partial_sum(ptr->begin(), ptr->end(), ptr->begin());
  std::vector<PetscInt> next(ptr->begin(), ptr->end() - 1);
  ids->resize(key.size());
  for (size_t i = 0; i < key.size(); ++i) (*ids)[next[key[i]]++] = (PetscInt)i;
}

bool MakePlan(const MeshData &gm, int size, Plan *p, std::string *err) {
  const int nn = gm.NumNodes(), ne = gm.NumElements();
  if (!PartitionElementsMetis(gm, size, &p->part, err)) return false;
  p->owner.assign(nn, size);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a) {
      int &o = p->owner[gm.triangles[3 * e + a]];
      o = std::min(o, p->part[e]);
    }
  for (int i = 0; i < nn; ++i)
    if (p->owner[i] == size) {
      *err = gm.source + ": node " + std::to_string(i) + " belongs to no triangle; remove it from the mesh";
      return false;
    }
  Bucket(p->part, size, &p->elem_ptr, &p->elems);
  Bucket(p->owner, size, &p->own_ptr, &p->owned);
  p->petsc_id.resize(nn);
  for (PetscInt k = 0; k < nn; ++k) p->petsc_id[p->owned[k]] = k;
  Bucket(gm.triangles, nn, &p->ne_ptr, &p->node_elems);  // triangle corners by node
  for (PetscInt &c : p->node_elems) c /= 3;                 // corner -> its triangle
  return true;
}

// Rank r's share, packed: mesh part first, then extra's data.
void PackShare(const MeshData &gm, const Plan &p, int r, const ShareWriter &extra, std::vector<PetscInt> *local_of,
               std::vector<PetscInt> *elem_local, ByteWriter *w) {
  const PetscInt no = p.own_ptr[r + 1] - p.own_ptr[r];
  std::vector<PetscInt> nodes(p.owned.begin() + p.own_ptr[r], p.owned.begin() + p.own_ptr[r + 1]);
  std::vector<PetscInt> elements(p.elems.begin() + p.elem_ptr[r], p.elems.begin() + p.elem_ptr[r + 1]);
  for (PetscInt l = 0; l < no; ++l) (*local_of)[nodes[l]] = l;
  std::vector<PetscInt> ghosts;
  for (PetscInt e : elements)
    for (int a = 0; a < 3; ++a) {
      const int v = gm.triangles[3 * e + a];
      if ((*local_of)[v] == -1) (*local_of)[v] = -2, ghosts.push_back(v);
    }
  std::sort(ghosts.begin(), ghosts.end(), [&](PetscInt a, PetscInt b) { return p.petsc_id[a] < p.petsc_id[b]; });
  for (PetscInt g : ghosts) (*local_of)[g] = (PetscInt)nodes.size(), nodes.push_back(g);
  for (size_t k = 0; k < elements.size(); ++k) (*elem_local)[elements[k]] = (PetscInt)k;

  std::vector<PetscInt> global_id(nodes.size());
  std::vector<double> X(3 * nodes.size());
  for (size_t l = 0; l < nodes.size(); ++l) {
    global_id[l] = p.petsc_id[nodes[l]];
    for (int i = 0; i < 3; ++i) X[3 * l + i] = gm.coords[3 * nodes[l] + i];
  }
  std::vector<int> tri(3 * elements.size());
  for (size_t k = 0; k < elements.size(); ++k)
    for (int a = 0; a < 3; ++a) tri[3 * k + a] = (int)(*local_of)[gm.triangles[3 * elements[k] + a]];
  // Exact preallocation of the owned rows: the neighbours over every element at the node,
  // including those of other ranks.
  std::vector<PetscInt> d_nnz(no), o_nnz(no), cols;
  const PetscInt lo = p.own_ptr[r], hi = p.own_ptr[r + 1];
  for (PetscInt l = 0; l < no; ++l) {
    cols.clear();
    for (PetscInt k = p.ne_ptr[nodes[l]]; k < p.ne_ptr[nodes[l] + 1]; ++k)
      for (int a = 0; a < 3; ++a) cols.push_back(p.petsc_id[gm.triangles[3 * p.node_elems[k] + a]]);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    d_nnz[l] = std::count_if(cols.begin(), cols.end(), [&](PetscInt c) { return c >= lo && c < hi; });
    o_nnz[l] = (PetscInt)cols.size() - d_nnz[l];
  }
  w->Put(gm.source);
  w->Put((PetscInt)gm.NumNodes()), w->Put((PetscInt)gm.NumElements());
  w->Put(no), w->Put(lo);
  w->Put(nodes), w->Put(global_id), w->Put(X), w->Put(elements), w->Put(tri), w->Put(d_nnz), w->Put(o_nnz);
  for (int kind = 0; kind < 2; ++kind) {
    const auto &sets = kind == 0 ? gm.node_sets : gm.element_sets;
    const std::vector<PetscInt> &of = kind == 0 ? *local_of : *elem_local;
    w->Put((unsigned long long)sets.size());
    for (const auto &kv : sets) {
      std::vector<PetscInt> ids;
      for (int id : kv.second)
        if (of[id] >= 0) ids.push_back(of[id]);
      std::sort(ids.begin(), ids.end());
      w->Put(kv.first), w->Put(ids);
    }
  }
  extra(RankShare{r, no, nodes, elements, *local_of}, w);
  for (PetscInt v : nodes) (*local_of)[v] = -1;
  for (PetscInt e : elements) (*elem_local)[e] = -1;
}

bool UnpackShare(ByteReader *rd, LocalMesh *m, std::vector<PetscInt> *d_nnz, std::vector<PetscInt> *o_nnz) {
  rd->Get(&m->source);
  rd->Get(&m->num_nodes_global), rd->Get(&m->num_elements_global);
  rd->Get(&m->num_owned), rd->Get(&m->owned_start);
  rd->Get(&m->natural_id), rd->Get(&m->global_id), rd->Get(&m->X), rd->Get(&m->element_natural), rd->Get(&m->tri);
  rd->Get(d_nnz), rd->Get(o_nnz);
  for (int kind = 0; kind < 2; ++kind) {
    unsigned long long nsets = 0;
    rd->Get(&nsets);
    for (unsigned long long k = 0; k < nsets && rd->ok; ++k) {
      std::string name;
      rd->Get(&name);
      rd->Get(&(kind == 0 ? m->node_sets : m->element_sets)[name]);
    }
  }
  m->num_ghost = (PetscInt)m->natural_id.size() - m->num_owned;
  m->num_elements = (PetscInt)m->element_natural.size();
  return rd->ok && m->num_ghost >= 0 && m->X.size() == 3 * m->natural_id.size() &&
         m->tri.size() == 3 * m->element_natural.size();
}

// Large buffers go in pieces (MPI counts are int).
constexpr size_t kChunk = size_t(1) << 30;

PetscErrorCode SendBytes(MPI_Comm comm, int to, const std::vector<char> &b) {
  unsigned long long n = b.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Send(&n, 1, MPI_UNSIGNED_LONG_LONG, to, 0, comm));
  for (size_t off = 0; off < b.size(); off += kChunk)
    PetscCallMPI(MPI_Send(b.data() + off, (int)std::min(kChunk, b.size() - off), MPI_BYTE, to, 0, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode RecvBytes(MPI_Comm comm, std::vector<char> *b) {
  unsigned long long n = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, comm, MPI_STATUS_IGNORE));
  b->resize(n);
  for (size_t off = 0; off < b->size(); off += kChunk)
    PetscCallMPI(MPI_Recv(b->data() + off, (int)std::min(kChunk, b->size() - off), MPI_BYTE, 0, 0, comm,
                          MPI_STATUS_IGNORE));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LocalMeshDistribute(MPI_Comm comm, const MeshData &gm, const ShareWriter &extra, LocalMesh *lm,
                                   std::vector<PetscInt> *d_nnz, std::vector<PetscInt> *o_nnz, ByteReader *extra_in) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<char> mine;
  {
    Plan plan;
    std::string err;
    int ok = 1;
    if (rank == 0) ok = MakePlan(gm, size, &plan, &err) ? 1 : 0;
    PetscCall(Rank0Outcome(comm, ok, err, PETSC_ERR_ARG_WRONG));
    if (rank == 0) {
      std::vector<PetscInt> local_of(gm.NumNodes(), -1), elem_local(gm.NumElements(), -1);
      for (int r = size - 1; r >= 0; --r) {  // rank 0's own share last: one other share in memory at a time
        ByteWriter w;
        PackShare(gm, plan, r, extra, &local_of, &elem_local, &w);
        if (r == 0) mine.swap(w.bytes);
        else PetscCall(SendBytes(comm, r, w.bytes));
      }
    } else {
      PetscCall(RecvBytes(comm, &mine));
    }
  }
  lm->share_bytes = mine.size();
  *extra_in = ByteReader(std::move(mine));
  PetscCheck(UnpackShare(extra_in, lm, d_nnz, o_nnz), PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "rank %d: the mesh share sent by rank 0 is malformed", rank);
  PetscCallMPI(MPI_Exscan(&lm->num_elements, &lm->element_start, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) lm->element_start = 0;
  PetscFunctionReturn(0);
}

// A triangle in its own MD frame (the frame of ref): node 0 at the origin, 2 coordinates a node.
static void LocalTriangle(const double X[9], const MembraneReference &ref, double T[6]) {
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 2; ++j) {
      double v = 0.0;
      for (int i = 0; i < 3; ++i) v += (X[3 * a + i] - X[i]) * ref.frame[3 * j + i];
      T[2 * a + j] = v;
    }
}

// Collective: every rank agrees on the first degenerate element (lowest scene id) and raises
// the message of the rank that holds it.
static PetscErrorCode AgreeOnBadElement(MPI_Comm comm, PetscInt bad, const std::string &msg) {
  PetscMPIInt rank;
  PetscInt first;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  const PetscInt none = PETSC_MAX_INT;
  if (bad < 0) bad = none;
  PetscCallMPI(MPI_Allreduce(&bad, &first, 1, MPIU_INT, MPI_MIN, comm));
  if (first == none) PetscFunctionReturn(0);
  PetscMPIInt holder = bad == first ? rank : INT_MAX, from;
  PetscCallMPI(MPI_Allreduce(&holder, &from, 1, MPI_INT, MPI_MIN, comm));
  std::string text = rank == from ? msg : std::string();
  int len = (int)text.size();
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, from, comm));
  text.resize(len);
  PetscCallMPI(MPI_Bcast(text.data(), len, MPI_CHAR, from, comm));
  SETERRQ(comm, PETSC_ERR_ARG_WRONG, "%s", text.c_str());
}

PetscErrorCode LocalMeshBuildReference(MPI_Comm comm, const double md_axis[3], const std::vector<double> &element_reference,
                                       LocalMesh *lm) {
  LocalMesh &m = *lm;
  PetscCheck(m.md.empty() || m.md.size() == 3 * (size_t)m.num_elements, PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "%s: %zu MD components for %" PetscInt_FMT " local elements (3 each)", m.source.c_str(), m.md.size(),
             m.num_elements);
  PetscInt bad = -1;
  std::string msg;
  PetscFunctionBeginUser;
  PetscCheck(element_reference.empty() || element_reference.size() == 9 * (size_t)m.num_elements, PETSC_COMM_SELF,
             PETSC_ERR_PLIB, "%s: %zu stress-free element coordinates for %" PetscInt_FMT " local elements (9 each)",
             m.source.c_str(), element_reference.size(), m.num_elements);
  m.ref.resize(m.num_elements);
  if (!element_reference.empty()) m.ref_placed.resize(6 * m.num_elements), m.ref_free.resize(6 * m.num_elements);
  for (PetscInt e = 0; e < m.num_elements && bad < 0; ++e) {
    double X[9];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) X[3 * a + i] = m.X[3 * m.tri[3 * e + a] + i];
    const double *axis = m.MdAxis(e, md_axis);
    int st = MembraneReferenceBuild(X, axis, 0.0, &m.ref[e]);
    if (st == KERNEL_OK && !element_reference.empty()) {
      const double *Y = &element_reference[9 * e];
      double md[3];
      MembraneReference free_ref;
      LocalTriangle(X, m.ref[e], &m.ref_placed[6 * e]);
      st = MembraneCarryAxis(X, Y, axis, md);
      if (st == KERNEL_OK) st = MembraneReferenceBuild(Y, md, 0.0, &free_ref);
      if (st == KERNEL_OK) LocalTriangle(Y, free_ref, &m.ref_free[6 * e]);
    }
    if (st != KERNEL_OK) {
      bad = m.element_natural[e];
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "%s: element %" PetscInt_FMT " (nodes %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT
                    "): %s; fix the mesh (remove or merge the element)",
                    m.source.c_str(), bad, m.natural_id[m.tri[3 * e]], m.natural_id[m.tri[3 * e + 1]],
                    m.natural_id[m.tri[3 * e + 2]], KernelStatusName(st));
      msg = buf;
    }
  }
  PetscCall(AgreeOnBadElement(comm, bad, msg));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalMeshBlendReference(MPI_Comm comm, LocalMesh *lm, double s) {
  LocalMesh &m = *lm;
  const double md[3] = {1.0, 0.0, 0.0};  // the triangles are in their MD frames
  PetscInt bad = -1, bad_global;
  PetscFunctionBeginUser;
  PetscCheck(!m.ref_free.empty(), comm, PETSC_ERR_PLIB, "no stress-free shapes to blend to");
  for (PetscInt e = 0; e < m.num_elements; ++e) {
    double Y[9] = {0.0};
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 2; ++j) Y[3 * a + j] = (1.0 - s) * m.ref_placed[6 * e + 2 * a + j] + s * m.ref_free[6 * e + 2 * a + j];
    if (MembraneReferenceBuild(Y, md, 0.0, &m.ref[e]) != KERNEL_OK && bad < 0) bad = m.element_natural[e];
  }
  PetscCallMPI(MPI_Allreduce(&bad, &bad_global, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(bad_global < 0, comm, PETSC_ERR_ARG_WRONG,
             "element %" PetscInt_FMT ": its stress-free shape blended %.3g of the way from the placed one is "
             "degenerate (the pattern folds this triangle over): check the cutting pattern of its strip",
             bad_global, s);
  m.ref_blend = s;
  PetscFunctionReturn(0);
}

} // namespace etfe
