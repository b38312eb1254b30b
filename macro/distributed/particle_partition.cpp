#include "distributed/particle_partition.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include <zoltan.h>

#include "distributed/zoltan_error.hpp"

#include "distributed/transfer.hpp"

namespace uhpc::macro::distributed {

// Zoltan's query functions: the owned particles of the set being balanced, one id each (local id =
// position in the set), unit weights, their positions.
struct ZoltanCallbacks {
  static const ParticleSet& set(void* data) { return *static_cast<ParticlePartition*>(data)->current_; }
  static int count(void* data, int* ierr) {
    *ierr = ZOLTAN_OK;
    return static_cast<int>(set(data).size());
  }
  static void list(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int, float*, int* ierr) {
    const ParticleSet& s = set(data);
    for (std::size_t i = 0; i < s.size(); ++i) {
      gids[i] = static_cast<ZOLTAN_ID_TYPE>(s.id[i]);
      lids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
    }
    *ierr = ZOLTAN_OK;
  }
  static int dimension(void*, int* ierr) {
    *ierr = ZOLTAN_OK;
    return 3;
  }
  static void positions(void* data, int, int, int n, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int, double* x, int* ierr) {
    const ParticleSet& s = set(data);
    for (int k = 0; k < n; ++k) std::copy(s.at(lids[k]), s.at(lids[k]) + 3, x + 3 * k);
    *ierr = ZOLTAN_OK;
  }
};

ParticlePartition::ParticlePartition(MPI_Comm comm, PartitionOptions options)
    : comm_(comm), options_(options) {
  if (!(options_.balance_tolerance >= 1.0) || !(options_.rebalance_threshold >= options_.balance_tolerance))
    throw std::invalid_argument("ParticlePartition: need 1 <= balance_tolerance <= rebalance_threshold");
  MPI_Comm_rank(comm_.get(), &rank_);
  MPI_Comm_size(comm_.get(), &size_);
  float version = 0.0f;
  check_zoltan(Zoltan_Initialize(0, nullptr, &version), "Zoltan_Initialize");
  zz_ = Zoltan_Create(comm_.get());
  if (!zz_) throw std::runtime_error("Zoltan_Create failed");
  const std::string tolerance = std::to_string(options_.balance_tolerance);
  // DEBUG_LEVEL first: set later, Zoltan has already announced the method. No lists: the owners come
  // from the cuts (balance). Rectilinear blocks: particles on a cut all go to one side, where rank_of
  // puts them, and Zoltan balances with that.
  const char* params[][2] = {{"DEBUG_LEVEL", "0"},     {"LB_METHOD", "RCB"},       {"KEEP_CUTS", "1"},
                             {"RCB_REUSE", "1"},       {"AVERAGE_CUTS", "1"},      {"NUM_GID_ENTRIES", "1"},
                             {"NUM_LID_ENTRIES", "1"}, {"OBJ_WEIGHT_DIM", "0"},    {"RETURN_LISTS", "NONE"},
                             {"RCB_OUTPUT_LEVEL", "0"}, {"IMBALANCE_TOL", tolerance.c_str()},
                             {"RCB_RECTILINEAR_BLOCKS", "1"}};
  for (const auto& p : params) check_zoltan(Zoltan_Set_Param(zz_, p[0], p[1]), p[0]);
  Zoltan_Set_Num_Obj_Fn(zz_, &ZoltanCallbacks::count, this);
  Zoltan_Set_Obj_List_Fn(zz_, &ZoltanCallbacks::list, this);
  Zoltan_Set_Num_Geom_Fn(zz_, &ZoltanCallbacks::dimension, this);
  Zoltan_Set_Geom_Multi_Fn(zz_, &ZoltanCallbacks::positions, this);
}

ParticlePartition::~ParticlePartition() { Zoltan_Destroy(&zz_); }

void ParticlePartition::balance(ParticleSet& owned) {
  current_ = &owned;
  int changes = 0, gid_entries = 0, lid_entries = 0, n_import = 0, n_export = 0;
  ZOLTAN_ID_PTR import_gids = nullptr, import_lids = nullptr, export_gids = nullptr, export_lids = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr, *export_parts = nullptr;
  const int code = Zoltan_LB_Partition(zz_, &changes, &gid_entries, &lid_entries, &n_import, &import_gids,
                                       &import_lids, &import_procs, &import_parts, &n_export, &export_gids,
                                       &export_lids, &export_procs, &export_parts);
  current_ = nullptr;
  Zoltan_LB_Free_Part(&import_gids, &import_lids, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_gids, &export_lids, &export_procs, &export_parts);
  check_zoltan(code, "Zoltan_LB_Partition");
  ++balances_;
  // Owners by region: rank_of, which migrate and every later question use.
  migrate(owned);
  balanced_imbalance_ = imbalance(owned);
}

void ParticlePartition::migrate(ParticleSet& owned) {
  if (!balanced()) throw std::logic_error("ParticlePartition::migrate: no cuts yet (balance first)");
  std::vector<int> owner(owned.size());
  for (std::size_t i = 0; i < owned.size(); ++i) owner[i] = rank_of(owned.at(i));
  std::vector<std::uint32_t> rows(owned.size());
  std::iota(rows.begin(), rows.end(), std::uint32_t{0});
  Transfer transfer(std::move(rows), std::move(owner), comm_.get());
  owned = transfer.carry(owned);
}

double ParticlePartition::imbalance(const ParticleSet& owned) const {
  const long long mine = static_cast<long long>(owned.size());
  long long most = 0, total = 0;
  MPI_Allreduce(&mine, &most, 1, MPI_LONG_LONG, MPI_MAX, comm_.get());
  MPI_Allreduce(&mine, &total, 1, MPI_LONG_LONG, MPI_SUM, comm_.get());
  if (total == 0) return 1.0;
  return static_cast<double>(most) * size_ / static_cast<double>(total);
}

bool ParticlePartition::rebalance_if_needed(ParticleSet& owned) {
  migrate(owned);
  // A body whose planes of particles cannot be split evenly stays above the threshold right after a
  // balance; only a drift beyond that asks for another.
  const double now = imbalance(owned);
  if (now <= options_.rebalance_threshold || now <= balanced_imbalance_) return false;
  balance(owned);
  return true;
}

int ParticlePartition::rank_of(const double x[3]) const {
  int proc = -1, part = -1;
  check_zoltan(Zoltan_LB_Point_PP_Assign(zz_, const_cast<double*>(x), &proc, &part), "Zoltan_LB_Point_PP_Assign");
  return proc;
}

}  // namespace uhpc::macro::distributed
