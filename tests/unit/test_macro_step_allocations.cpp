// The step loop of the macro solver allocates nothing once the neighbour counts have settled: every
// buffer (neighbour lists, search workspace, shape tables, per-thread force buffers) keeps its memory.
// Counted through the global operator new of this test program.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include "bodies/generators.hpp"
#include "box_impact_sphere.hpp"
#include "solver/explicit_solver.hpp"

using uhpc::test::g_allocations;

namespace uhpc::macro {
namespace {

SolverOptions with_strain(StrainConfiguration strain) {
  SolverOptions o;
  o.strain_configuration = strain;
  return o;
}

void no_allocation_inside_the_step_loop(StrainConfiguration strain, double shape_reuse = 0.0) {
  const ParticleBody body = box_body(0.05, 0.04, 0.03, 0.005);
  SolverOptions options = with_strain(strain);
  options.shape_reuse_tolerance = shape_reuse;
  ExplicitSolver solver(Particles::from_body(body, 2500.0, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{2500.0, 20e9, 15e9}), body.size()), options);
  set_initial_velocity(solver.particles(), [](const double* x) -> Vec3 { return {50.0 * x[1], -30.0 * x[2], 5.0}; });
  Wall wall;
  wall.point = {0.0, 0.0, -0.0001};
  wall.normal = {0, 0, 1};
  solver.add_wall(wall);
  solver.initialize();
  for (int s = 0; s < 5; ++s) ASSERT_TRUE(solver.step());  // capacities settle
  const long before = g_allocations.load();
  for (int s = 0; s < 50; ++s) ASSERT_TRUE(solver.step());
  EXPECT_EQ(g_allocations.load() - before, 0);
}

TEST(MacroStepAllocations, NoAllocationInsideTheStepLoop) {
  no_allocation_inside_the_step_loop(SolverOptions{}.strain_configuration);
}
TEST(MacroStepAllocations, NoAllocationInsideTheStepLoopWithLazyRows) {
  no_allocation_inside_the_step_loop(SolverOptions{}.strain_configuration, 3e-4);
}
TEST(MacroStepAllocations, NoAllocationInsideTheStepLoopWithMidpointStrain) {
  no_allocation_inside_the_step_loop(StrainConfiguration::Midpoint);
}

// The same with the rigid sphere pressing into the box during the counted steps (contact forces, the
// contact ledger and the saved state of the step-collapse guard reuse their memory too).
void no_allocation_with_the_sphere_in_contact(StrainConfiguration strain, double shape_reuse = 0.0) {
  const ParticleBody body = box_body(0.05, 0.04, 0.03, 0.005);
  SolverOptions options = with_strain(strain);
  options.shape_reuse_tolerance = shape_reuse;
  options.support_factor = 2.5;  // NSNI at 2.0 is unstable under a point contact (macro/README.md)
  ExplicitSolver solver(Particles::from_body(body, 2500.0, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{2500.0, 20e9, 15e9}), body.size()), options);
  solver.set_sphere(test::box_impact_sphere(50.0));
  solver.initialize();
  for (int s = 0; s < 5; ++s) ASSERT_TRUE(solver.step());
  int in_contact = 0;
  const long before = g_allocations.load();
  for (int s = 0; s < 50; ++s) {
    ASSERT_TRUE(solver.step()) << to_string(solver.failure().kind);
    if (solver.contact().particles_in_contact > 0) ++in_contact;
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(in_contact, 20);
}

TEST(MacroStepAllocations, NoAllocationWithTheSphereInContact) {
  no_allocation_with_the_sphere_in_contact(SolverOptions{}.strain_configuration);
}
TEST(MacroStepAllocations, NoAllocationWithTheSphereInContactWithLazyRows) {
  no_allocation_with_the_sphere_in_contact(SolverOptions{}.strain_configuration, 3e-4);
}
TEST(MacroStepAllocations, NoAllocationWithTheSphereInContactWithMidpointStrain) {
  no_allocation_with_the_sphere_in_contact(StrainConfiguration::Midpoint);
}

}  // namespace
}  // namespace uhpc::macro
