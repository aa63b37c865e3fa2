// Parallel HDF5 helpers shared by the results file and the checkpoints: collective row-block
// datasets, scalar attributes, and the scatter between PETSc order (rows owned by each rank)
// and the scene's ("natural") order of nodes, elements and contact pairs.
#pragma once
#include <hdf5.h>
#include <petscvec.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "etfe/base/layout.h"

namespace etfe {

struct Problem;

// Layout::Items rows (a physics term's: a gas chamber, a cable segment) are the same on every
// rank and written by rank 0 (no natural order to scatter to).

// One row scatter per layout, created on first use; a field of ncomp values per row moves
// one component at a time, so the cache holds two vectors of one value per row and one index
// set per layout, whatever fields are written (at 10^6 triangles a scatter per (layout,
// components) kept ~12 values per element alive beside the factorization).
class NaturalOrder {
public:
  explicit NaturalOrder(Problem *p) : problem_(p) {}
  ~NaturalOrder();
  PetscInt GlobalRows(Layout layout) const;
  MPI_Comm Comm() const;
  // owned (PETSc order, ncomp per row) -> this rank's block of natural rows (nrows x ncomp).
  PetscErrorCode ToNatural(Layout layout, int ncomp, const double *owned, std::vector<double> *natural,
                           PetscInt *row0, PetscInt *nrows);
  // This rank's block of natural rows (as laid out by ToNatural) -> owned rows in PETSc order.
  PetscErrorCode FromNatural(Layout layout, int ncomp, const double *natural_rows, double *owned);
  // This rank's natural row block for a layout (row0, nrows), without moving data.
  PetscErrorCode RowBlock(Layout layout, PetscInt *row0, PetscInt *nrows);

private:
  struct Entry {
    VecScatter scatter = nullptr;
    Vec owned = nullptr, natural = nullptr;  // one value per row
  };
  PetscErrorCode Get(Layout layout, Entry **e);
  Problem *problem_;
  std::map<int, Entry> entries_;
};

// Collective: owned rows (PETSc order) written as the dataset `name` in the scene's order,
// as doubles or (as_int) integers. With `checksum`, adds the dataset's DataChecksum to it.
PetscErrorCode H5WriteNatural(const std::string &file, NaturalOrder &order, hid_t group, const char *name,
                              Layout layout, int ncomp, const double *owned, bool as_int = false,
                              uint64_t *checksum = nullptr);
// Collective: the dataset `name` (scene order) read back into owned rows (PETSc order).
PetscErrorCode H5ReadNatural(const std::string &file, NaturalOrder &order, hid_t group, const char *name,
                             Layout layout, int ncomp, double *owned);

// A checksum of a dataset that does not depend on how its rows are split over ranks: the sum
// (mod 2^64, collective) of a 64-bit mix of (dataset name, position, bit pattern) over this
// rank's rows [row0, row0 + nrows) of ncomp doubles. Any flipped bit or moved value changes it.
PetscErrorCode DataChecksum(MPI_Comm comm, const char *name, PetscInt row0, PetscInt nrows, int ncomp,
                            const double *rows, uint64_t *sum);
uint64_t ValueChecksum(const char *name, double value);

// Collective on the file's communicator. `file` names the file in messages.
PetscErrorCode H5WriteRows(const std::string &file, hid_t group, const char *name, hid_t type, hsize_t total_rows,
                           hsize_t cols, hsize_t row0, hsize_t nrows, const void *data);
PetscErrorCode H5ReadRows(const std::string &file, hid_t group, const char *name, hid_t type, hsize_t total_rows,
                          hsize_t cols, hsize_t row0, hsize_t nrows, void *data);
PetscErrorCode H5WriteAttribute(const std::string &file, hid_t obj, const char *name, hid_t type, const void *value);
// A 1-D double array attribute (at least one value).
PetscErrorCode H5WriteArrayAttribute(const std::string &file, hid_t obj, const char *name, const std::vector<double> &v);
PetscErrorCode H5WriteString(const std::string &file, hid_t obj, const char *name, const std::string &value);
PetscErrorCode H5ReadAttribute(const std::string &file, hid_t obj, const char *name, hid_t type, void *value);
PetscErrorCode H5ReadString(const std::string &file, hid_t obj, const char *name, std::string *value);

// H5Fclose of a file that was written, noting a failure: after a failed close (a full disk) this
// HDF5 (1.10) keeps an identifier whose file it has freed, and closing the library (H5close,
// MPI_Finalize's callback) then crashes on it.
herr_t H5FcloseWritten(hid_t file);
// Whether such a close failed in this process (the library must then not be closed).
bool H5AnyCloseFailed();

} // namespace etfe
