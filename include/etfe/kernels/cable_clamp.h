// A sliding cable through clamps with capstan friction (docs/theory.md §14, docs/cables.md).
// PETSc-free, no allocation.
//
// The clamps split the cable's chain into m sub-chains j = 0 .. m-1 (clamp i joins sub-chain i to
// sub-chain i + 1). Each sub-chain carries one force N_j = EA (l_j - L0_j) / L0_j (engineering
// strain over the sub-chain, 0 when l_j <= L0_j), l_j its current length, L0_j its stress-free
// length. Stress-free length crosses a clamp only by slip: in an increment, clamp i passes
// Delta_i from sub-chain i to sub-chain i + 1 (negative: the other way), so
// L0_j = L0c_j - Delta_j + Delta_{j-1} and the total stress-free length is conserved.
//
// The law at clamp i (Coulomb friction over the wrap: the capstan, or Euler-Eytelwein, law), with
// r_i = exp(mu theta_i) >= 1 and theta_i the cable's turning angle at the clamp node:
//   Phi_i = max(N_i, N_{i+1}) - r_i min(N_i, N_{i+1}) <= 0;
//   stick (Phi_i < 0): Delta_i = 0;  slip: Phi_i = 0, the cable moves towards the higher force
//   (Delta_i > 0 when N_{i+1} > N_i), never against it.
// Return map (backward Euler over the increment, like the contact law's implicit return map):
// from the committed lengths L0c an elastic (all-stick) trial; the clamps whose trial violates
// Phi <= 0 slip, their equations N_high - r N_low = 0 are solved by Newton in Delta; a slipping
// clamp whose Delta comes out against its direction sticks again, a sticking one whose Phi turns
// positive slips; repeated until the set settles.
//
// Tangent: at the solution the slipping clamps' equations G(Delta, l, r) = 0 hold, so
// dDelta/dl = -G_Delta^-1 G_l and dDelta/dr = -G_Delta^-1 G_r (implicit function theorem); the
// returned dN/dl and dN/dr are the exact derivatives of the returned forces for a fixed set of
// slipping clamps (the finite-difference checks, stick and slip).
#pragma once

namespace etfe {

// Clamps per cable the kernels take (fixed arrays: a kernel allocates nothing).
constexpr int kCableMaxClamps = 16;

// What the return map found.
struct CableClampReturnResult {
  int iterations = 0;  // Newton iterations over all active-set passes
  bool converged = true;
};

// The return map. m = clamps + 1 sub-chains (1 <= m <= kCableMaxClamps + 1).
// In: l[m] current sub-chain lengths, L0c[m] committed stress-free lengths, EA, r[m-1] capstan
// ratios exp(mu theta) (>= 1).
// Out: N[m] forces, L0[m] stress-free lengths, delta[m-1] slip in this increment (+: from sub-chain
// i into i + 1), status[m-1] (0 stick, +1 slip into i + 1, -1 slip into i); where not null,
// dNdl[m x m] (dN_j/dl_k, row-major) and dNdr[m x (m-1)] (dN_j/dr_i).
CableClampReturnResult CableClampReturn(int m, const double *l, const double *L0c, double EA, const double *r, double *N,
                                        double *L0, double *delta, int *status, double *dNdl, double *dNdr);

// The cable's turning angle at node b between the segments a -> b and b -> c:
// theta = atan2(|e1 x e2|, e1 . e2) in [0, pi]; grad (9: d theta / d(a, b, c)) where not null
// (zero where the cable runs straight, theta < 1e-12: the angle has a kink there).
double CableTurningAngle(const double a[3], const double b[3], const double c[3], double grad[9]);

// A sliding cable through clamps, nodes 0 .. k in the layout of CableSliding (cable.h), clamps at
// the interior node indices clamp[0] < ... < clamp[nc-1] (0 < clamp < k), friction coefficient mu
// (every clamp), committed stress-free lengths L0c[nc + 1]. At x: the sub-chains' lengths, the
// turning angles (current geometry), the return map; f = sum_j N_j dl_j/dx (3 (k+1)); K = df/dx
// ((3 (k+1))^2, row-major, may be null):
//   sum_j N_j (segment geometric stiffness) + sum_jk dN_j/dl_k g_j g_k^T
//   + sum_ji dN_j/dr_i g_j (mu r_i dtheta_i/dx)^T,     g_j = dl_j/dx;
// the last part makes K non-symmetric where clamps slip. state (may be null) receives per
// sub-chain length and force and stress-free length, per clamp angle, ratio, slip and status.
struct CableClampState {
  double length[kCableMaxClamps + 1], force[kCableMaxClamps + 1], L0[kCableMaxClamps + 1];
  double theta[kCableMaxClamps], ratio[kCableMaxClamps], delta[kCableMaxClamps];
  int status[kCableMaxClamps];
  CableClampReturnResult result;
};
void CableClamped(int nodes, const double *x, int nc, const int *clamp, const double *L0c, double EA, double mu,
                  double *f, double *K, CableClampState *state);

} // namespace etfe
