#pragma once
// The coefficients of a rebuilt enriched model (crack growth) that keep the displacement field.
//
// Growth changes enriched functions under their coefficients: a moved tip ramp, a tip that stops on
// another crack (its ramp goes, the junction cut-off comes in, node sides H(x_J) flip). Carrying the
// coefficients over by (crack, node) then changes the field itself, and near fully open cracks, where
// the enriched coefficients have drifted along nearly free directions to hundreds of openings, the
// change is large: on a 5.0 mm cell one junction made 2.9x the largest work of spurious strain energy
// before any iteration (micro/README.md, growth).
//
// [choice] FieldTransfer::Project (default): the carried coefficients plus the L2 projection, onto the
// new space, of the field they miss, delta = u_old - u_carried (evaluated at the new model's domain
// points, the old functions recomputed there). The projection's unknowns are the generalized nodes
// whose supports meet a point where delta is not round-off (1e-10 of the largest displacement), so
// coefficients away from the change stay as they were, and a field the new space holds is kept
// exactly. FieldTransfer::Carry: the coefficients by (crack, node) only (new ones 0), the former rule.
#include <Eigen/Core>
#include <vector>

#include "crack_geometry.hpp"
#include "enrichment.hpp"
#include "rk_galerkin_model.hpp"

namespace uhpc::micro {

enum class FieldTransfer { Project, Carry };

struct TransferReport {
  std::size_t projected_gnodes = 0;  // unknowns of the projection (0: nothing changed, or Carry)
  double missed_m = 0.0;             // largest |delta| of the carried coefficients at a domain point
  double residual_m = 0.0;           // largest |delta| left after the projection
};

// d on `to` for the field of d_from on `from` (built on from_cracks); both on the same base model.
Eigen::VectorXd transfer_field(const RkGalerkinModel& base, const EnrichedModel& from,
                               const std::vector<Crack>& from_cracks, const Eigen::VectorXd& d_from,
                               const EnrichedModel& to, FieldTransfer method, TransferReport* report = nullptr);

}  // namespace uhpc::micro
