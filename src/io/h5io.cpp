// Parallel HDF5 helpers (see h5io.h).
#include "etfe/io/h5io.h"

#include <cerrno>
#include <cstring>
#include <vector>

#include "etfe/assembly/problem.h"

namespace etfe {

#define ETFE_H5CHECK(call, what)                                                                   \
  do {                                                                                             \
    if ((call) < 0)                                                                                \
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,                                          \
              "HDF5: %s failed in %s (disk full, quota, or the file removed or damaged?); the "      \
              "steps listed in its .xmf are complete", what, file.c_str());                        \
  } while (0)

NaturalOrder::~NaturalOrder() {
  for (auto &kv : entries_) {
    VecScatterDestroy(&kv.second.scatter);
    VecDestroy(&kv.second.owned);
    VecDestroy(&kv.second.natural);
  }
}

PetscInt NaturalOrder::GlobalRows(Layout layout) const {
  const Problem *P = problem_;
  switch (layout) {
  case Layout::Nodes: return P->mesh.num_nodes_global;
  case Layout::Cells: return P->mesh.num_elements_global;
  case Layout::Items: return 0;  // replicated: H5WriteRows, never scattered
  case Layout::Pairs: {
    PetscInt n = 0, first;
    std::vector<PetscInt> ids;
    for (const auto &term : P->terms)
      if (term->PairRows(&n, &first, &ids)) break;
    return n;
  }
  }
  return 0;
}

MPI_Comm NaturalOrder::Comm() const { return problem_->comm; }

PetscErrorCode NaturalOrder::Get(Layout layout, Entry **result) {
  Problem *P = problem_;
  const LocalMesh &m = P->mesh;
  PetscFunctionBeginUser;
  auto it = entries_.find((int)layout);
  if (it == entries_.end()) {
    PetscInt nloc = 0, first = 0;
    std::vector<PetscInt> to;
    if (layout == Layout::Nodes) {
      nloc = m.num_owned, first = m.owned_start;
      to.assign(m.natural_id.begin(), m.natural_id.begin() + nloc);
    } else if (layout == Layout::Cells) {
      nloc = m.num_elements, first = m.element_start;
      to.assign(m.element_natural.begin(), m.element_natural.end());
    } else {
      PetscInt n;
      for (const auto &term : P->terms)
        if (term->PairRows(&n, &first, &to)) break;
      nloc = (PetscInt)to.size();
    }
    const PetscInt nglob = GlobalRows(layout);
    Entry e;
    IS isf, ist;
    PetscInt n = PETSC_DECIDE, N = nglob;
    PetscCall(PetscSplitOwnership(P->comm, &n, &N));
    PetscCall(VecCreateMPI(P->comm, nloc, nglob, &e.owned));
    PetscCall(VecCreateMPI(P->comm, n, nglob, &e.natural));
    PetscCall(ISCreateStride(P->comm, nloc, first, 1, &isf));
    PetscCall(ISCreateGeneral(P->comm, nloc, to.data(), PETSC_COPY_VALUES, &ist));
    PetscCall(VecScatterCreate(e.owned, isf, e.natural, ist, &e.scatter));
    PetscCall(ISDestroy(&isf));
    PetscCall(ISDestroy(&ist));
    it = entries_.emplace((int)layout, e).first;
  }
  *result = &it->second;
  PetscFunctionReturn(0);
}

PetscErrorCode NaturalOrder::RowBlock(Layout layout, PetscInt *row0, PetscInt *nrows) {
  Entry *e;
  PetscInt lo, n;
  PetscFunctionBeginUser;
  PetscCall(Get(layout, &e));
  PetscCall(VecGetOwnershipRange(e->natural, &lo, nullptr));
  PetscCall(VecGetLocalSize(e->natural, &n));
  *row0 = lo;
  *nrows = n;
  PetscFunctionReturn(0);
}

PetscErrorCode NaturalOrder::ToNatural(Layout layout, int ncomp, const double *owned, std::vector<double> *natural,
                                       PetscInt *row0, PetscInt *nrows) {
  Entry *e;
  PetscScalar *a;
  const PetscScalar *b;
  PetscInt n, nn;
  PetscFunctionBeginUser;
  PetscCall(Get(layout, &e));
  PetscCall(VecGetLocalSize(e->owned, &n));
  PetscCall(RowBlock(layout, row0, nrows));
  nn = *nrows;
  natural->assign((size_t)nn * ncomp, 0.0);
  for (int c = 0; c < ncomp; ++c) {
    PetscCall(VecGetArray(e->owned, &a));
    for (PetscInt i = 0; i < n; ++i) a[i] = owned[(size_t)i * ncomp + c];
    PetscCall(VecRestoreArray(e->owned, &a));
    PetscCall(VecScatterBegin(e->scatter, e->owned, e->natural, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(e->scatter, e->owned, e->natural, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(e->natural, &b));
    for (PetscInt j = 0; j < nn; ++j) (*natural)[(size_t)j * ncomp + c] = b[j];
    PetscCall(VecRestoreArrayRead(e->natural, &b));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode NaturalOrder::FromNatural(Layout layout, int ncomp, const double *natural_rows, double *owned) {
  Entry *e;
  PetscScalar *a;
  const PetscScalar *b;
  PetscInt n, nn;
  PetscFunctionBeginUser;
  PetscCall(Get(layout, &e));
  PetscCall(VecGetLocalSize(e->natural, &nn));
  PetscCall(VecGetLocalSize(e->owned, &n));
  for (int c = 0; c < ncomp; ++c) {
    PetscCall(VecGetArray(e->natural, &a));
    for (PetscInt j = 0; j < nn; ++j) a[j] = natural_rows[(size_t)j * ncomp + c];
    PetscCall(VecRestoreArray(e->natural, &a));
    PetscCall(VecScatterBegin(e->scatter, e->natural, e->owned, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(e->scatter, e->natural, e->owned, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecGetArrayRead(e->owned, &b));
    for (PetscInt i = 0; i < n; ++i) owned[(size_t)i * ncomp + c] = b[i];
    PetscCall(VecRestoreArrayRead(e->owned, &b));
  }
  PetscFunctionReturn(0);
}

namespace {

PetscErrorCode SelectRows(const std::string &file, hid_t fspace, hid_t mspace, hsize_t row0, hsize_t nrows,
                          hsize_t cols) {
  hsize_t start[2] = {row0, 0}, count[2] = {nrows, cols};
  PetscFunctionBeginUser;
  if (nrows > 0) {
    ETFE_H5CHECK(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), "row selection");
  } else {
    H5Sselect_none(fspace);
    H5Sselect_none(mspace);
  }
  PetscFunctionReturn(0);
}

// A collective write can fail on some ranks only (a full disk): every rank of the file learns it,
// so that all stop together (and can mark the results failed) instead of waiting for each other.
// write_errno: errno right after the write (a full disk says so only there).
PetscErrorCode AgreeOnWrite(const std::string &file, hid_t obj, const char *name, bool written, int write_errno) {
  int ok = written, all = ok;
  PetscFunctionBeginUser;
  hid_t fid = H5Iget_file_id(obj), fapl = fid >= 0 ? H5Fget_access_plist(fid) : -1;
  if (fapl >= 0 && H5Pget_driver(fapl) == H5FD_MPIO) {
    MPI_Comm comm;
    MPI_Info info;
    if (H5Pget_fapl_mpio(fapl, &comm, &info) >= 0) {
      PetscCallMPI(MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm));
      PetscCallMPI(MPI_Comm_free(&comm));
      if (info != MPI_INFO_NULL) PetscCallMPI(MPI_Info_free(&info));
    }
  }
  if (fapl >= 0) H5Pclose(fapl);
  if (fid >= 0) H5Fclose(fid);
  if (!ok) errno = write_errno;  // for the error exit's message and status
  PetscCheck(all, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: writing %s failed in %s%s", name, file.c_str(),
             ok ? " (on another rank)" : "");
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode H5WriteRows(const std::string &file, hid_t group, const char *name, hid_t type, hsize_t total_rows,
                           hsize_t cols, hsize_t row0, hsize_t nrows, const void *data) {
  PetscFunctionBeginUser;
  hsize_t dims[2] = {total_rows, cols}, count[2] = {nrows, cols};
  const int rank = cols > 1 ? 2 : 1;
  hid_t fspace = H5Screate_simple(rank, dims, nullptr);
  hid_t dset = H5Dcreate2(group, name, type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(dset, name);
  hid_t mspace = H5Screate_simple(rank, count, nullptr);
  PetscCall(SelectRows(file, fspace, mspace, row0, nrows, cols));
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  errno = 0;
  const herr_t written = H5Dwrite(dset, type, mspace, fspace, dxpl, data);
  const int write_errno = errno;
  H5Pclose(dxpl);
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(dset);
  PetscCall(AgreeOnWrite(file, group, name, written >= 0, write_errno));
  PetscFunctionReturn(0);
}

PetscErrorCode H5ReadRows(const std::string &file, hid_t group, const char *name, hid_t type, hsize_t total_rows,
                          hsize_t cols, hsize_t row0, hsize_t nrows, void *data) {
  PetscFunctionBeginUser;
  PetscCheck(H5Lexists(group, name, H5P_DEFAULT) > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "%s: dataset %s is missing (not a complete file of this kind)", file.c_str(), name);
  hid_t dset = H5Dopen2(group, name, H5P_DEFAULT);
  ETFE_H5CHECK(dset, name);
  hid_t fspace = H5Dget_space(dset);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_ndims(fspace);
  H5Sget_simple_extent_dims(fspace, dims, nullptr);
  PetscCheck(dims[0] == total_rows && (rank == 1 ? cols == 1 : dims[1] == cols), PETSC_COMM_SELF,
             PETSC_ERR_FILE_UNEXPECTED, "%s: dataset %s has %llu x %llu entries, expected %llu x %llu", file.c_str(),
             name, (unsigned long long)dims[0], (unsigned long long)(rank == 1 ? 1 : dims[1]),
             (unsigned long long)total_rows, (unsigned long long)cols);
  hsize_t count[2] = {nrows, cols};
  hid_t mspace = H5Screate_simple(rank, count, nullptr);
  PetscCall(SelectRows(file, fspace, mspace, row0, nrows, cols));
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  ETFE_H5CHECK(H5Dread(dset, type, mspace, fspace, dxpl, data), name);
  H5Pclose(dxpl);
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(dset);
  PetscFunctionReturn(0);
}

namespace {
// One attribute of obj in the given dataspace, replacing an existing one of that name.
PetscErrorCode WriteAttributeIn(const std::string &file, hid_t obj, const char *name, hid_t type, hid_t space,
                                const void *value) {
  PetscFunctionBeginUser;
  if (H5Aexists(obj, name) > 0) ETFE_H5CHECK(H5Adelete(obj, name), name);
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(a, name);
  ETFE_H5CHECK(H5Awrite(a, type, value), name);
  H5Aclose(a);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode H5WriteAttribute(const std::string &file, hid_t obj, const char *name, hid_t type, const void *value) {
  PetscFunctionBeginUser;
  hid_t space = H5Screate(H5S_SCALAR);
  PetscErrorCode ierr = WriteAttributeIn(file, obj, name, type, space, value);
  H5Sclose(space);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode H5WriteArrayAttribute(const std::string &file, hid_t obj, const char *name, const std::vector<double> &v) {
  PetscFunctionBeginUser;
  const hsize_t n = v.size();
  hid_t space = H5Screate_simple(1, &n, nullptr);
  PetscErrorCode ierr = WriteAttributeIn(file, obj, name, H5T_NATIVE_DOUBLE, space, v.data());
  H5Sclose(space);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode H5WriteString(const std::string &file, hid_t obj, const char *name, const std::string &v) {
  PetscFunctionBeginUser;
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, v.size() + 1);
  PetscCall(H5WriteAttribute(file, obj, name, t, v.c_str()));
  H5Tclose(t);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ReadAttribute(const std::string &file, hid_t obj, const char *name, hid_t type, void *value) {
  PetscFunctionBeginUser;
  PetscCheck(H5Aexists(obj, name) > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "%s: attribute %s is missing (not a file of this kind, or written by another version)", file.c_str(),
             name);
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  ETFE_H5CHECK(a, name);
  ETFE_H5CHECK(H5Aread(a, type, value), name);
  H5Aclose(a);
  PetscFunctionReturn(0);
}

PetscErrorCode H5ReadString(const std::string &file, hid_t obj, const char *name, std::string *value) {
  PetscFunctionBeginUser;
  PetscCheck(H5Aexists(obj, name) > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "%s: attribute %s is missing (not a file of this kind)", file.c_str(), name);
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t t = H5Aget_type(a);
  size_t n = H5Tget_size(t);
  std::vector<char> buf(n + 1, 0);
  ETFE_H5CHECK(H5Aread(a, t, buf.data()), name);
  H5Tclose(t);
  H5Aclose(a);
  *value = buf.data();
  PetscFunctionReturn(0);
}

namespace {

uint64_t Mix(uint64_t x) {  // splitmix64's finalizer: every input bit reaches every output bit
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

uint64_t NameHash(const char *name) {  // FNV-1a
  uint64_t h = 0xcbf29ce484222325ULL;
  for (const char *c = name; *c; ++c) h = (h ^ (unsigned char)*c) * 0x100000001b3ULL;
  return h;
}

uint64_t Bits(double v) {
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

} // namespace

uint64_t ValueChecksum(const char *name, double value) { return Mix(NameHash(name) ^ Mix(Bits(value))); }

PetscErrorCode DataChecksum(MPI_Comm comm, const char *name, PetscInt row0, PetscInt nrows, int ncomp,
                            const double *rows, uint64_t *sum) {
  const uint64_t salt = NameHash(name);
  uint64_t local = 0, total = 0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nrows * ncomp; ++i) {
    const uint64_t pos = (uint64_t)(row0 * ncomp + i);
    local += Mix(salt ^ Mix(pos + 0x9e3779b97f4a7c15ULL) ^ Mix(Bits(rows[i]) + pos));
  }
  PetscCallMPI(MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm));
  *sum += total;
  PetscFunctionReturn(0);
}

PetscErrorCode H5WriteNatural(const std::string &file, NaturalOrder &order, hid_t group, const char *name,
                              Layout layout, int ncomp, const double *owned, bool as_int, uint64_t *checksum) {
  std::vector<double> a;
  PetscInt row0 = 0, nrows = 0;
  PetscFunctionBeginUser;
  PetscCall(order.ToNatural(layout, ncomp, owned, &a, &row0, &nrows));
  const hsize_t total = order.GlobalRows(layout);
  if (checksum) PetscCall(DataChecksum(order.Comm(), name, row0, nrows, ncomp, a.data(), checksum));
  if (as_int) {
    std::vector<int> v(a.begin(), a.end());
    PetscCall(H5WriteRows(file, group, name, H5T_NATIVE_INT, total, ncomp, row0, nrows, v.data()));
  } else {
    PetscCall(H5WriteRows(file, group, name, H5T_NATIVE_DOUBLE, total, ncomp, row0, nrows, a.data()));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode H5ReadNatural(const std::string &file, NaturalOrder &order, hid_t group, const char *name,
                             Layout layout, int ncomp, double *owned) {
  PetscInt row0, nrows;
  PetscFunctionBeginUser;
  PetscCall(order.RowBlock(layout, &row0, &nrows));
  std::vector<double> rows((size_t)nrows * ncomp);
  PetscCall(H5ReadRows(file, group, name, H5T_NATIVE_DOUBLE, order.GlobalRows(layout), ncomp, row0, nrows,
                       rows.data()));
  PetscCall(order.FromNatural(layout, ncomp, rows.data(), owned));
  PetscFunctionReturn(0);
}

namespace {
bool g_close_failed = false;
} // namespace

herr_t H5FcloseWritten(hid_t file) {
  const herr_t r = H5Fclose(file);
  if (r < 0) g_close_failed = true;
  return r;
}

bool H5AnyCloseFailed() { return g_close_failed; }

} // namespace etfe
