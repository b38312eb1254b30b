// The ensemble file (common/include/uhpc/ensemble_file.hpp): the contract between uhpc-micro ensemble and
// uhpc-calibrate. Round trip, and one clear InputError per kind of bad file.
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "uhpc/ensemble_file.hpp"
#include "synthetic_ensemble.hpp"
#include "test_support.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hdf5_io.hpp"

namespace uhpc {
namespace {

const SdelConstants<double> kTable4{1.0, 2e-4, 120.5, 4.1e6};

Ensemble small_ensemble() {
  SyntheticEnsembleSettings s;
  s.sizes_m = {0.003, 0.0065};
  s.points = 11;
  s.noise_std = 0.01;
  s.seed = 3;
  return synthesize_ensemble(kTable4, s);
}

std::vector<double> flat(const std::vector<std::vector<double>>& rows) {
  std::vector<double> f;
  for (const auto& r : rows) f.insert(f.end(), r.begin(), r.end());
  return f;
}

// Writes the file dataset by dataset, letting a test change one thing (what the writer would refuse).
struct RawFile {
  std::string skip;                  // dataset not written
  std::string units_of, units;       // dataset written with other units
  bool provenance = true;
  std::function<void(std::vector<double>&)> edit_nominal;
  std::function<void(std::vector<double>&)> edit_sizes;
  bool damage_transposed = false;

  void write(const std::filesystem::path& path, const Ensemble& e) const {
    H5Writer w(path);
    const std::size_t n = e.size_count(), m = e.strain_count();
    auto u = [&](const std::string& name, const std::string& normal) { return name == units_of ? units : normal; };
    auto sizes = e.sizes_m;
    if (edit_sizes) edit_sizes(sizes);
    auto nominal = e.nominal_strength_Pa;
    if (edit_nominal) edit_nominal(nominal);
    if (skip != "/sizes") w.write("sizes", sizes, u("/sizes", "m"));
    if (skip != "/strain") w.write("strain", e.strain, u("/strain", "1"));
    const H5Dims dd = damage_transposed ? H5Dims{m, n} : H5Dims{n, m};
    if (skip != "/damage/mean") w.write("damage/mean", flat(e.damage_mean), dd, u("/damage/mean", "1"));
    if (skip != "/damage/std") w.write("damage/std", flat(e.damage_std), {n, m}, "1");
    if (skip != "/stress/mean") w.write("stress/mean", flat(e.stress_mean_Pa), {n, m}, "Pa");
    if (skip != "/stress/std") w.write("stress/std", flat(e.stress_std_Pa), {n, m}, "Pa");
    if (skip != "/cells") w.write("cells", e.cells, "1");
    if (skip != "/nominal_strength") w.write("nominal_strength", nominal, u("/nominal_strength", "Pa"));
    if (provenance) w.write_provenance(Provenance::make("test", ""));
    w.close();
  }
};

class CalibrateEnsembleFile : public test::ScratchDirTest {
 protected:
  std::string bad(const RawFile& raw, const Ensemble& e = small_ensemble()) {
    const auto path = dir_ / "bad.h5";
    raw.write(path, e);
    return test::error_of<InputError>([&] { (void)read_ensemble(path); });
  }
  std::string name() const { return (dir_ / "bad.h5").string(); }
};

TEST_F(CalibrateEnsembleFile, RoundTripKeepsEveryValueAndTheProvenance) {
  const Ensemble e = small_ensemble();
  write_ensemble(dir_ / "e.h5", e, Provenance::make("uhpc-micro ensemble", "abc", 42));
  const Ensemble r = read_ensemble(dir_ / "e.h5");
  EXPECT_EQ(r.sizes_m, e.sizes_m);
  EXPECT_EQ(r.strain, e.strain);
  EXPECT_EQ(r.damage_mean, e.damage_mean);
  EXPECT_EQ(r.damage_std, e.damage_std);
  EXPECT_EQ(r.stress_mean_Pa, e.stress_mean_Pa);
  EXPECT_EQ(r.stress_std_Pa, e.stress_std_Pa);
  EXPECT_EQ(r.cells, e.cells);
  EXPECT_EQ(r.nominal_strength_Pa, e.nominal_strength_Pa);
  ASSERT_TRUE(r.provenance.has_value());
  EXPECT_EQ(r.provenance->program, "uhpc-micro ensemble");
  EXPECT_EQ(r.provenance->seed, 42u);
}

TEST_F(CalibrateEnsembleFile, TheRawWriterOfTheseTestsMakesAValidFile) {
  RawFile{}.write(dir_ / "ok.h5", small_ensemble());
  EXPECT_NO_THROW((void)read_ensemble(dir_ / "ok.h5"));
}

TEST_F(CalibrateEnsembleFile, MissingFile) {
  const auto path = dir_ / "nothing.h5";
  EXPECT_EQ(test::error_of<InputError>([&] { (void)read_ensemble(path); }),
            path.string() + ": cannot open file (No such file or directory)");
}

TEST_F(CalibrateEnsembleFile, NotAnHdf5File) {
  const auto path = dir_ / "text.h5";
  std::ofstream(path) << "not hdf5";
  EXPECT_EQ(test::error_of<InputError>([&] { (void)read_ensemble(path); })
                .rfind(path.string() + ": not a readable HDF5 file: cannot open as HDF5: ", 0),
            0u);
}

// An ensemble written by uhpc-micro carries checksums: one byte of a stress value flipped in the file is
// refused naming the file and the dataset, never read as another stress.
TEST_F(CalibrateEnsembleFile, AFlippedValueInAWrittenEnsembleIsRefusedNamingTheDataset) {
  const Ensemble e = small_ensemble();
  const auto path = dir_ / "e.h5";
  write_ensemble(path, e, Provenance::make("uhpc-micro ensemble", "abc", 42));
  std::string bytes = test::read_file(path);
  const double value = e.stress_mean_Pa[1][5];
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&value), sizeof value));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 1] ^= 0x20;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_EQ(test::error_of<InputError>([&] { (void)read_ensemble(path); }),
            path.string() + ": not a readable HDF5 file: dataset 'stress/mean': cannot read (corrupt storage or "
                            "checksum mismatch): data error detected by Fletcher32 checksum");
}

TEST_F(CalibrateEnsembleFile, EachMissingDatasetIsNamed) {
  for (const std::string ds : {"/sizes", "/strain", "/damage/mean", "/damage/std", "/stress/mean", "/stress/std",
                               "/cells", "/nominal_strength"}) {
    RawFile raw;
    raw.skip = ds;
    EXPECT_EQ(bad(raw), name() + ": dataset '" + ds + "': required dataset is missing");
  }
}

TEST_F(CalibrateEnsembleFile, WrongUnits) {
  RawFile raw;
  raw.units_of = "/strain";
  raw.units = "m";
  EXPECT_EQ(bad(raw), name() + ": dataset '/strain': expected units \"1\", got \"m\"");
  raw.units_of = "/nominal_strength";
  raw.units = "MPa";
  EXPECT_EQ(bad(raw), name() + ": dataset '/nominal_strength': expected units \"Pa\", got \"MPa\"");
}

// A file of no size passed the reader and crashed uhpc-calibrate (the front of an empty list).
TEST_F(CalibrateEnsembleFile, NoSizesIsRefused) {
  Ensemble e;
  e.strain = {0.0, 1e-4};
  EXPECT_EQ(bad(RawFile{}, e), name() + ": dataset '/sizes': no sizes: an ensemble needs at least one cell size");
}

TEST_F(CalibrateEnsembleFile, WrongShape) {
  RawFile raw;
  raw.damage_transposed = true;
  EXPECT_EQ(bad(raw), name() + ": dataset '/damage/mean': expected shape (2 x 11), got (11 x 2)");
}

TEST_F(CalibrateEnsembleFile, NonFiniteValuesAreLocated) {
  RawFile raw;
  raw.edit_nominal = [](std::vector<double>& v) { v[1] = std::numeric_limits<double>::infinity(); };
  EXPECT_EQ(bad(raw), name() + ": dataset '/nominal_strength': infinite value at index 1");
}

TEST_F(CalibrateEnsembleFile, SizesMustBePositiveAndAscending) {
  RawFile raw;
  raw.edit_sizes = [](std::vector<double>& v) { std::swap(v[0], v[1]); };
  EXPECT_EQ(bad(raw), name() + ": dataset '/sizes': must be strictly ascending, but entry 1 (0.003) follows 0.0065");
  raw.edit_sizes = [](std::vector<double>& v) { v[0] = -0.003; };
  EXPECT_EQ(bad(raw), name() + ": dataset '/sizes': value -0.003 at index 0 is out of range, must be > 0");
}

TEST_F(CalibrateEnsembleFile, ProvenanceIsRequired) {
  RawFile raw;
  raw.provenance = false;
  EXPECT_EQ(bad(raw), name() + ": root attribute 'provenance' is missing");
}

TEST_F(CalibrateEnsembleFile, TheWriterRefusesWhatTheReaderWouldReject) {
  Ensemble e = small_ensemble();
  e.damage_mean[1][4] = std::nan("");
  const std::string what = test::error_of<std::invalid_argument>(
      [&] { write_ensemble(dir_ / "w.h5", e, Provenance::make("test", "")); });
  EXPECT_NE(what.find("'/damage/mean': NaN value at size index 1 (0.0065 m), strain index 4"), std::string::npos) << what;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "w.h5"));
}

}  // namespace
}  // namespace uhpc
