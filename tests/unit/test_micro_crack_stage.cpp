// The cracks of a cell and what is built on them (micro/analysis/crack_stage.hpp): a rebuild after
// growth keeps the committed history of the points there were and starts the new ones at the
// activation opening; save/restore brings back the geometry and the history exactly; every build has
// its own id; a rebuild without the field returns zero coefficients of the new model's size.
#include <gtest/gtest.h>

#include "cell_mesh.hpp"
#include "crack_growth.hpp"
#include "crack_stage.hpp"
#include "uniaxial_cell.hpp"

namespace uhpc::micro {
namespace {

constexpr double kSide = 1e-3, kW0 = 1e-8;

struct Fixture {
  CellGeometry cell;
  CellDiscretization mesh;
  RkGalerkinModel base;
  ElasticProblem unit;
  Fixture() {
    cell.side_m = kSide;
    cell.seeds.push_back({-1, {0.0, 0.5e-3}, {0.4e-3, 0.5e-3}});  // a planned crack from the left edge
    MeshOptions m;
    m.nominal_spacing_m = 100e-6;
    mesh = mesh_cell(cell, m);
    base = build_rk_galerkin_model(mesh, RkGalerkinOptions{});
    unit = uniaxial_problem(kSide, LoadAxis::Y, 1.0 / kSide, PlaneStrain{4.4e10, 0.2}, 100.0);
  }
  CrackStage stage() const {
    std::vector<std::array<double, 2>> points;
    for (const PointConstraint& c : unit.points) points.push_back(c.x_m);
    return CrackStage(base, mesh, unit, BoundaryPart::Top, 1, points, EnrichmentOptions{}, FieldTransfer::Project, kW0,
                      cracks_from_seeds(cell, mesh, GrowthOptions{}));
  }
  void grow(CrackStage& s) const { ASSERT_TRUE(advance_crack(s.cracks(), 0, {1.0, 0.0}, cell, mesh, GrowthOptions{})); }
};

TEST(microCrackStage, ARebuildAfterGrowthKeepsTheHistoryOfThePointsThereWere) {
  const Fixture f;
  CrackStage s = f.stage();
  f.grow(s);
  s.rebuild(Eigen::VectorXd(), false);
  const std::size_t per_segment = s.model().cohesive.size();
  ASSERT_GT(per_segment, 0u);
  EXPECT_FALSE(s.softening());
  EXPECT_EQ(s.open_segments(), 0u);
  std::vector<CohesiveHistory> h = s.flat_history();
  for (const CohesiveHistory& x : h) EXPECT_EQ(x.kappa, kW0);
  for (std::size_t p = 0; p < h.size(); ++p) h[p] = {kW0 * (2.0 + static_cast<double>(p)), 0.1 * p, 0.0};
  s.commit(h);
  EXPECT_TRUE(s.softening());
  EXPECT_EQ(s.open_segments(), 1u);
  f.grow(s);
  s.rebuild(Eigen::VectorXd(), false);
  const std::vector<CohesiveHistory> after = s.flat_history();
  ASSERT_EQ(after.size(), 2 * per_segment);
  for (std::size_t p = 0; p < after.size(); ++p) {
    const CohesivePoint& q = s.model().cohesive[p];
    if (q.segment == 0) {
      EXPECT_EQ(after[p].kappa, kW0 * (2.0 + q.gauss));  // the first segment's points, in Gauss order
      EXPECT_EQ(after[p].shear_dissipated, 0.1 * q.gauss);
    } else {
      EXPECT_EQ(after[p].kappa, kW0);
    }
  }
}

TEST(microCrackStage, SaveAndRestoreBringBackTheGeometryAndTheHistory) {
  const Fixture f;
  CrackStage s = f.stage();
  f.grow(s);
  s.rebuild(Eigen::VectorXd(), false);
  std::vector<CohesiveHistory> h = s.flat_history();
  h[0].kappa = 3.0 * kW0;
  s.commit(h);
  const CrackStage::Saved saved = s.save();
  const double length = s.active_length();
  f.grow(s);
  f.grow(s);
  s.rebuild(Eigen::VectorXd(), false);
  s.commit(std::vector<CohesiveHistory>(s.model().cohesive.size(), CohesiveHistory{5.0 * kW0, 0.0, 0.0}));
  EXPECT_GT(s.active_length(), length);
  s.restore(saved);
  s.rebuild(Eigen::VectorXd(), false);
  EXPECT_EQ(s.active_length(), length);
  EXPECT_EQ(s.cracks()[0].active, 1u);
  const std::vector<CohesiveHistory> back = s.flat_history();
  ASSERT_EQ(back.size(), h.size());
  for (std::size_t p = 0; p < h.size(); ++p) EXPECT_EQ(back[p].kappa, h[p].kappa);
}

TEST(microCrackStage, EveryBuildHasItsOwnIdAndAFreshStartHasNoField) {
  const Fixture f;
  CrackStage s = f.stage();
  EXPECT_FALSE(s.built());
  const Eigen::VectorXd d0 = s.rebuild(Eigen::VectorXd(), true);  // nothing to carry at the first build
  EXPECT_TRUE(s.built());
  EXPECT_EQ(s.id(), 1);
  EXPECT_EQ(d0.size(), static_cast<Eigen::Index>(s.model().dof_count()));
  EXPECT_EQ(d0.norm(), 0.0);
  EXPECT_EQ(s.system().dofs(), s.model().dof_count());
  f.grow(s);
  const Eigen::VectorXd d1 = s.rebuild(Eigen::VectorXd::Ones(d0.size()), false);
  EXPECT_EQ(s.id(), 2);
  EXPECT_GT(d1.size(), d0.size());  // the grown crack enriches more nodes
  EXPECT_EQ(d1.norm(), 0.0);
}

TEST(microCrackStage, ARebuildWithTheFieldKeepsAnUncrackedDisplacement) {
  // Before anything is active the model is the standard one: a uniform stretch carried across a
  // rebuild onto the first segment's enriched model stays the same stretch (no jump).
  const Fixture f;
  CrackStage s = f.stage();
  s.rebuild(Eigen::VectorXd(), false);
  const std::size_t n = s.model().standard_nodes;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.model().dof_count()));
  for (std::size_t i = 0; i < n; ++i) d[static_cast<Eigen::Index>(2 * i + 1)] = 1e-3 * f.mesh.nodes_m[i][1];
  f.grow(s);
  const Eigen::VectorXd carried = s.rebuild(d, true);
  ASSERT_GT(s.model().dof_count(), 2 * n);
  EXPECT_LE((carried.head(static_cast<Eigen::Index>(2 * n)) - d.head(static_cast<Eigen::Index>(2 * n))).norm(),
            1e-9 * d.norm());
  EXPECT_LE(carried.tail(static_cast<Eigen::Index>(s.model().dof_count() - 2 * n)).norm(), 1e-9 * d.norm());
}

}  // namespace
}  // namespace uhpc::micro
