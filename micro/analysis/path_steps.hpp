#pragma once
// The step sizes of the crack analysis's path following (docs/physics.md section 2): one increment per
// path control, halved when a step fails (the control gives up below its minimum) and grown after easy
// steps (up to its maximum), so each control keeps the step size its own history found.
#include <algorithm>

namespace uhpc::micro {

// What a path step holds: the far-face displacement lambda, the crack-opening integral over all
// cohesive points, or the opening integral over the process zone only.
enum class Hold { Lambda, Opening, Zone };

class PathSteps {
 public:
  struct Range {
    double initial, min, max;
  };
  // `opening`: the opening holds' increments (of the mean opening / w_c); `strain`: the displacement
  // hold's (of e_bar); `growth`: the factor after an easy step.
  PathSteps(Range opening, Range strain, double growth) : opening_(opening), strain_(strain), growth_(growth) {
    reset_openings();
    lambda_ = strain.initial;
  }

  double size(Hold h) const { return h == Hold::Zone ? zone_ : h == Hold::Opening ? crack_ : lambda_; }
  // Halves the increment of `h`; false once it is below the minimum (the control has failed).
  bool cut(Hold h) {
    double& d = of(h);
    d *= 0.5;
    return d >= range(h).min;
  }
  // After a step that converged easily.
  void grow(Hold h) {
    double& d = of(h);
    d = std::min(d * growth_, range(h).max);
  }
  // Both opening holds back to their initial increment (a new control phase begins).
  void reset_openings() { crack_ = zone_ = opening_.initial; }

 private:
  double& of(Hold h) { return h == Hold::Zone ? zone_ : h == Hold::Opening ? crack_ : lambda_; }
  const Range& range(Hold h) const { return h == Hold::Lambda ? strain_ : opening_; }

  Range opening_, strain_;
  double growth_;
  double crack_ = 0.0, zone_ = 0.0, lambda_ = 0.0;
};

}  // namespace uhpc::micro
