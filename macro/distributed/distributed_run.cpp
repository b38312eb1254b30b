#include "distributed/distributed_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace uhpc::macro::distributed {

namespace {
// The ranks' minimum and sums for the solver's RankShare, on the run's communicator.
RankShare rank_share(MPI_Comm comm, std::vector<std::uint8_t> owned, std::vector<std::uint32_t> ids) {
  RankShare share;
  share.owned = std::move(owned);
  share.ids = std::move(ids);
  share.min = [comm](double value) {
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, comm);
    return value;
  };
  share.sum = [comm](double* values, int count) { MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_SUM, comm); };
  share.gather = [comm, counts = std::vector<int>(), displs = std::vector<int>()](const std::vector<double>& mine,
                                                                                std::vector<double>& all) mutable {
    int size = 1;
    MPI_Comm_size(comm, &size);
    counts.resize(static_cast<std::size_t>(size));
    displs.resize(static_cast<std::size_t>(size));
    int count = static_cast<int>(mine.size());
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    int total = 0;
    for (int r = 0; r < size; ++r) displs[static_cast<std::size_t>(r)] = total, total += counts[static_cast<std::size_t>(r)];
    all.resize(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, comm);
  };
  return share;
}

double all_min(double value, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, comm);
  return value;
}
}  // namespace

DistributedRun::DistributedRun(MPI_Comm comm, std::size_t total, SolverFactory factory, PartitionOptions options)
    : comm_(comm), factory_(std::move(factory)), partition_(comm, options) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_.get(), &rank);
  MPI_Comm_size(comm_.get(), &size);
  const std::size_t ranks = static_cast<std::size_t>(size), r = static_cast<std::size_t>(rank);
  if (total < ranks)
    throw std::invalid_argument("DistributedRun: " + std::to_string(total) + " particles cannot be shared by " +
                                std::to_string(size) + " ranks");
  // Every rank starts from a contiguous block of the body; the balance sends each particle to its region.
  std::vector<std::uint32_t> block;
  for (std::size_t i = total * r / ranks; i < total * (r + 1) / ranks; ++i) block.push_back(static_cast<std::uint32_t>(i));
  const ExplicitSolver start = factory_(block);
  const Particles& p = start.particles();
  if (p.n != block.size()) throw std::logic_error("DistributedRun: the factory gave a solver of another size");
  const int width = static_cast<int>(start.particle_record_width()) + 1;  // + the support radius
  owned_ = ParticleSet(width);
  std::vector<double> record(static_cast<std::size_t>(width));
  double min_support = std::numeric_limits<double>::infinity(), max_support = 0.0;
  for (std::size_t k = 0; k < block.size(); ++k) {
    start.write_particle(k, record.data());
    record.back() = p.support[k];
    owned_.push_back(block[k], record.data());
    min_support = std::min(min_support, p.support[k]);
    max_support = std::max(max_support, p.support[k]);
  }
  // The serial search's skin (ShapeCache: s = skin times the smallest support radius of the body).
  skin_m_ = start.options().neighbour_skin * all_min(min_support, comm_.get());
  cell_m_ = -all_min(-max_support, comm_.get());
  if (!(skin_m_ > 0.0))
    throw std::invalid_argument("DistributedRun: the halo needs a Verlet skin (solver.neighbour_skin > 0)");
  partition_.balance(owned_);
  owned_.sort_by_id();
  build_local(false);
}

void DistributedRun::build_local(bool from_records) {
  int empty = owned_.size() == 0 ? 1 : 0;  // decided together: a rank alone would leave the others waiting
  MPI_Allreduce(MPI_IN_PLACE, &empty, 1, MPI_INT, MPI_MAX, comm_.get());
  if (empty) throw std::runtime_error("DistributedRun: a rank was left without particles; use fewer ranks");
  const int width = owned_.width;
  std::vector<double> node_reach(owned_.size()), row_reach(owned_.size());
  for (std::size_t k = 0; k < owned_.size(); ++k) {
    const double a = owned_.at(k)[width - 1];
    node_reach[k] = a + 2.0 * skin_m_;  // Halo: owner computes
    row_reach[k] = a;
  }
  halo_ = std::make_unique<Halo>(partition_, owned_, node_reach, row_reach, cell_m_);
  sent_ = halo_->sent_rows();
  const ParticleSet local = halo_->local(owned_, &owned_at_);
  local_ids_ = local.id;
  owned_mask_.assign(local.size(), 0);
  for (const std::size_t at : owned_at_) owned_mask_[at] = 1;
  ghost_at_.clear();
  for (std::size_t i = 0; i < local.size(); ++i)
    if (!owned_mask_[i]) ghost_at_.push_back(i);

  auto solver = std::make_unique<ExplicitSolver>(factory_(local_ids_));
  if (solver->particles().n != local_ids_.size()) throw std::logic_error("DistributedRun: the factory gave a solver of another size");
  solver->set_rank_share(rank_share(comm_.get(), owned_mask_, local_ids_));
  if (from_records) {  // the particles from their records, the run's state from the solver it replaces
    for (std::size_t i = 0; i < local.size(); ++i) solver->read_particle(i, local.at(i));
    solver->continue_from(*solver_);
  } else {
    solver->initialize();
  }
  solver_ = std::move(solver);
  // A fresh solver's ghosts hold their own forces of the initial state (their rows are not all here).
  if (!from_records) refresh_ghosts();
  x_at_halo_ = solver_->particles().x;
  ++halo_builds_;
}

void DistributedRun::pack_owned() {
  for (std::size_t k = 0; k < owned_.size(); ++k) solver_->write_particle(owned_at_[k], owned_.at(k));
}

const ParticleSet& DistributedRun::owned_records() {
  pack_owned();
  return owned_;
}

// The halo holds every K within a_K + 2 s + a_J of an owned J. A row that touches J when the rows are next
// built has its point L within a_J of J and its nodes K within a_K of L, so |x_K - x_J| < a_K + a_J then
// (the start-of-step rows of EndpointAverage are the last step's, built at positions already checked);
// while no particle will have moved more than s since the halo, |x_K - x_J| was below a_K + a_J + 2 s
// when it was made. So the largest motion since the halo plus the next step's travel, bounded by
// dt |v| + dt^2 |a| / 2 (velocity Verlet), must stay within s; the ranks' largest.
double DistributedRun::reach_after_next_step() const {
  const Particles& p = solver_->particles();
  const double dt = solver_->dt();
  double most = 0.0;
  for (const std::size_t i : owned_at_) {
    double moved2 = 0.0, v2 = 0.0, a2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double m = p.x[3 * i + d] - x_at_halo_[3 * i + d];
      moved2 += m * m;
      v2 += p.v[3 * i + d] * p.v[3 * i + d];
      a2 += p.a[3 * i + d] * p.a[3 * i + d];
    }
    const double travel = dt * std::sqrt(v2) + 0.5 * dt * dt * std::sqrt(a2);
    most = std::max(most, std::sqrt(moved2) + travel);
  }
  if (!std::isfinite(most)) most = std::numeric_limits<double>::infinity();
  return -all_min(-most, comm_.get());
}

void DistributedRun::refresh_ghosts() {
  for (const std::uint32_t k : sent_) solver_->write_particle(owned_at_[k], owned_.at(k));
  halo_->refresh(owned_);
  const ParticleSet& ghosts = halo_->ghosts();
  for (std::size_t g = 0; g < ghosts.size(); ++g) solver_->read_particle(ghost_at_[g], ghosts.at(g));
}

bool DistributedRun::step() {
  if (!solver_->step()) return false;
  refresh_ghosts();
  if (reach_after_next_step() > skin_m_) {
    const auto t0 = std::chrono::steady_clock::now();
    pack_owned();
    partition_.rebalance_if_needed(owned_);
    owned_.sort_by_id();
    build_local(true);
    halo_build_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double travel = reach_after_next_step();  // the travel alone, just after the build
    if (travel > skin_m_)
      throw std::runtime_error("DistributedRun: a particle may travel " + std::to_string(travel) +
                               " m in the next step, more than the halo's skin (" + std::to_string(skin_m_) + " m)");
  }
  return true;
}

}  // namespace uhpc::macro::distributed
