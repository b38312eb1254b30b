#pragma once
// Kernel (window) functions of the RK approximation, in the normalized distance z = |x - x_I| / a_I
// (a_I the support radius). Radial kernels: the support is a disc (2D) or ball (3D). Only the shape
// matters for RK shape functions (the moment matrix cancels any normalization), so the kernels are
// left unnormalized, with phi(0) = 2/3 (cubic B-spline) and 1 (quartic spline).
#include <string>
#include <string_view>

namespace uhpc {

enum class KernelType { CubicBSpline, QuarticSpline };

struct KernelValue {
  double w;      // phi(z)
  double dw_dz;  // d phi / d z
};

// phi and its derivative at z >= 0; zero for z >= 1. Inline: it sits in the innermost loops.
inline KernelValue kernel_value(KernelType type, double z) {
  if (z >= 1.0) return {0.0, 0.0};
  switch (type) {
    case KernelType::CubicBSpline:
      if (z <= 0.5) return {2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z, -8.0 * z + 12.0 * z * z};
      {
        const double s = 1.0 - z;  // 4/3 (1-z)^3 on [1/2, 1)
        return {4.0 / 3.0 * s * s * s, -4.0 * s * s};
      }
    case KernelType::QuarticSpline: {
      const double z2 = z * z;
      return {1.0 - 6.0 * z2 + 8.0 * z2 * z - 3.0 * z2 * z2, -12.0 * z + 24.0 * z2 - 12.0 * z2 * z};
    }
  }
  return {0.0, 0.0};
}

// "cubic_bspline" | "quartic_spline"; throws std::invalid_argument listing the names otherwise.
KernelType kernel_from_name(std::string_view name);
std::string kernel_name(KernelType type);

}  // namespace uhpc
