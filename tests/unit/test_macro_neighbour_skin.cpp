// The Verlet skin of the shape cache (SolverOptions::neighbour_skin) is exact: candidate lists searched
// with grown radii and filtered with the search's own test give the same neighbour lists, in the same
// order, as a fresh search, so a run with the skin is bitwise identical to one without. Checked on a
// spinning, deforming free body and on the sphere impact (fast particles force re-searches), and the
// skin must actually save searches.
#include <cstdio>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "box_impact_sphere.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

ExplicitSolver make(double skin, bool sphere_impact) {
  const ParticleBody body = box_body(0.05, 0.04, 0.03, 0.005);
  SolverOptions options;
  options.neighbour_skin = skin;
  options.support_factor = 2.0;
  ExplicitSolver solver(Particles::from_body(body, 2500.0, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{2500.0, 20e9, 15e9}), body.size()), options);
  if (sphere_impact) {
    solver.set_sphere(test::box_impact_sphere());
  } else {
    set_initial_velocity(solver.particles(), [](const double* x) -> Vec3 {
      return {3000.0 * (x[1] - 0.02), -3000.0 * (x[0] - 0.025) + 400.0 * x[2], 20.0};
    });
  }
  solver.initialize();
  return solver;
}

void compare(bool sphere_impact, int steps) {
  ExplicitSolver fresh = make(0.0, sphere_impact), skin = make(0.1, sphere_impact);
  for (int s = 0; s < steps; ++s) {
    ASSERT_TRUE(fresh.step());
    ASSERT_TRUE(skin.step());
  }
  const Particles &a = fresh.particles(), &b = skin.particles();
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.x.size(); ++i) differ += (a.x[i] != b.x[i] || a.v[i] != b.v[i]) ? 1 : 0;
  for (std::size_t i = 0; i < a.stress_grad.size(); ++i) differ += a.stress_grad[i] != b.stress_grad[i] ? 1 : 0;
  std::printf("%s, %d steps: searches %zu (fresh) vs %zu + %zu reuses (skin 0.1), %zu values differ\n",
              sphere_impact ? "sphere impact" : "spinning body", steps, fresh.shapes().searches,
              skin.shapes().searches, skin.shapes().reuses, differ);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(fresh.ledger().balance_error(), skin.ledger().balance_error());
  EXPECT_LT(skin.shapes().searches, fresh.shapes().searches / 2);
  EXPECT_EQ(skin.shapes().searches + skin.shapes().reuses, fresh.shapes().searches);
}

TEST(MacroNeighbourSkin, BitwiseIdenticalOnASpinningBody) { compare(false, 150); }
TEST(MacroNeighbourSkin, BitwiseIdenticalThroughASphereImpact) { compare(true, 150); }

}  // namespace
}  // namespace uhpc::macro
