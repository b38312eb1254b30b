#include "uhpc/ensemble_file.hpp"

#include <cmath>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "uhpc/errors.hpp"
#include "uhpc/hdf5_io.hpp"

namespace uhpc {
namespace {

// One validation routine for reading and writing; `fail` decides the exception type, so a file the
// writer accepts is exactly a file the reader accepts.
template <typename Fail>
class Checker {
 public:
  explicit Checker(Fail fail) : fail_(std::move(fail)) {}

  void finite(const std::string& name, const std::vector<double>& v, std::size_t columns,
              const std::vector<double>& sizes) const {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (std::isfinite(v[i])) continue;
      const std::string what = std::isnan(v[i]) ? "NaN" : "infinite";
      if (columns == 0) fail_(name, fmt::format("{} value at index {}", what, i));
      const std::size_t k = i / columns;
      fail_(name, fmt::format("{} value at size index {} ({} m), strain index {}", what, k,
                              k < sizes.size() ? sizes[k] : NAN, i % columns));
    }
  }
  void ascending(const std::string& name, const std::vector<double>& v) const {
    for (std::size_t i = 1; i < v.size(); ++i) {
      if (!(v[i] > v[i - 1])) {
        fail_(name, fmt::format("must be strictly ascending, but entry {} ({}) follows {}", i, v[i], v[i - 1]));
      }
    }
  }
  void at_least(const std::string& name, const std::vector<double>& v, double lo, bool open) const {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (open ? !(v[i] > lo) : !(v[i] >= lo)) {
        fail_(name, fmt::format("value {} at index {} is out of range, must be {} {}", v[i], i, open ? ">" : ">=", lo));
      }
    }
  }

  void all(const Ensemble& e, const std::vector<double>& flat_dm, const std::vector<double>& flat_ds,
           const std::vector<double>& flat_sm, const std::vector<double>& flat_ss) const {
    const std::size_t m = e.strain_count();
    finite("/sizes", e.sizes_m, 0, e.sizes_m);
    finite("/strain", e.strain, 0, e.sizes_m);
    finite("/damage/mean", flat_dm, m, e.sizes_m);
    finite("/damage/std", flat_ds, m, e.sizes_m);
    finite("/stress/mean", flat_sm, m, e.sizes_m);
    finite("/stress/std", flat_ss, m, e.sizes_m);
    finite("/nominal_strength", e.nominal_strength_Pa, 0, e.sizes_m);
    at_least("/sizes", e.sizes_m, 0.0, true);
    ascending("/sizes", e.sizes_m);
    if (m < 2) fail_("/strain", fmt::format("needs at least 2 strains, got {}", m));
    ascending("/strain", e.strain);
    at_least("/damage/std", flat_ds, 0.0, false);
    at_least("/stress/std", flat_ss, 0.0, false);
    at_least("/nominal_strength", e.nominal_strength_Pa, 0.0, true);
    for (std::size_t k = 0; k < e.cells.size(); ++k) {
      if (e.cells[k] < 1) fail_("/cells", fmt::format("value {} at index {} is out of range, must be >= 1", e.cells[k], k));
    }
  }

 private:
  Fail fail_;
};

std::vector<double> flatten(const std::vector<std::vector<double>>& rows) {
  std::vector<double> flat;
  for (const auto& r : rows) flat.insert(flat.end(), r.begin(), r.end());
  return flat;
}

std::vector<std::vector<double>> unflatten(const std::vector<double>& flat, std::size_t n, std::size_t m) {
  std::vector<std::vector<double>> rows(n);
  for (std::size_t k = 0; k < n; ++k) rows[k].assign(flat.begin() + k * m, flat.begin() + (k + 1) * m);
  return rows;
}

std::string dims_text(const H5Dims& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? " x " : "") + std::to_string(dims[i]);
  return s + ")";
}

// Reads one dataset, checking presence, units and shape; errors name the file and the dataset.
class EnsembleReader {
 public:
  explicit EnsembleReader(const std::filesystem::path& path) : path_(path.string()), h5_(open(path)) {}

  [[noreturn]] void fail(const std::string& dataset, const std::string& reason) const {
    throw InputError(path_ + ": dataset '" + dataset + "': " + reason);
  }

  H5Array<double> doubles(const std::string& name, const std::string& units, const H5Dims& expected) const {
    check(name, units, expected);
    return wrap([&] { return h5_.read_doubles(name); });
  }
  H5Array<std::int64_t> integers(const std::string& name, const std::string& units, const H5Dims& expected) const {
    check(name, units, expected);
    return wrap([&] { return h5_.read_int64(name); });
  }
  // The length of a 1D dataset (used for /sizes and /strain, which define n and m).
  std::size_t length(const std::string& name) const {
    require(name);
    const H5Dims d = wrap([&] { return h5_.dims(name); });
    if (d.size() != 1) fail(name, "expected a 1D dataset, got shape " + dims_text(d));
    return d[0];
  }
  Provenance provenance() const {
    if (!h5_.has_attribute("", "provenance")) throw InputError(path_ + ": root attribute 'provenance' is missing");
    try {
      return h5_.provenance();
    } catch (const std::runtime_error& e) {
      throw InputError(path_ + ": root attribute 'provenance': " + e.what());
    }
  }

 private:
  static H5Reader open(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      throw InputError(path.string() + ": cannot open file (No such file or directory)");
    }
    // A user's ensemble may come from any program (h5py): without checksums it is accepted, after a
    // child process has read it whole (hdf5_io.hpp); one written by uhpc-micro is verified.
    try {
      return H5Reader(path, H5Checksums::optional);
    } catch (const std::runtime_error& e) {
      // The reader's message names the file first: said once.
      std::string reason = e.what();
      const std::string head = path.string() + ": ";
      if (reason.rfind(head, 0) == 0) reason.erase(0, head.size());
      throw InputError(head + "not a readable HDF5 file: " + reason);
    }
  }
  void require(const std::string& name) const {
    if (!wrap([&] { return h5_.has(name); })) fail(name, "required dataset is missing");
  }
  void check(const std::string& name, const std::string& units, const H5Dims& expected) const {
    require(name);
    const H5Dims d = wrap([&] { return h5_.dims(name); });
    if (d != expected) fail(name, "expected shape " + dims_text(expected) + ", got " + dims_text(d));
    std::string got;
    try {
      got = h5_.units(name);
    } catch (const std::runtime_error&) {
      fail(name, "attribute 'units' is missing");
    }
    if (got != units) fail(name, "expected units \"" + units + "\", got \"" + got + "\"");
  }
  template <typename F>
  auto wrap(F&& f) const -> decltype(f()) {
    try {
      return f();
    } catch (const std::runtime_error& e) {
      // The HDF5 layer's message already names file and dataset; a corrupt file is bad input.
      throw InputError(e.what());
    }
  }

  std::string path_;
  H5Reader h5_;
};

}  // namespace

Ensemble read_ensemble(const std::filesystem::path& path) {
  const EnsembleReader r(path);
  Ensemble e;
  const std::size_t n = r.length("/sizes");
  const std::size_t m = r.length("/strain");
  // An ensemble of no size or no strain has no curve to fit (uhpc-calibrate read past an empty list).
  if (n == 0) r.fail("/sizes", "no sizes: an ensemble needs at least one cell size");
  if (m == 0) r.fail("/strain", "no strains: an ensemble needs at least one strain");
  e.sizes_m = r.doubles("/sizes", "m", {n}).values;
  e.strain = r.doubles("/strain", "1", {m}).values;
  const auto dm = r.doubles("/damage/mean", "1", {n, m}).values;
  const auto ds = r.doubles("/damage/std", "1", {n, m}).values;
  const auto sm = r.doubles("/stress/mean", "Pa", {n, m}).values;
  const auto ss = r.doubles("/stress/std", "Pa", {n, m}).values;
  e.cells = r.integers("/cells", "1", {n}).values;
  e.nominal_strength_Pa = r.doubles("/nominal_strength", "Pa", {n}).values;
  const auto fail = [&r](const std::string& name, const std::string& reason) { r.fail(name, reason); };
  Checker<decltype(fail)>(fail).all(e, dm, ds, sm, ss);
  e.damage_mean = unflatten(dm, n, m);
  e.damage_std = unflatten(ds, n, m);
  e.stress_mean_Pa = unflatten(sm, n, m);
  e.stress_std_Pa = unflatten(ss, n, m);
  e.provenance = r.provenance();
  return e;
}

void write_ensemble(const std::filesystem::path& path, const Ensemble& e, const Provenance& provenance) {
  const std::size_t n = e.size_count(), m = e.strain_count();
  const auto fail = [&path](const std::string& name, const std::string& reason) {
    throw std::invalid_argument("write_ensemble " + path.string() + ": '" + name + "': " + reason);
  };
  if (n == 0) fail("/sizes", "no sizes");
  for (const auto* rows : {&e.damage_mean, &e.damage_std, &e.stress_mean_Pa, &e.stress_std_Pa}) {
    if (rows->size() != n) fail("curves", "one row per size expected");
    for (const auto& row : *rows) {
      if (row.size() != m) fail("curves", "one value per strain expected");
    }
  }
  if (e.cells.size() != n || e.nominal_strength_Pa.size() != n) fail("/cells", "one value per size expected");
  const auto dm = flatten(e.damage_mean), ds = flatten(e.damage_std);
  const auto sm = flatten(e.stress_mean_Pa), ss = flatten(e.stress_std_Pa);
  Checker<decltype(fail)>(fail).all(e, dm, ds, sm, ss);

  H5Writer w(path);
  w.write("sizes", e.sizes_m, "m");
  w.write("strain", e.strain, "1");
  w.write("damage/mean", dm, {n, m}, "1");
  w.write("damage/std", ds, {n, m}, "1");
  w.write("stress/mean", sm, {n, m}, "Pa");
  w.write("stress/std", ss, {n, m}, "Pa");
  w.write("cells", e.cells, "1");
  w.write("nominal_strength", e.nominal_strength_Pa, "Pa");
  w.write_provenance(provenance);
  w.close();
}

}  // namespace uhpc
