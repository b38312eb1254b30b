#pragma once
// ensemble.h5: the contract between `uhpc-micro ensemble` (writer) and `uhpc-calibrate` (reader).
// It lives in common/ so that both programs share this one implementation.
// The layout is documented in calibrate/README.md; in short (n = sizes, m = strains, row-major):
//   /sizes (n) "m", /strain (m) "1", /damage/mean, /damage/std (n x m) "1",
//   /stress/mean, /stress/std (n x m) "Pa", /cells (n) int64 "1", /nominal_strength (n) "Pa",
//   root attribute "provenance".
// The reader validates everything (presence, shape, units, finiteness, ordering) and reports the
// first problem as one InputError naming the file, the dataset and the reason.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "uhpc/provenance.hpp"

namespace uhpc {

struct Ensemble {
  std::vector<double> sizes_m;             // ascending, > 0
  std::vector<double> strain;              // common grid, strictly ascending
  std::vector<std::vector<double>> damage_mean;  // [size][strain]
  std::vector<std::vector<double>> damage_std;   // [size][strain], >= 0 (spread over the cells)
  std::vector<std::vector<double>> stress_mean_Pa;
  std::vector<std::vector<double>> stress_std_Pa;
  std::vector<std::int64_t> cells;         // cells averaged per size, >= 1
  std::vector<double> nominal_strength_Pa; // peak of the mean stress curve per size, > 0
  std::optional<Provenance> provenance;    // always present in a file read back

  std::size_t size_count() const { return sizes_m.size(); }
  std::size_t strain_count() const { return strain.size(); }
};

// Reads and validates `path`. Throws InputError "<path>: dataset '<name>': <reason>" (or
// "<path>: <reason>" for the file itself) for a missing file, a missing dataset or attribute, a wrong
// shape or units, a non-finite value, non-ascending sizes or strains, negative spread, cells < 1.
Ensemble read_ensemble(const std::filesystem::path& path);

// Checks the in-memory arrays against the same rules (std::invalid_argument on a programming error)
// and writes the file atomically with `provenance`.
void write_ensemble(const std::filesystem::path& path, const Ensemble& ensemble, const Provenance& provenance);

}  // namespace uhpc
