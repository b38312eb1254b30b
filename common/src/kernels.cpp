#include "uhpc/kernels.hpp"

#include <stdexcept>

namespace uhpc {

KernelType kernel_from_name(std::string_view name) {
  if (name == "cubic_bspline") return KernelType::CubicBSpline;
  if (name == "quartic_spline") return KernelType::QuarticSpline;
  throw std::invalid_argument("unknown kernel '" + std::string(name) +
                              "', expected one of: cubic_bspline, quartic_spline");
}

std::string kernel_name(KernelType type) {
  switch (type) {
    case KernelType::CubicBSpline: return "cubic_bspline";
    case KernelType::QuarticSpline: return "quartic_spline";
  }
  return "unknown";
}

}  // namespace uhpc
