#include "distributed/transfer.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

#include <zoltan_comm.h>

#include "distributed/zoltan_error.hpp"

namespace uhpc::macro::distributed {

namespace {
constexpr int kTag = 7301;  // any tag: Zoltan_Comm keeps a plan's messages apart by it
}  // namespace

Transfer::Transfer(std::vector<std::uint32_t> rows, std::vector<int> ranks, MPI_Comm comm) : rows_(std::move(rows)) {
  if (ranks.size() != rows_.size()) throw std::invalid_argument("Transfer: one rank for each row");
  check_zoltan(Zoltan_Comm_Create(&plan_, static_cast<int>(ranks.size()), ranks.data(), comm, kTag, &received_),
               "Zoltan_Comm_Create");
}

Transfer::~Transfer() {
  if (plan_) Zoltan_Comm_Destroy(&plan_);
}

ParticleSet Transfer::carry(const ParticleSet& from) {
  for (std::uint32_t r : rows_)
    if (r >= from.size()) throw std::logic_error("Transfer::carry: a row beyond the set");
  source_size_ = from.size();
  // A record: the id in the first double's bytes, then the values.
  const std::size_t w = static_cast<std::size_t>(from.width) + 1;
  send_.resize(w * rows_.size());
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    double* r = send_.data() + w * k;
    r[0] = 0.0;
    std::memcpy(r, &from.id[rows_[k]], sizeof(std::uint32_t));
    std::copy(from.at(rows_[k]), from.at(rows_[k]) + from.width, r + 1);
  }
  receive_.resize(w * static_cast<std::size_t>(received_));
  check_zoltan(Zoltan_Comm_Do(plan_, kTag + 1, reinterpret_cast<char*>(send_.data()), static_cast<int>(w * sizeof(double)),
                       reinterpret_cast<char*>(receive_.data())),
        "Zoltan_Comm_Do");
  std::vector<std::uint32_t> ids(static_cast<std::size_t>(received_));
  for (std::size_t k = 0; k < ids.size(); ++k) std::memcpy(&ids[k], receive_.data() + w * k, sizeof(std::uint32_t));
  std::vector<std::size_t> by_id(ids.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  std::sort(by_id.begin(), by_id.end(), [&ids](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  order_.assign(ids.size(), 0);
  for (std::size_t s = 0; s < by_id.size(); ++s) order_[by_id[s]] = s;
  ParticleSet to(from.width);
  to.id.resize(ids.size());
  to.values.resize(static_cast<std::size_t>(from.width) * ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    to.id[order_[k]] = ids[k];
    std::copy(receive_.data() + w * k + 1, receive_.data() + w * (k + 1), to.at(order_[k]));
  }
  return to;
}

void Transfer::refresh(const ParticleSet& from, ParticleSet& to) const {
  const std::size_t w = static_cast<std::size_t>(from.width);
  if (from.size() != source_size_ || to.width != from.width || to.size() != order_.size())
    throw std::logic_error("Transfer::refresh: not the sets this transfer carried");
  send_.resize(w * rows_.size());
  for (std::size_t k = 0; k < rows_.size(); ++k) std::copy(from.at(rows_[k]), from.at(rows_[k]) + w, send_.data() + w * k);
  receive_.resize(w * order_.size());
  check_zoltan(Zoltan_Comm_Do(plan_, kTag + 2, reinterpret_cast<char*>(send_.data()), static_cast<int>(w * sizeof(double)),
                       reinterpret_cast<char*>(receive_.data())),
        "Zoltan_Comm_Do");
  for (std::size_t k = 0; k < order_.size(); ++k)
    std::copy(receive_.data() + w * k, receive_.data() + w * (k + 1), to.at(order_[k]));
}

}  // namespace uhpc::macro::distributed
