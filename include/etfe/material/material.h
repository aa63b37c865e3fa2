// Constitutive laws behind one interface: GL strain (and committed history) in, PK2 stress and
// tangent (and trial history) out. Registered by name (-material_type). An elastic law keeps no
// history, so a scene without plasticity allocates none. The film has one law; a surface group of
// the general scene may have its own (-film_<group>_material_*, Problem::MaterialOf).
#pragma once
#include <petscsys.h>

#include <memory>

namespace etfe {

struct WrinkleInfo;      // etfe/kernels/wrinkling.h
struct PlasticMaterial;  // etfe/kernels/plasticity.h

class Material {
public:
  virtual ~Material() = default;
  virtual const char *Name() const = 0;
  // Doubles of history per element; 0 means no history arrays are allocated.
  virtual int HistorySize() const { return 0; }
  virtual void InitHistory(double *hist) const {}
  // S, D from E = (Exx, Eyy, 2Exy) in the element frame. hist_old/hist_new are nullptr when
  // HistorySize() == 0. Returns a KernelStatus.
  virtual int Evaluate(const double E[3], const double *hist_old, double *hist_new, double S[3],
                       double D[9]) const = 0;
  // Physical seconds from the committed history to the state Evaluate is asked for (the load
  // stepper sets it per increment; 0, the default, is the committed state's instantaneous
  // response). Only laws with time read it.
  virtual void SetIncrementSeconds(double seconds) {}
  // Whether the history holds a plastic strain (then PlasticStrain reads it).
  virtual bool HasPlasticStrain() const { return false; }
  // Plastic strain (Voigt) and its equivalent value from a history record, if the law has one.
  virtual bool PlasticStrain(const double *hist, double ep[3], double *ep_bar) const {
    return false;
  }
  // The ETFE elasto-plastic parameters when the law is that one (the tension field's wrinkled
  // return map needs them), else nullptr.
  virtual const PlasticMaterial *PlasticLaw() const { return nullptr; }
  // Tension-field state at E from the committed history (-membrane_wrinkling tension_field):
  // false when the law does not relax compression.
  virtual bool Wrinkling(const double E[3], const double *hist, WrinkleInfo *info) const {
    return false;
  }
  // Young's modulus and Poisson's ratio (every law here has an elastic part).
  virtual void ElasticConstants(double *young, double *nu) const = 0;
  virtual PetscErrorCode View(MPI_Comm comm) const = 0;
};

// Most history doubles per element a law may keep (the element loops hold one on the stack):
// the viscoelastic-plastic law with 32 Prony terms keeps 7 + 3 * 32.
constexpr int kMaxHistorySize = 112;

// prefix: nullptr for the film's law (-material_*); "film_<group>_" for a surface group's own law
// (-film_<group>_material_*, each option falling back to the film's -material_* value).
typedef PetscErrorCode (*MaterialCreator)(const char *prefix, std::unique_ptr<Material> *);

// Form finding: a constant PK2 stress (s_md, s_td, 0) in the element's MD/TD frame and no
// material stiffness, so the tangent is the geometric stiffness alone (thesis eqs. 2.14-2.20).
std::unique_ptr<Material> MaterialCreatePrescribedStress(double s_md, double s_td);

// The law wrapped in the tension-field membrane (-membrane_wrinkling tension_field,
// src/material/tension_field.cpp): compression relaxed (plastic: uniaxial flow along the wrinkles).
std::unique_ptr<Material> MaterialWrapTensionField(std::unique_ptr<Material> inner);

PetscErrorCode MaterialRegisterAll(void);
// The law of -material_type and its -material_* options; with a prefix ("film_<group>_") the
// group's -film_<group>_material_* options over the film's (collective).
PetscErrorCode MaterialCreateFromOptions(MPI_Comm comm, std::unique_ptr<Material> *material,
                                         const char *prefix = nullptr);
// Whether any -<prefix>material_* option a law reads is given (a surface group's own law).
PetscErrorCode MaterialOptionsGiven(MPI_Comm comm, const char *prefix, PetscBool *given);

} // namespace etfe
