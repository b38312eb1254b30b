#pragma once
// The rigid sphere of the macro tests' impact case: 10 g, 6 mm radius, over the centre of the z = 0
// face of the 50 x 40 x 30 mm box of box_body(0.05, 0.04, 0.03, 0.005), a few um from the four
// particles nearest its axis, flying in at `speed` (m/s).
#include "solver/rigid_sphere.hpp"

namespace uhpc::test {

inline macro::RigidSphere box_impact_sphere(double speed = 300.0) {
  macro::RigidSphere sphere;
  sphere.mass_kg = 0.01;
  sphere.radius_m = 0.006;
  sphere.x = {0.025, 0.02, -0.0053};
  sphere.v = {0.0, 0.0, speed};
  return sphere;
}

}  // namespace uhpc::test
