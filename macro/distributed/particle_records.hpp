#pragma once
// A solver's particles as records that travel between ranks (migration, ghosts): each particle's
// evolving fields, as the checkpoint lists them (SolverCheckpoint::particle_fields, the list the
// step-repeat guard and the checkpoint files use too), its material state's bytes and the constants of
// the step loop that a checkpoint leaves to the case (mass, volume0, spacing, support), in one row of
// doubles, the position first. to_records and from_records are each other's inverse, bit for bit.
#include <cstddef>
#include <string>
#include <vector>

#include "distributed/particle_set.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro::distributed {

struct RecordLayout {
  std::vector<std::string> fields;  // the checkpoint's fields, "x" first
  std::vector<int> widths;          // doubles a particle of each
  std::size_t state_bytes = 0;      // material state bytes a particle
  int width = 0;                    // doubles a record: fields, constants (4), state
};

// The layout of a checkpoint of n particles (std::invalid_argument when a field or the states do not
// divide into n, or when there is no "x").
RecordLayout record_layout(const SolverCheckpoint& c, std::size_t n);
// Records of the particles at `rows` of c and p, named by their global ids `ids` (one each).
ParticleSet to_records(const RecordLayout& layout, const SolverCheckpoint& c, const Particles& p,
                       const std::vector<std::uint32_t>& rows, const std::vector<std::uint32_t>& ids);
// The records' particles, in the records' order, into c's fields and states, the step state's per-
// particle forces of the last step (f_ext_old, f_contact_old: f_ext and f_contact, as they are after
// every completed step) and p's constants (p.n and those four fields; p's other fields are not
// touched). c's other step state and counters are left as they are.
void from_records(const RecordLayout& layout, const ParticleSet& records, SolverCheckpoint& c, Particles& p);

}  // namespace uhpc::macro::distributed
