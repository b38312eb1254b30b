#include "distributed/distributed_run.hpp"

#include "distributed/huge_pages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
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

int as_count(std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("DistributedRun: more values for one rank than an MPI count holds");
  return static_cast<int>(n);
}

// Where each rank's part starts, with room for the last one's (MPI's counts and displacements are ints).
std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> at(counts.size(), 0);
  std::size_t sum = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    at[r] = as_count(sum);
    sum += static_cast<std::size_t>(counts[r]);
  }
  as_count(sum);
  return at;
}

// Lazy rows travel with their particles: the rows of the particles `ids` (ascending) of a new rank
// solver, each from the solver `old` of the rank that owned it (old_ids, old_owned: that solver's
// particles). The records go into `blob`; one pointer a particle, in the order of ids. A rank's own rows
// are written straight into it (or, with keep_own, left where they are: a null pointer), the others'
// come through MPI_Alltoallv. Collective.
std::vector<const double*> rows_from_owners(MPI_Comm comm, std::size_t total, const ExplicitSolver& old,
                                            const std::vector<std::uint32_t>& old_ids,
                                            const std::vector<std::uint8_t>& old_owned,
                                            const std::vector<std::uint32_t>& ids, std::vector<double>& blob,
                                            bool keep_own = false) {
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const std::size_t ranks = static_cast<std::size_t>(size), me = static_cast<std::size_t>(rank);
  // Who owned each particle.
  std::vector<std::uint32_t> mine;
  for (std::size_t i = 0; i < old_ids.size(); ++i)
    if (old_owned[i]) mine.push_back(old_ids[i]);
  std::vector<int> counts(ranks);
  int count = as_count(mine.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<std::uint32_t> every(total);
  MPI_Allgatherv(mine.data(), count, MPI_UINT32_T, every.data(), counts.data(), displacements(counts).data(),
                 MPI_UINT32_T, comm);
  std::vector<int> owner(total, -1);
  for (std::size_t r = 0, k = 0; r < ranks; ++r)
    for (int c = 0; c < counts[r]; ++c) owner[every[k++]] = static_cast<int>(r);
  const auto old_index = [&](std::uint32_t id) {
    return static_cast<std::size_t>(std::lower_bound(old_ids.begin(), old_ids.end(), id) - old_ids.begin());
  };
  // Each rank asks the other owners for its particles' rows, in ascending ids per owner.
  std::vector<int> ask(ranks, 0), asked(ranks);
  for (const std::uint32_t id : ids) ++ask[static_cast<std::size_t>(owner[id])];
  ask[me] = 0;
  MPI_Alltoall(ask.data(), 1, MPI_INT, asked.data(), 1, MPI_INT, comm);
  const std::vector<int> ask_at = displacements(ask), asked_at = displacements(asked);
  std::vector<std::uint32_t> questions(static_cast<std::size_t>(ask_at.back() + ask.back()));
  std::vector<std::uint32_t> requests(static_cast<std::size_t>(asked_at.back() + asked.back()));
  std::vector<int> filled = ask_at;
  for (const std::uint32_t id : ids)
    if (static_cast<std::size_t>(owner[id]) != me)
      questions[static_cast<std::size_t>(filled[static_cast<std::size_t>(owner[id])]++)] = id;
  MPI_Alltoallv(questions.data(), ask.data(), ask_at.data(), MPI_UINT32_T, requests.data(), asked.data(),
                asked_at.data(), MPI_UINT32_T, comm);
  // The owners answer with the records, rank by rank, each buffer sized once.
  std::vector<int> answer_size(ranks, 0), answered(ranks);
  std::size_t answer_total = 0, own_total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    std::size_t doubles = 0;
    for (int k = 0; k < asked[r]; ++k)
      doubles += old.row_record_length(old_index(requests[static_cast<std::size_t>(asked_at[r] + k)]));
    answer_size[r] = as_count(doubles);
    answer_total += doubles;
  }
  if (!keep_own)
    for (const std::uint32_t id : ids)
      if (static_cast<std::size_t>(owner[id]) == me) own_total += old.row_record_length(old_index(id));
  std::vector<double> answers(answer_total);
  double* out = answers.data();
  for (const std::uint32_t id : requests) out = old.write_row(old_index(id), out);
  MPI_Alltoall(answer_size.data(), 1, MPI_INT, answered.data(), 1, MPI_INT, comm);
  const std::vector<int> answered_at = displacements(answered);
  const std::size_t received = static_cast<std::size_t>(answered_at.back() + answered.back());
  blob.resize(received + own_total);
  MPI_Alltoallv(answers.data(), answer_size.data(), displacements(answer_size).data(), MPI_DOUBLE, blob.data(),
                answered.data(), answered_at.data(), MPI_DOUBLE, comm);
  answers = std::vector<double>();
  // The own rows after the received ones; each owner's records in the order they were asked for.
  std::vector<std::size_t> next(ranks);
  for (std::size_t r = 0; r < ranks; ++r) next[r] = static_cast<std::size_t>(answered_at[r]);
  double* own = blob.data() + received;
  std::vector<const double*> records(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::size_t from = static_cast<std::size_t>(owner[ids[i]]);
    if (from == me) {
      records[i] = keep_own ? nullptr : own;
      if (!keep_own) own = old.write_row(old_index(ids[i]), own);
    } else {
      records[i] = blob.data() + next[from];
      next[from] += static_cast<std::size_t>(blob[next[from]]);  // the record's length
    }
  }
  return records;
}
}  // namespace

DistributedRun::DistributedRun(MPI_Comm comm, std::size_t total, SolverFactory factory, PartitionOptions options)
    : comm_(comm), factory_(std::move(factory)), partition_(comm, options), total_(total) {
  advise_huge_pages_for_large_blocks();  // every halo build makes the rank's solver afresh (huge_pages.hpp)
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
  // A kept lazy row's nodes and its point have moved relative to each other by up to the tolerance
  // times the point's support radius since it was built (ShapeCache::row_due), and the point relative
  // to the owned particle it touches likewise: the halo reaches that much further.
  kept_row_reach_m_ = 2.0 * start.options().shape_reuse_tolerance * cell_m_;
  if (!(skin_m_ > 0.0))
    throw std::invalid_argument("DistributedRun: the halo needs a Verlet skin (solver.neighbour_skin > 0)");
  local_of_id_.assign(total, -1);
  partition_.balance(owned_);
  owned_.sort_by_id();
  build_local(false);
}

void DistributedRun::build_local(bool from_records) {
  int empty = owned_.size() == 0 ? 1 : 0;  // decided together: a rank alone would leave the others waiting
  MPI_Allreduce(MPI_IN_PLACE, &empty, 1, MPI_INT, MPI_MAX, comm_.get());
  if (empty) throw std::invalid_argument("DistributedRun: a rank was left without particles; use fewer ranks");
  const int width = owned_.width;
  std::vector<double> node_reach(owned_.size()), row_reach(owned_.size());
  for (std::size_t k = 0; k < owned_.size(); ++k) {
    const double a = owned_.at(k)[width - 1];
    node_reach[k] = a + 2.0 * skin_m_ + kept_row_reach_m_;  // Halo: owner computes
    row_reach[k] = a;
  }
  const std::vector<std::uint32_t> old_ids = std::move(local_ids_);
  const std::vector<std::uint8_t> old_owned = std::move(owned_mask_);
  halo_ = std::make_unique<Halo>(partition_, owned_, node_reach, row_reach, cell_m_);
  sent_ = halo_->sent_rows();
  const ParticleSet local = halo_->local(owned_, &owned_at_);
  local_ids_ = local.id;
  for (const std::uint32_t id : old_ids) local_of_id_[id] = -1;
  for (std::size_t i = 0; i < local_ids_.size(); ++i) local_of_id_[local_ids_[i]] = static_cast<std::int32_t>(i);
  owned_mask_.assign(local.size(), 0);
  for (const std::size_t at : owned_at_) owned_mask_[at] = 1;
  ghost_at_.clear();
  for (std::size_t i = 0; i < local.size(); ++i)
    if (!owned_mask_[i]) ghost_at_.push_back(i);

  // What the new solver takes from the one it replaces: the run's state and (lazy rows) the rows as their
  // owners kept them (none after a drop: every rank builds them afresh then). The old solver is freed
  // before the new one is made, so that a rank never holds two.
  std::optional<ExplicitSolver::RunState> run;
  std::vector<double> blob;
  std::vector<const double*> rows;
  if (from_records) {
    run = solver_->run_state();
    if (solver_->lazy_rows() && solver_->shapes().has_rows(solver_->particles().n))
      rows = rows_from_owners(comm_.get(), total_, *solver_, old_ids, old_owned, local_ids_, blob);
  }
  if (solver_) {
    rows_built_ += solver_->shapes().rows_built;
    rows_kept_ += solver_->shapes().rows_kept;
    if (solver_->shapes().has_rows(solver_->particles().n)) {  // (else those of the solver before it)
      fragments_at_build_.clear();
      for (std::size_t i = 0; i < old_owned.size(); ++i)
        if (old_owned[i] && solver_->shapes().fragment(i)) fragments_at_build_.push_back(old_ids[i]);
    }
    solver_.reset();
  }
  auto solver = std::make_unique<ExplicitSolver>(factory_(local_ids_));
  if (solver->particles().n != local_ids_.size()) throw std::logic_error("DistributedRun: the factory gave a solver of another size");
  solver->set_rank_share(rank_share(comm_.get(), owned_mask_, local_ids_));
  if (from_records) {  // the particles from their records
    for (std::size_t i = 0; i < local.size(); ++i) solver->read_particle(i, local.at(i));
    solver->continue_from(*run);
    if (!rows.empty()) solver->install_rows(rows, [this](std::uint32_t id) { return local_index(id); });
  } else {
    solver->initialize();
  }
  solver_ = std::move(solver);
  // A fresh solver's ghosts hold their own forces of the initial state (their rows are not all here).
  if (!from_records) refresh_ghosts();
  // Its lazy rows were laid out from what this rank holds: a ghost's slot may be short of its owner's.
  if (!from_records && solver_->lazy_rows()) rows_from_their_owners();
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

void DistributedRun::resume(const SolverCheckpoint& checkpoint) {
  for (const auto& [name, values] : checkpoint.particle_fields)
    if (name == "x" && values.size() != 3 * total_)
      throw std::invalid_argument("the checkpoint holds " + std::to_string(values.size() / 3) + " particles, the run " +
                                  std::to_string(total_));
  int failed = 0;
  std::string why;
  try {
    solver_->resume_part(checkpoint);
  } catch (const std::invalid_argument& e) {
    failed = 1;
    why = e.what();
  }
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, comm_.get());
  if (failed) throw std::invalid_argument(why.empty() ? "DistributedRun::resume: another rank refused the checkpoint" : why);
  pack_owned();
  partition_.rebalance_if_needed(owned_);
  owned_.sort_by_id();
  build_local(true);
}

std::int32_t DistributedRun::local_index(std::uint32_t id) const {
  return id < local_of_id_.size() ? local_of_id_[id] : -1;
}

std::vector<std::uint32_t> DistributedRun::owned_fragments() const {
  const ShapeCache& shapes = solver_->shapes();
  if (!shapes.has_rows(solver_->particles().n)) return fragments_at_build_;  // none built since the build
  std::vector<std::uint32_t> ids;
  for (const std::size_t i : owned_at_)
    if (shapes.fragment(i)) ids.push_back(local_ids_[i]);
  return ids;
}

// Every row of the rank as its owner holds it: the owned rows stay where they are (kept, not copied
// through records), a ghost's takes its owner's slot (ShapeCache: a ghost's row laid out from a partial
// neighbourhood may have a short slot, and one that came to touch an owned particle before the next
// halo build would then keep stale values where its owner rebuilds). Collective.
void DistributedRun::rows_from_their_owners() {
  std::vector<double> blob;
  const std::vector<const double*> rows =
      rows_from_owners(comm_.get(), total_, *solver_, local_ids_, owned_mask_, local_ids_, blob, true);
  solver_->install_rows(rows, [this](std::uint32_t id) { return local_index(id); });
}

bool DistributedRun::step() {
  const std::size_t layouts = solver_->shapes().layouts;
  if (!solver_->step()) return false;
  refresh_ghosts();
  const bool new_layout = solver_->lazy_rows() && solver_->shapes().layouts != layouts;  // on every rank alike
  if (reach_after_next_step() <= skin_m_) {
    if (new_layout) {
      const auto t0 = std::chrono::steady_clock::now();
      rows_from_their_owners();
      row_exchange_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ++row_exchanges_;
    }
  } else {
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
