// The field transfer across a rebuild of the enriched model (micro/analysis/field_transfer.hpp):
//  - nothing changes where the functions do not (same cracks: the coefficients come back bit for bit);
//  - a field the new space holds is kept exactly: the same two cracks listed in the other order make
//    the (crack, node) carry hand each crack's coefficients to the other, and the projection must
//    restore the field to round-off;
//  - a tip advance changes coefficients only near the change, and the projection's L2 error is
//    below the carry's.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "cell_mesh.hpp"
#include "crack_geometry.hpp"
#include "enrichment.hpp"
#include "field_transfer.hpp"
#include "rk_galerkin_model.hpp"

namespace uhpc::micro {
namespace {

constexpr double kSide = 1e-3;

struct Fixture {
  CellGeometry cell;
  CellDiscretization mesh;
  RkGalerkinModel base;
  Fixture() {
    cell.side_m = kSide;
    MeshOptions o;
    o.nominal_spacing_m = 100e-6;
    mesh = mesh_cell(cell, o);
    base = build_rk_galerkin_model(mesh, RkGalerkinOptions{});
  }
  EnrichedModel model(const std::vector<Crack>& cracks) const {
    return build_enriched_model(base, mesh, cracks, {{0.0, 0.5 * kSide}}, EnrichmentOptions{});
  }
};

// A straight crack from the edge at (x, y0) along +y (or -y), planned over `planned` segments of 0.1 mm.
Crack edge_crack(double x, double y0, double dir, int planned, std::size_t active) {
  Crack c;
  c.root = CrackEnd::Edge;
  for (int k = 0; k <= planned; ++k) c.points.push_back({x, y0 + dir * 0.1e-3 * k});
  c.active = active;
  return c;
}

// Smooth but arbitrary coefficients: standard ones of a loaded cell's size, enriched ones like openings.
Eigen::VectorXd coefficients(const EnrichedModel& em) {
  Eigen::VectorXd d(static_cast<Eigen::Index>(em.dof_count()));
  for (Eigen::Index i = 0; i < d.size(); ++i)
    d[i] = i < static_cast<Eigen::Index>(2 * em.standard_nodes) ? 1e-7 * std::sin(0.37 * static_cast<double>(i))
                                                                 : 1e-6 * std::cos(1.0 + 0.71 * static_cast<double>(i));
  return d;
}

// Largest |u_a - u_b| and |u_a| over the domain points of `to`, u_a of d_from on `from`, u_b of d on `to`.
std::pair<double, double> field_difference(const Fixture& f, const EnrichedModel& from, const std::vector<Crack>& from_cracks,
                                           const Eigen::VectorXd& d_from, const EnrichedModel& to,
                                           const std::vector<Crack>& to_cracks, const Eigen::VectorXd& d) {
  const std::vector<double> a = enriched_displacement(f.base, from, from_cracks, to.domain, to.x, d_from);
  const std::vector<double> b = enriched_displacement(f.base, to, to_cracks, to.domain, to.x, d);
  double diff = 0.0, size = 0.0;
  for (std::size_t p = 0; 2 * p < a.size(); ++p) {
    diff = std::max(diff, std::hypot(a[2 * p] - b[2 * p], a[2 * p + 1] - b[2 * p + 1]));
    size = std::max(size, std::hypot(a[2 * p], a[2 * p + 1]));
  }
  return {diff, size};
}

// The L2 norm of u_a - u_b over the domain of `to` (as above).
double l2_difference(const Fixture& f, const EnrichedModel& from, const std::vector<Crack>& from_cracks,
                     const Eigen::VectorXd& d_from, const EnrichedModel& to, const std::vector<Crack>& to_cracks,
                     const Eigen::VectorXd& d) {
  const std::vector<double> a = enriched_displacement(f.base, from, from_cracks, to.domain, to.x, d_from);
  const std::vector<double> b = enriched_displacement(f.base, to, to_cracks, to.domain, to.x, d);
  double sum = 0.0;
  for (std::size_t p = 0; 2 * p < a.size(); ++p)
    sum += to.weight[p] * (std::pow(a[2 * p] - b[2 * p], 2) + std::pow(a[2 * p + 1] - b[2 * p + 1], 2));
  return std::sqrt(sum);
}

TEST(microFieldTransfer, UnchangedCracksKeepEveryCoefficient) {
  const Fixture f;
  const std::vector<Crack> cracks{edge_crack(0.3e-3 + 3.1e-6, 0.0, 1.0, 6, 4)};
  const EnrichedModel a = f.model(cracks), b = f.model(cracks);
  const Eigen::VectorXd d = coefficients(a);
  TransferReport rep;
  const Eigen::VectorXd t = transfer_field(f.base, a, cracks, d, b, FieldTransfer::Project, &rep);
  EXPECT_EQ(rep.projected_gnodes, 0u);
  ASSERT_EQ(t.size(), d.size());
  EXPECT_EQ((t - d).cwiseAbs().maxCoeff(), 0.0);
}

TEST(microFieldTransfer, AFieldTheNewSpaceHoldsIsKeptExactly) {
  const Fixture f;
  const Crack A = edge_crack(0.3e-3 + 3.1e-6, 0.0, 1.0, 6, 4);    // open tip at y = 0.4 mm
  const Crack B = edge_crack(0.7e-3 - 2.3e-6, kSide, -1.0, 6, 3);  // from the top, open tip at 0.7 mm
  const std::vector<Crack> ab{A, B}, ba{B, A};
  const EnrichedModel from = f.model(ab), to = f.model(ba);
  ASSERT_EQ(from.enriched_node.size(), to.enriched_node.size());
  const Eigen::VectorXd d = coefficients(from);

  const Eigen::VectorXd carried = transfer_field(f.base, from, ab, d, to, FieldTransfer::Carry);
  const auto [carry_error, size] = field_difference(f, from, ab, d, to, ba, carried);
  TransferReport rep;
  const Eigen::VectorXd projected = transfer_field(f.base, from, ab, d, to, FieldTransfer::Project, &rep);
  const auto [error, size2] = field_difference(f, from, ab, d, to, ba, projected);
  std::printf("largest |u| %.3e m; carried: largest error %.3e m; projected (%zu unknowns): %.3e m\n", size,
              carry_error, rep.projected_gnodes, error);
  ASSERT_GT(size, 0.0);
  EXPECT_GT(carry_error, 0.1 * size);  // the carry hands A's coefficients to B: a different field
  EXPECT_LT(error, 1e-8 * size);
  EXPECT_NEAR(rep.missed_m, carry_error, 1e-12 * size);
}

TEST(microFieldTransfer, ATipAdvanceChangesCoefficientsOnlyNearTheChange) {
  const Fixture f;
  const double x = 0.3e-3 + 3.1e-6;
  const std::vector<Crack> before{edge_crack(x, 0.0, 1.0, 6, 4)}, after{edge_crack(x, 0.0, 1.0, 6, 5)};
  const EnrichedModel from = f.model(before), to = f.model(after);
  const Eigen::VectorXd d = coefficients(from);
  TransferReport rep;
  const Eigen::VectorXd projected = transfer_field(f.base, from, before, d, to, FieldTransfer::Project, &rep);
  const Eigen::VectorXd carried = transfer_field(f.base, from, before, d, to, FieldTransfer::Carry);
  ASSERT_GT(rep.projected_gnodes, 0u);

  // The functions change where the old and new ramps differ: along the last two segments (y 0.3-0.5 mm).
  // Beyond three support radii of that every coefficient stays.
  double a_max = 0.0;
  for (const double a : f.base.support_radius) a_max = std::max(a_max, a);
  std::size_t far = 0;
  for (std::size_t i = 0; i < f.base.node_count(); ++i) {
    const double* xi = &f.base.nodes[2 * i];
    const double y = std::clamp(xi[1], 0.3e-3, 0.5e-3);
    if (std::hypot(xi[0] - x, xi[1] - y) <= 3.0 * a_max) continue;
    ++far;
    EXPECT_EQ(projected[static_cast<Eigen::Index>(2 * i)], d[static_cast<Eigen::Index>(2 * i)]) << "node " << i;
    EXPECT_EQ(projected[static_cast<Eigen::Index>(2 * i + 1)], d[static_cast<Eigen::Index>(2 * i + 1)]) << "node " << i;
  }
  EXPECT_GT(far, 10u);
  const double e_carry = l2_difference(f, from, before, d, to, after, carried);
  const double e_project = l2_difference(f, from, before, d, to, after, projected);
  std::printf("L2 error of the field after a tip advance: carried %.3e, projected %.3e (m^2); %zu unknowns\n", e_carry,
              e_project, rep.projected_gnodes);
  EXPECT_LT(e_project, e_carry);
}

}  // namespace
}  // namespace uhpc::micro
