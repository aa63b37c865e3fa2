// Tension-field membrane around any law with an elastic part (-membrane_wrinkling
// tension_field). The kernel (src/kernels/wrinkling.cpp) decides taut / wrinkled /
// slack from the elastic strain Ee = E - Ep (Ep the committed plastic strain, 0 for the elastic
// law) with the mixed stress/strain criterion:
//  * taut: the wrapped law runs unchanged (the same call, so an element that never wrinkles
//    gives bit for bit the numbers of -membrane_wrinkling none, plastic return map included);
//  * wrinkled or slack, elastic law: the relaxed stress of E and its tangent;
//  * the ETFE elasto-plastic law: src/kernels/wrinkling_plastic.cpp decides on the plane-stress
//    return map's answer (taut when it leaves no compression); a wrinkled element flows by a
//    uniaxial return map along the wrinkles (associated flow of the uniaxial stress, on the
//    same hardening curve); a slack one keeps its history (no stress, no flow).
// A taut trial stays taut through the return map (the plane-stress map shrinks the deviatoric
// modes faster than the mean one, so the minor principal stress does not drop below 0).
#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

#include "etfe/kernels/status.h"
#include "etfe/kernels/wrinkling.h"
#include "etfe/kernels/wrinkling_plastic.h"
#include "etfe/material/material.h"

namespace etfe {

namespace {

class TensionFieldMaterial : public Material {
public:
  explicit TensionFieldMaterial(std::unique_ptr<Material> in)
      : inner(std::move(in)), name(std::string(inner->Name()) + " + tension field") {}
  const char *Name() const override { return name.c_str(); }
  int HistorySize() const override { return inner->HistorySize(); }
  void InitHistory(double *h) const override { inner->InitHistory(h); }
  bool HasPlasticStrain() const override { return inner->HasPlasticStrain(); }
  bool PlasticStrain(const double *h, double ep[3], double *ep_bar) const override {
    return inner->PlasticStrain(h, ep, ep_bar);
  }
  void ElasticConstants(double *e, double *n) const override { inner->ElasticConstants(e, n); }
  void SetIncrementSeconds(double seconds) override { inner->SetIncrementSeconds(seconds); }
  // The wrapped law's plastic parameters: the relaxed film yields where the inner law does.
  const PlasticMaterial *PlasticLaw() const override { return inner->PlasticLaw(); }

  bool Wrinkling(const double E[3], const double *hist, WrinkleInfo *info) const override {
    if (const PlasticMaterial *pm = inner->PlasticLaw()) {
      PlasticState committed, trial;
      double S[3], D[9];
      std::memcpy(&committed, hist, sizeof committed);
      TensionFieldPlastic(*pm, E, committed, &trial, S, D, info);
      return true;
    }
    double young, nu, Ee[3];
    ElasticStrain(E, hist, Ee, &young, &nu);
    TensionFieldClassify(young, nu, Ee, info);
    return true;
  }

  int Evaluate(const double E[3], const double *hold, double *hnew, double S[3],
               double D[9]) const override {
    double Dl[9];
    if (const PlasticMaterial *pm = inner->PlasticLaw()) {
      PlasticState committed, trial;
      std::memcpy(&committed, hold, sizeof committed);
      const int st = TensionFieldPlastic(*pm, E, committed, &trial, S, D ? D : Dl, nullptr);
      if (hnew) std::memcpy(hnew, &trial, sizeof trial);
      return st;
    }
    double young, nu, Ee[3];
    ElasticStrain(E, hold, Ee, &young, &nu);
    WrinkleInfo info;
    TensionFieldClassify(young, nu, Ee, &info);
    if (info.state == WRINKLE_TAUT) return inner->Evaluate(E, hold, hnew, S, D);
    TensionFieldStress(young, nu, Ee, S, D ? D : Dl, nullptr);
    if (hnew) std::copy(hold, hold + inner->HistorySize(), hnew);
    return KERNEL_OK;
  }

  PetscErrorCode View(MPI_Comm comm) const override {
    PetscFunctionBeginUser;
    PetscCall(inner->View(comm));
    PetscCall(PetscPrintf(comm, "  wrinkling: tension field (no compression; taut/wrinkled/slack per element%s)\n",
                          inner->PlasticLaw() ? "; uniaxial return map along the wrinkles, no flow while slack" : ""));
    PetscFunctionReturn(0);
  }

private:
  std::unique_ptr<Material> inner;
  std::string name;

  void ElasticStrain(const double E[3], const double *hist, double Ee[3], double *young,
                     double *nu) const {
    inner->ElasticConstants(young, nu);
    double ep[3] = {0.0, 0.0, 0.0}, ep_bar;
    if (hist && inner->HasPlasticStrain()) inner->PlasticStrain(hist, ep, &ep_bar);
    for (int i = 0; i < 3; ++i) Ee[i] = E[i] - ep[i];
  }
};

} // namespace

std::unique_ptr<Material> MaterialWrapTensionField(std::unique_ptr<Material> inner) {
  return std::make_unique<TensionFieldMaterial>(std::move(inner));
}

} // namespace etfe
