#include "distributed/particle_records.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <stdexcept>

namespace uhpc::macro::distributed {

namespace {
// The constants of the step loop, in record order.
constexpr std::vector<double> Particles::*kConstants[] = {&Particles::mass, &Particles::volume0, &Particles::spacing,
                                                          &Particles::support};

int state_doubles(const RecordLayout& layout) {
  return static_cast<int>((layout.state_bytes + sizeof(double) - 1) / sizeof(double));
}
}  // namespace

RecordLayout record_layout(const SolverCheckpoint& c, std::size_t n) {
  if (n == 0) throw std::invalid_argument("record_layout: no particles");
  RecordLayout layout;
  const auto add = [&](const std::string& name, const std::vector<double>& values) {
    if (values.size() % n != 0) throw std::invalid_argument("record_layout: field '" + name + "' does not divide into the particles");
    layout.fields.push_back(name);
    layout.widths.push_back(static_cast<int>(values.size() / n));
    layout.width += layout.widths.back();
  };
  for (const auto& [name, values] : c.particle_fields)  // the position first (ParticleSet's convention)
    if (name == "x") add(name, values);
  if (layout.fields.empty()) throw std::invalid_argument("record_layout: the checkpoint has no positions (x)");
  for (const auto& [name, values] : c.particle_fields)
    if (name != "x") add(name, values);
  if (c.material_states.size() % n != 0) throw std::invalid_argument("record_layout: the material states do not divide into the particles");
  layout.state_bytes = c.material_states.size() / n;
  layout.width += static_cast<int>(std::size(kConstants)) + state_doubles(layout);
  return layout;
}

namespace {
const std::vector<double>& field(const SolverCheckpoint& c, const std::string& name) {
  for (const auto& f : c.particle_fields)
    if (f.first == name) return f.second;
  throw std::invalid_argument("particle records: the checkpoint has no field '" + name + "'");
}
}  // namespace

ParticleSet to_records(const RecordLayout& layout, const SolverCheckpoint& c, const Particles& p,
                       const std::vector<std::uint32_t>& rows, const std::vector<std::uint32_t>& ids) {
  if (rows.size() != ids.size()) throw std::invalid_argument("to_records: one global id for each row");
  ParticleSet records(layout.width);
  std::vector<double> r(static_cast<std::size_t>(layout.width));
  std::vector<const std::vector<double>*> fields;
  for (const std::string& name : layout.fields) fields.push_back(&field(c, name));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::uint32_t i = rows[k];
    double* out = r.data();
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const double* from = fields[f]->data() + static_cast<std::size_t>(layout.widths[f]) * i;
      out = std::copy(from, from + layout.widths[f], out);
    }
    for (auto constant : kConstants) *out++ = (p.*constant)[i];
    std::fill(out, r.data() + r.size(), 0.0);  // the state's last double may be partly padding
    std::memcpy(out, c.material_states.data() + layout.state_bytes * i, layout.state_bytes);
    records.push_back(ids[k], r.data());
  }
  return records;
}

void from_records(const RecordLayout& layout, const ParticleSet& records, SolverCheckpoint& c, Particles& p) {
  if (records.width != layout.width) throw std::invalid_argument("from_records: records of another layout");
  const std::size_t n = records.size();
  c.particle_fields.clear();
  for (std::size_t k = 0; k < layout.fields.size(); ++k)
    c.particle_fields.emplace_back(layout.fields[k], std::vector<double>(static_cast<std::size_t>(layout.widths[k]) * n));
  c.material_states.assign(layout.state_bytes * n, 0);
  p.n = n;
  for (auto constant : kConstants) (p.*constant).assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double* in = records.at(i);
    for (std::size_t k = 0; k < layout.fields.size(); ++k) {
      const std::size_t w = static_cast<std::size_t>(layout.widths[k]);
      std::copy(in, in + w, c.particle_fields[k].second.data() + w * i);
      in += w;
    }
    for (auto constant : kConstants) (p.*constant)[i] = *in++;
    std::memcpy(c.material_states.data() + layout.state_bytes * i, in, layout.state_bytes);
  }
  c.state.f_ext_old = field(c, "f_ext");
  c.state.f_contact_old = field(c, "f_contact");
}

}  // namespace uhpc::macro::distributed
