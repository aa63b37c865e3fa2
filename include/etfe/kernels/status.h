// Status codes returned by the pure physics kernels. The assembler turns a non-OK status into
// SNESSetFunctionDomainError() and names the element or contact pair.
#pragma once

namespace etfe {

enum KernelStatus : int {
  KERNEL_OK = 0,
  KERNEL_DEGENERATE = 1,  // reference triangle with (near) zero area or repeated nodes
  KERNEL_COLLAPSED = 2,   // current area ratio below the allowed minimum
  KERNEL_NONFINITE = 3,   // NaN or Inf in the input or the result
  KERNEL_NO_CONVERGENCE = 4  // a local Newton (return map) did not converge
};

inline const char *KernelStatusName(int s) {
  switch (s) {
  case KERNEL_OK: return "ok";
  case KERNEL_DEGENERATE: return "degenerate reference triangle";
  case KERNEL_COLLAPSED: return "collapsed element";
  case KERNEL_NONFINITE: return "non-finite value";
  case KERNEL_NO_CONVERGENCE: return "local return map did not converge";
  default: return "unknown kernel status";
  }
}

} // namespace etfe
