#pragma once
// The directory of each cell size in an ensemble's output (size_3.0mm/cell_07/), shared by
// generate-ensemble and ensemble: two sizes with the same name would write into one directory.
#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "uhpc/config.hpp"

namespace uhpc::micro {

inline std::string size_label(double size_m) { return fmt::format("size_{:.1f}mm", size_m * 1e3); }

// Bad input (the key `key` of `cfg`) when two of `sizes_m` share a directory name.
inline void require_distinct_size_dirs(const Config& cfg, const std::string& key, const std::vector<double>& sizes_m) {
  for (std::size_t i = 0; i < sizes_m.size(); ++i)
    for (std::size_t j = i + 1; j < sizes_m.size(); ++j)
      if (size_label(sizes_m[i]) == size_label(sizes_m[j]))
        cfg.fail(key, fmt::format("entries {} and {} share the directory name {} (sizes must differ by at least "
                                  "0.1 mm)", i, j, size_label(sizes_m[i])));
}

}  // namespace uhpc::micro
