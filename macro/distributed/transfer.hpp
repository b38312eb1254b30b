#pragma once
// Irregular point-to-point sends of particle records through Zoltan's communication package
// (Zoltan_Comm): the plan is made once from "row k goes to rank r" (copies and sends to oneself
// allowed) and used for a first carry of whole records, then for refreshing the same rows' values as
// often as wanted (a halo's ghosts each step) until the owners change. Every call is collective.
#include <cstdint>
#include <vector>

#include <mpi.h>

#include "distributed/particle_set.hpp"

struct Zoltan_Comm_Obj;

namespace uhpc::macro::distributed {

class Transfer {
 public:
  // rows[k] of the set given to carry/refresh goes to rank ranks[k].
  Transfer(std::vector<std::uint32_t> rows, std::vector<int> ranks, MPI_Comm comm);
  ~Transfer();
  Transfer(const Transfer&) = delete;
  Transfer& operator=(const Transfer&) = delete;

  // Ids and values of the rows; returns what this rank received, sorted by id.
  ParticleSet carry(const ParticleSet& from);
  // The same rows' values again (ids unchanged), into `to` as carry returned it. After carry, from the
  // same set (the same ids in the same places; std::logic_error when its size or width changed).
  void refresh(const ParticleSet& from, ParticleSet& to) const;
  // The rows sent (refresh reads only these of `from`), in the plan's order, a row once per rank.
  const std::vector<std::uint32_t>& rows() const { return rows_; }

 private:
  std::vector<std::uint32_t> rows_;
  std::size_t source_size_ = 0;  // the size of the set carried from
  Zoltan_Comm_Obj* plan_ = nullptr;
  int received_ = 0;
  std::vector<std::size_t> order_;  // sorted position of the k-th record received
  mutable std::vector<double> send_, receive_;
};

}  // namespace uhpc::macro::distributed
