// The branch restart's part of a checkpoint (see checkpoint_branch.h).
#include "checkpoint_branch.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "checkpoint_compare.h"
#include "etfe/io/h5io.h"

namespace etfe {

namespace {

constexpr const char *kDataset = "load_path_fingerprints";

// A 64-bit value as two exactly representable halves, each in the checksum by name.
std::uint64_t Checksum(const std::vector<std::uint64_t> &v) {
  std::uint64_t h = 0;
  for (size_t k = 0; k < v.size(); ++k) {
    const std::string name = "load_path" + std::to_string(k);
    h += ValueChecksum(name.c_str(), (double)(v[k] >> 32)) + 3 * ValueChecksum(name.c_str(), (double)(v[k] & 0xffffffffULL));
  }
  return h;
}

bool Read(hid_t f, std::vector<std::uint64_t> *v) {
  bool good = false;
  H5E_BEGIN_TRY {
    hid_t d = H5Dopen2(f, kDataset, H5P_DEFAULT);
    hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
    const hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
    if (n >= 0) {
      v->assign((size_t)n, 0);
      good = n == 0 || H5Dread(d, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v->data()) >= 0;
    }
    if (sp >= 0) H5Sclose(sp);
    if (d >= 0) H5Dclose(d);
  }
  H5E_END_TRY;
  return good;
}

} // namespace

PetscErrorCode LoadPathWrite(Problem *P, const std::string &file, hid_t f, std::uint64_t *sum) {
  std::vector<std::uint64_t> lp;
  PetscFunctionBeginUser;
  for (std::uint64_t state : P->load_path_states) lp.push_back(PhysicsFingerprintFrom(P, state));
  PetscCall(H5WriteRows(file, f, kDataset, H5T_NATIVE_UINT64, lp.size(), 1, 0, P->rank == 0 ? lp.size() : 0,
                        lp.data()));
  *sum += Checksum(lp);
  PetscFunctionReturn(0);
}

bool LoadPathVerify(hid_t f, std::uint64_t *sum) {
  if (H5Lexists(f, kDataset, H5P_DEFAULT) <= 0) return true;
  std::vector<std::uint64_t> lp;
  if (!Read(f, &lp)) return false;
  *sum += Checksum(lp);
  return true;
}

PetscErrorCode BranchDifferences(Problem *P, const std::string &path, hid_t f, std::string *table) {
  double t = 0.0;
  PetscFunctionBeginUser;
  PetscCall(H5ReadAttribute(path, f, "t", H5T_NATIVE_DOUBLE, &t));
  const long long k = std::llround(t), stages = (long long)P->scene.NumStages();
  char line[320];
  std::vector<std::uint64_t> lp;
  if (std::fabs(t - (double)k) > 1e-9) {
    std::snprintf(line, sizeof line, "\n    the checkpoint is at load time %.9g, inside a stage: a base state ends at a "
                  "stage end (write it with -checkpoint_stage_end, the default, or -checkpoint_final)", t);
    *table += line;
  } else if (k >= stages) {
    std::snprintf(line, sizeof line, "\n    the checkpoint is at the end of stage %lld and this run has %lld stages: "
                  "nothing is left to branch (add the branch's stages, e.g. -structure_stages %lld)", k, stages, k + 1);
    *table += line;
  } else if (H5Lexists(f, kDataset, H5P_DEFAULT) <= 0 || !Read(f, &lp) || (long long)lp.size() <= k)
    *table += "\n    the checkpoint holds no load-path fingerprints (written by an etfe without branch restarts): run "
              "the base again";
  else if (lp[k] != PhysicsFingerprintFrom(P, P->load_path_states[k])) {
    std::snprintf(line, sizeof line, "\n    the options agree, but what they resolve to up to load time %lld does "
                  "not: supports or their motions, loads or chambers in stages 1-%lld, the film or its material", k, k);
    *table += line;
  }
  PetscFunctionReturn(0);
}

} // namespace etfe
