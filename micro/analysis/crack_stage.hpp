#pragma once
// The cracks of one cell and what is built on them (docs/physics.md section 2): the crack polylines,
// the committed history of every cohesive point, kept per crack and segment so that it survives a
// rebuild, and the enriched model and fracture system of the current geometry, rebuilt whenever the
// cracks change (growth, or a step undone). The crack analysis (cell_analysis.cpp) steers it; this
// class knows nothing of load steps.
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "cohesive_assembly.hpp"
#include "crack_geometry.hpp"
#include "enrichment.hpp"
#include "field_transfer.hpp"

namespace uhpc::micro {

class CrackStage {
 public:
  // `base`, `mesh` and `unit_problem` must outlive the stage; `cracks` start with what is active.
  // New cohesive points start at `activation_opening` (the cohesive law's w0), with no damage.
  CrackStage(const RkGalerkinModel& base, const CellDiscretization& mesh, const ElasticProblem& unit_problem,
             BoundaryPart far, int axis, std::vector<std::array<double, 2>> constraint_points,
             const EnrichmentOptions& enrichment, FieldTransfer transfer, double activation_opening,
             std::vector<Crack> cracks);

  // Builds the enriched model and system of the current cracks. Returns the coefficients of the new
  // model: with `keep_field`, those that keep the displacement field of `d` on the previous model
  // (field_transfer.hpp); else (or at the first build) zero.
  Eigen::VectorXd rebuild(const Eigen::VectorXd& d, bool keep_field);

  std::vector<Crack>& cracks() { return cracks_; }
  const std::vector<Crack>& cracks() const { return cracks_; }
  const EnrichedModel& model() const { return *em_; }
  FractureSystem& system() { return *sys_; }
  const FractureSystem& system() const { return *sys_; }
  bool built() const { return em_ != nullptr; }
  long id() const { return id_; }  // counts the builds: the sparsity pattern's key

  // The committed history of the model's cohesive points (EnrichedModel::cohesive order), and back.
  std::vector<CohesiveHistory> flat_history() const;
  void commit(const std::vector<CohesiveHistory>& trial);
  // Has any cohesive point opened beyond its activation opening?
  bool softening() const;
  // Active segments with a point opened beyond its activation opening.
  std::size_t open_segments() const;
  double active_length() const;

  // The geometry and the history (not the model: rebuild() after restore() when the geometry changed).
  struct Saved {
    std::vector<Crack> cracks;
    std::vector<std::vector<CohesiveHistory>> history;
  };
  Saved save() const { return {cracks_, history_}; }
  void restore(const Saved& s) {
    cracks_ = s.cracks;
    history_ = s.history;
  }

 private:
  bool opened(const CohesiveHistory& h) const { return h.kappa > activation_opening_ * (1.0 + 1e-9); }
  std::size_t index(std::int32_t segment, std::int32_t gauss) const {
    return static_cast<std::size_t>(segment) * static_cast<std::size_t>(gauss_) + static_cast<std::size_t>(gauss);
  }

  const RkGalerkinModel& base_;
  const CellDiscretization& mesh_;
  const ElasticProblem& unit_;
  BoundaryPart far_;
  int axis_;
  std::vector<std::array<double, 2>> constraint_points_;
  EnrichmentOptions enrichment_;
  FieldTransfer transfer_;
  double activation_opening_;
  int gauss_;  // cohesive points per segment
  std::vector<Crack> cracks_;
  std::vector<std::vector<CohesiveHistory>> history_;  // per crack: segment x Gauss point
  std::vector<Crack> built_on_;                        // the cracks em_ was built on
  std::unique_ptr<EnrichedModel> em_;
  std::unique_ptr<FractureSystem> sys_;  // refers to em_
  long id_ = 0;
};

}  // namespace uhpc::micro
