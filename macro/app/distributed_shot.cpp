#include "distributed_shot.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <mpi.h>

#include "case_setup.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/gather.hpp"

namespace uhpc::macro {

namespace {

using distributed::DistributedRun;

double all_min(double value) {
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return value;
}

class DistributedShot final : public ShotStepper {
 public:
  DistributedShot(const CaseSettings& settings, const ParticleBody& body, const MaterialSet& law)
      : body_(body),
        law_(law),
        run_(MPI_COMM_WORLD, body.size(), [&settings, &body, &law](const std::vector<std::uint32_t>& ids) {
          return make_part_solver(settings, body, law, ids);
        }) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  }

  bool step() override { return run_.step(); }
  const ExplicitSolver& solver() const override { return run_.solver(); }
  bool writes() const override { return rank_ == 0; }

  // Each rank fills its own particles' records; rank 0 gathers them in the order of their ids.
  FieldOutput::RecordSource field_records(const FieldRecords& records) override {
    distributed::ParticleSet mine(static_cast<int>(records.width()));
    std::vector<double> record(records.width());
    each_owned([&](std::size_t i, std::uint32_t id) {
      records.fill(run_.solver(), i, record.data());
      mine.push_back(id, record.data());
    });
    auto all = std::make_shared<const distributed::ParticleSet>(distributed::gather(mine, MPI_COMM_WORLD, 0));
    if (rank_ != 0) return {};
    return [all](std::size_t i, double* out) { std::copy(all->at(i), all->at(i) + all->width, out); };
  }

  const Particles* body_particles() override {
    distributed::ParticleSet mine(6);  // x, v
    const Particles& p = run_.solver().particles();
    each_owned([&](std::size_t i, std::uint32_t id) {
      const double xv[6] = {p.x[3 * i], p.x[3 * i + 1], p.x[3 * i + 2], p.v[3 * i], p.v[3 * i + 1], p.v[3 * i + 2]};
      mine.push_back(id, xv);
    });
    const distributed::ParticleSet all = distributed::gather(mine, MPI_COMM_WORLD, 0);
    if (rank_ != 0) return nullptr;
    const std::size_t n = body_.size();
    body_now_.n = n;
    body_now_.x.resize(3 * n);
    body_now_.v.resize(3 * n);
    for (std::size_t k = 0; k < n; ++k)
      for (int d = 0; d < 3; ++d) body_now_.x[3 * k + d] = all.at(k)[d], body_now_.v[3 * k + d] = all.at(k)[3 + d];
    body_now_.mass = masses();
    body_now_.spacing = body_.spacing;
    return &body_now_;
  }

  // Every rank has the agreed kind, step and time. The particle is the one one process would name: the
  // first it meets (the smallest global id), or for an energy balance failure the most kinetic (mass
  // |v|^2, the first of equals); the lowest rank that named it describes it.
  FailureReport failure() override {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    FailureReport f = run_.solver().failure();
    const double id = f.particle >= 0 ? static_cast<double>(f.particle) : kNone;
    double key = id;
    if (f.particle >= 0 && f.kind == StepFailure::EnergyBalance) {
      const std::vector<std::uint32_t>& ids = run_.local_ids();  // ascending
      const auto at = std::lower_bound(ids.begin(), ids.end(), static_cast<std::uint32_t>(f.particle)) - ids.begin();
      key = -run_.solver().particles().mass[static_cast<std::size_t>(at)] *
            (f.v[0] * f.v[0] + f.v[1] * f.v[1] + f.v[2] * f.v[2]);
    }
    const double best_key = all_min(key);
    const double best_id = all_min(key == best_key ? id : kNone);
    if (best_id == kNone) return f;  // the sphere's, or no particle's: the same on every rank
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int describer = static_cast<int>(all_min(id == best_id && key == best_key ? rank_ : size));
    double state[8] = {f.x[0], f.x[1], f.x[2], f.v[0], f.v[1], f.v[2], f.volume_m3, f.volume0_m3};
    MPI_Bcast(state, 8, MPI_DOUBLE, describer, MPI_COMM_WORLD);
    f.particle = static_cast<std::int64_t>(best_id);
    f.x = {state[0], state[1], state[2]};
    f.v = {state[3], state[4], state[5]};
    f.volume_m3 = state[6];
    f.volume0_m3 = state[7];
    return f;
  }

  std::size_t fragment_particles() override {
    double count = static_cast<double>(run_.owned_fragments().size());  // exact in a double
    MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    return static_cast<std::size_t>(count);
  }

  std::vector<std::uint8_t> fragment_flags() override {
    const std::vector<std::uint32_t> mine = run_.owned_fragments();
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size)), starts(static_cast<std::size_t>(size), 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    for (int r = 1; r < size; ++r) starts[r] = starts[r - 1] + counts[r - 1];
    std::vector<std::uint32_t> ids(rank_ == 0 ? static_cast<std::size_t>(starts.back() + counts.back()) : 0);
    MPI_Gatherv(mine.data(), count, MPI_UINT32_T, ids.data(), counts.data(), starts.data(), MPI_UINT32_T, 0, MPI_COMM_WORLD);
    if (rank_ != 0) return {};
    std::vector<std::uint8_t> flags(body_.size(), 0);
    for (const std::uint32_t id : ids) flags[id] = 1;
    return flags;
  }

  double rows_kept_fraction() override {
    double rows[2] = {static_cast<double>(run_.rows_built()), static_cast<double>(run_.rows_kept())};
    MPI_Allreduce(MPI_IN_PLACE, rows, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    return kept_fraction(rows[0], rows[1]);
  }

  // Rank 0 gathers every particle's record and makes the whole body's checkpoint of them.
  SolverCheckpoint checkpoint() override {
    const distributed::ParticleSet all = distributed::gather(run_.owned_records(), MPI_COMM_WORLD, 0);
    if (rank_ != 0) return {};
    return run_.solver().body_checkpoint(all.size(), all.values.data(), static_cast<std::size_t>(all.width));
  }
  void resume(const SolverCheckpoint& checkpoint) override { run_.resume(checkpoint); }
  void drop_rows() override { run_.drop_rows(); }
  bool agree(bool decided) override {
    int flag = decided ? 1 : 0;
    MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return flag != 0;
  }

  double target_mass_kg() override {  // summed as one process sums it, so that the outcome is decided alike
    double mass = 0.0;
    for (const double m : masses()) mass += m;
    return mass;
  }

 private:
  // f(i, id) for each particle the rank owns: its place in the rank's solver and its global id.
  template <class F>
  void each_owned(F&& f) const {
    const std::vector<std::uint8_t>& owned = run_.owned();
    const std::vector<std::uint32_t>& ids = run_.local_ids();
    for (std::size_t i = 0; i < owned.size(); ++i)
      if (owned[i]) f(i, ids[i]);
  }
  // The body's masses as one process has them (Particles::from_body), from the body every rank holds.
  std::vector<double> masses() const {
    const double rho = reference_density(law_);
    std::vector<double> m(body_.size());
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = rho * body_.volume[i];
    return m;
  }

  const ParticleBody& body_;
  const MaterialSet& law_;
  DistributedRun run_;
  int rank_ = 0;
  Particles body_now_;           // rank 0: the body's positions, velocities, masses and spacings
};

}  // namespace

int world_ranks() {
  int started = 0, size = 1;
  MPI_Initialized(&started);
  if (started) MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int world_rank() {
  int started = 0, rank = 0;
  MPI_Initialized(&started);
  if (started) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

std::unique_ptr<ShotStepper> make_distributed_shot(const CaseSettings& settings, const ParticleBody& body,
                                                   const MaterialSet& law) {
  return std::make_unique<DistributedShot>(settings, body, law);
}

}  // namespace uhpc::macro
