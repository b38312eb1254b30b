#include "crack_stage.hpp"

#include <utility>

namespace uhpc::micro {

CrackStage::CrackStage(const RkGalerkinModel& base, const CellDiscretization& mesh, const ElasticProblem& unit_problem,
                       BoundaryPart far, int axis, std::vector<std::array<double, 2>> constraint_points,
                       const EnrichmentOptions& enrichment, FieldTransfer transfer, double activation_opening,
                       std::vector<Crack> cracks)
    : base_(base),
      mesh_(mesh),
      unit_(unit_problem),
      far_(far),
      axis_(axis),
      constraint_points_(std::move(constraint_points)),
      enrichment_(enrichment),
      transfer_(transfer),
      activation_opening_(activation_opening),
      gauss_(enrichment.crack_points),
      cracks_(std::move(cracks)),
      history_(cracks_.size()) {}

Eigen::VectorXd CrackStage::rebuild(const Eigen::VectorXd& d, bool keep_field) {
  auto em = std::make_unique<EnrichedModel>(build_enriched_model(base_, mesh_, cracks_, constraint_points_, enrichment_));
  auto sys = std::make_unique<FractureSystem>(base_, *em, unit_, far_, axis_);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(em->dof_count()));
  if (em_ && keep_field) out = transfer_field(base_, *em_, built_on_, d, *em, transfer_);
  sys_ = std::move(sys);  // (the old system refers to the old model: replace it first)
  em_ = std::move(em);
  built_on_ = cracks_;
  ++id_;
  for (std::size_t c = 0; c < cracks_.size(); ++c)
    history_[c].resize(cracks_[c].active * static_cast<std::size_t>(gauss_), CohesiveHistory{activation_opening_, 0.0, 0.0});
  return out;
}

std::vector<CohesiveHistory> CrackStage::flat_history() const {
  std::vector<CohesiveHistory> h;
  h.reserve(em_->cohesive.size());
  for (const CohesivePoint& p : em_->cohesive) h.push_back(history_[p.crack][index(p.segment, p.gauss)]);
  return h;
}

void CrackStage::commit(const std::vector<CohesiveHistory>& trial) {
  for (std::size_t i = 0; i < trial.size(); ++i) {
    const CohesivePoint& p = em_->cohesive[i];
    history_[p.crack][index(p.segment, p.gauss)] = trial[i];
  }
}

bool CrackStage::softening() const {
  for (const auto& h : history_)
    for (const CohesiveHistory& x : h)
      if (opened(x)) return true;
  return false;
}

std::size_t CrackStage::open_segments() const {
  std::size_t n = 0;
  for (std::size_t c = 0; c < cracks_.size(); ++c)
    for (std::size_t g = 0; g < cracks_[c].active; ++g) {
      bool open = false;
      for (int q = 0; q < gauss_; ++q) open = open || opened(history_[c][g * static_cast<std::size_t>(gauss_) + q]);
      n += open ? 1 : 0;
    }
  return n;
}

double CrackStage::active_length() const {
  double l = 0.0;
  for (const Crack& c : cracks_) l += c.active_length();
  return l;
}

}  // namespace uhpc::micro
