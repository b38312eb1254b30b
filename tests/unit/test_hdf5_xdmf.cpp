// HDF5 result files (round trips with units, temporary-then-rename, error messages, provenance) and
// the XDMF particle-field writer (document structure, and every reference resolvable in the .h5).
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/hdf5_io.hpp"
#include "uhpc/xdmf.hpp"

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using uhpc::H5Dims;
using uhpc::H5Reader;
using uhpc::H5Writer;

namespace {

using H5Test = uhpc::test::ScratchDirTest;

std::string read_text(const fs::path& path) { return uhpc::test::read_file(path); }

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The exception message of `f`, or "" if it did not throw std::runtime_error.
template <typename F>
std::string runtime_error_of(F&& f) {
  return uhpc::test::error_of<std::runtime_error>(f);
}

uhpc::Provenance sample_provenance() {
  uhpc::Provenance p = uhpc::Provenance::make("uhpc-micro run", "cbf29ce484222325",
                                              std::numeric_limits<std::uint64_t>::max());
  return p;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
// H5Writer / H5Reader

TEST_F(H5Test, RoundTripOfDoubleAndIntegerDatasetsInNestedGroups) {
  const fs::path file = dir_ / "curves.h5";
  const std::vector<double> strain = {0.0, 1e-4, 2e-4, 3.5e-4};
  const std::vector<double> stress = {1, 2, 3, 4, 5, 6};  // 2 x 3
  const std::vector<std::int64_t> ids = {-3, 0, std::numeric_limits<std::int64_t>::max(), 7, 8, 9};
  const std::vector<std::int32_t> steps = {10, 20, 30};
  const std::vector<std::uint8_t> flags = {0, 1, 255};
  {
    H5Writer w(file);
    w.write("strain", strain, "1");
    w.write("size_0.01/cell_3/stress", stress.data(), {2, 3}, "Pa");
    w.write("/size_0.01/ids", ids, {3, 2}, "1");
    w.write("a/b/c/steps", steps, "1");
    w.write("a/flags", flags, "1");
    w.close();
  }
  H5Reader r(file);
  const auto s = r.read_doubles("strain");
  EXPECT_EQ(s.values, strain);
  EXPECT_THAT(s.dims, ElementsAre(4u));
  EXPECT_EQ(r.units("strain"), "1");

  const auto t = r.read_doubles("size_0.01/cell_3/stress");
  EXPECT_EQ(t.values, stress);
  EXPECT_THAT(t.dims, ElementsAre(2u, 3u));
  EXPECT_EQ(r.units("/size_0.01/cell_3/stress"), "Pa");

  const auto i = r.read_int64("size_0.01/ids");
  EXPECT_EQ(i.values, ids);
  EXPECT_THAT(i.dims, ElementsAre(3u, 2u));

  EXPECT_THAT(r.read_int64("a/b/c/steps").values, ElementsAre(10, 20, 30));
  EXPECT_THAT(r.read_int64("a/flags").values, ElementsAre(0, 1, 255));
  EXPECT_THAT(r.read_doubles("a/b/c/steps").values, ElementsAre(10.0, 20.0, 30.0));  // integers convert
  EXPECT_THAT(r.dims("size_0.01/cell_3/stress"), ElementsAre(2u, 3u));

  EXPECT_TRUE(r.has("a/b"));
  EXPECT_TRUE(r.has("a/b/c/steps"));
  EXPECT_FALSE(r.has("a/x/y"));
  EXPECT_THAT(r.children(""), ElementsAre("a", "size_0.01", "strain"));
  EXPECT_THAT(r.children("size_0.01"), ElementsAre("cell_3", "ids"));
}

TEST_F(H5Test, EveryDatasetCarriesUnitsAndEmptyUnitsAreRejected) {
  const fs::path file = dir_ / "u.h5";
  H5Writer w(file);
  const std::vector<double> v = {1.0, 2.0};
  EXPECT_THROW(w.write("v", v, ""), std::invalid_argument);
  EXPECT_FALSE(w.has("v"));
  w.write("v", v, "m/s");
  EXPECT_THROW(w.write("v", v, "m/s"), std::invalid_argument);      // written twice
  EXPECT_THROW(w.write("w", v, {3}, "m"), std::invalid_argument);   // dims do not match
  EXPECT_THROW(w.write("", v, "m"), std::invalid_argument);         // no name
  EXPECT_THROW(w.write("a//b", v, "m"), std::invalid_argument);     // malformed name
  w.close();
  EXPECT_EQ(H5Reader(file).units("v"), "m/s");
}

TEST_F(H5Test, EmptyDatasetRoundTrips) {
  const fs::path file = dir_ / "e.h5";
  H5Writer w(file);
  w.write("none", std::vector<double>{}, "Pa");
  w.write("rows", static_cast<const double*>(nullptr), {0, 3}, "m");
  w.close();
  H5Reader r(file);
  EXPECT_TRUE(r.read_doubles("none").values.empty());
  EXPECT_THAT(r.read_doubles("rows").dims, ElementsAre(0u, 3u));
}

TEST_F(H5Test, MissingDatasetErrorNamesFileAndDataset) {
  const fs::path file = dir_ / "m.h5";
  {
    H5Writer w(file);
    w.write("group/x", std::vector<double>{1.0}, "1");
    w.close();
  }
  H5Reader r(file);
  EXPECT_EQ(runtime_error_of([&] { r.read_doubles("nope"); }), file.string() + ": dataset 'nope': not found");
  EXPECT_EQ(runtime_error_of([&] { r.read_int64("group/y/z"); }), file.string() + ": dataset 'group/y/z': not found");
  EXPECT_EQ(runtime_error_of([&] { r.units("nope"); }), file.string() + ": dataset 'nope': not found");
  EXPECT_THAT(runtime_error_of([&] { r.read_doubles("group"); }), HasSubstr("dataset 'group': not a dataset"));
  EXPECT_THAT(runtime_error_of([&] { r.string_attribute("group/x", "colour"); }),
              HasSubstr(file.string() + ": object 'group/x': attribute 'colour': not found"));
}

TEST_F(H5Test, IntegersOnlyReadRejectsFloatingPointData) {
  const fs::path file = dir_ / "f.h5";
  {
    H5Writer w(file);
    w.write("x", std::vector<double>{1.5}, "m");
    w.close();
  }
  EXPECT_THAT(runtime_error_of([&] { H5Reader(file).read_int64("x"); }), HasSubstr("dataset 'x': holds no integers"));
}

TEST_F(H5Test, OpeningMissingOrForeignFileNamesIt) {
  EXPECT_EQ(runtime_error_of([&] { H5Reader r(dir_ / "absent.h5"); }), (dir_ / "absent.h5").string() + ": no such file");
  uhpc::write_text_atomic(dir_ / "text.h5", "not hdf5");
  EXPECT_THAT(runtime_error_of([&] { H5Reader r(dir_ / "text.h5"); }),
              HasSubstr((dir_ / "text.h5").string() + ": cannot open as HDF5"));
}

TEST_F(H5Test, HdfLibraryPrintsNothingOnErrors) {
  const fs::path file = dir_ / "q.h5";
  {
    H5Writer w(file);
    w.write("x", std::vector<double>{1.0}, "1");
    w.close();
  }
  uhpc::write_text_atomic(dir_ / "text.h5", "not hdf5");
  ::testing::internal::CaptureStderr();
  H5Reader r(file);
  EXPECT_THROW(r.read_doubles("missing/deep/name"), std::runtime_error);
  EXPECT_THROW(r.string_attribute("", "nothing"), std::runtime_error);
  EXPECT_THROW(H5Reader bad(dir_ / "text.h5"), std::runtime_error);
  EXPECT_FALSE(r.has("x/y"));
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(H5Test, TemporaryIsRenamedOnCloseAndDiscardedWithoutClose) {
  const fs::path file = dir_ / "result.h5";
  const fs::path tmp = uhpc::temporary_path_for(file);
  {
    H5Writer w(file);
    w.write("x", std::vector<double>{1.0}, "1");
    EXPECT_TRUE(fs::exists(tmp));
    EXPECT_FALSE(fs::exists(file));
    w.close();
    EXPECT_FALSE(w.is_open());
    EXPECT_THROW(w.write("y", std::vector<double>{1.0}, "1"), std::logic_error);
  }
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(tmp));

  const fs::path failed = dir_ / "failed" / "result.h5";  // parent directory is created
  {
    H5Writer w(failed);
    w.write("x", std::vector<double>{1.0}, "1");
    EXPECT_TRUE(fs::exists(uhpc::temporary_path_for(failed)));
  }  // destroyed without close(): as after an exception in a failed run
  EXPECT_FALSE(fs::exists(failed));
  EXPECT_FALSE(fs::exists(uhpc::temporary_path_for(failed)));
  EXPECT_TRUE(fs::is_empty(dir_ / "failed"));
}

TEST_F(H5Test, FailedRunKeepsThePreviousResult) {
  const fs::path file = dir_ / "result.h5";
  {
    H5Writer w(file);
    w.write("x", std::vector<double>{1.0}, "1");
    w.close();
  }
  try {
    H5Writer w(file);
    w.write("x", std::vector<double>{2.0}, "1");
    throw std::runtime_error("solver diverged");
  } catch (const std::runtime_error&) {
  }
  EXPECT_THAT(H5Reader(file).read_doubles("x").values, ElementsAre(1.0));
}

TEST_F(H5Test, MovedWriterOwnsTheFile) {
  const fs::path file = dir_ / "moved.h5";
  H5Writer a(file);
  a.write("x", std::vector<double>{1.0}, "1");
  H5Writer b(std::move(a));
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move): checking the moved-from state
  b.write("y", std::vector<double>{2.0}, "1");
  b.close();
  H5Reader r(file);
  EXPECT_TRUE(r.has("x"));
  EXPECT_TRUE(r.has("y"));
}

TEST_F(H5Test, AttributesOnRootGroupsAndDatasets) {
  const fs::path file = dir_ / "attr.h5";
  {
    H5Writer w(file);
    w.write("size_0.01/stress", std::vector<double>{1.0, 2.0}, "Pa");
    w.create_group("empty/group");
    w.set_attribute("", "format", "uhpc-ensemble-1");
    w.set_attribute("/", "cells", 12);
    w.set_attribute("size_0.01", "cell_size_m", 0.01);
    w.set_attribute("size_0.01/stress", "peak_Pa", 2.0);
    w.set_attribute("size_0.01/stress", "peak_Pa", 3.0);  // replaced
    w.set_attribute("empty/group", "steps", std::int64_t{-5});
    w.set_attribute("empty/group", "big", std::uint64_t{1} << 40);
    EXPECT_THROW(w.set_attribute("empty", "too_big", std::numeric_limits<std::uint64_t>::max()), std::out_of_range);
    EXPECT_THROW(w.set_attribute("missing", "x", 1.0), std::runtime_error);
    w.close();
  }
  H5Reader r(file);
  EXPECT_EQ(r.string_attribute("", "format"), "uhpc-ensemble-1");
  EXPECT_EQ(r.int64_attribute("/", "cells"), 12);
  EXPECT_EQ(r.double_attribute("size_0.01", "cell_size_m"), 0.01);
  EXPECT_EQ(r.double_attribute("size_0.01/stress", "peak_Pa"), 3.0);
  EXPECT_EQ(r.int64_attribute("empty/group", "steps"), -5);
  EXPECT_EQ(r.int64_attribute("empty/group", "big"), std::int64_t{1} << 40);
  EXPECT_DOUBLE_EQ(r.double_attribute("empty/group", "steps"), -5.0);  // integers convert
  EXPECT_TRUE(r.has_attribute("size_0.01/stress", "units"));
  EXPECT_FALSE(r.has_attribute("size_0.01/stress", "colour"));
  EXPECT_FALSE(r.has_attribute("nowhere", "units"));
  EXPECT_THAT(runtime_error_of([&] { r.int64_attribute("size_0.01", "cell_size_m"); }), HasSubstr("not an integer"));
  EXPECT_THAT(runtime_error_of([&] { r.double_attribute("", "format"); }), HasSubstr("not a number"));
}

TEST_F(H5Test, ProvenanceRoundTripThroughHdf5KeepsLargestSeed) {
  const fs::path file = dir_ / "prov.h5";
  const uhpc::Provenance p = sample_provenance();
  {
    H5Writer w(file);
    w.write("x", std::vector<double>{1.0}, "1");
    w.write_provenance(p);
    w.close();
  }
  H5Reader r(file);
  const uhpc::Provenance back = r.provenance();
  EXPECT_EQ(back.program, p.program);
  EXPECT_EQ(back.version, p.version);
  EXPECT_EQ(back.git_commit, p.git_commit);
  EXPECT_EQ(back.config_hash, p.config_hash);
  EXPECT_EQ(back.date_utc, p.date_utc);
  ASSERT_TRUE(back.seed.has_value());
  EXPECT_EQ(*back.seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(nlohmann::json::parse(r.string_attribute("", "provenance")), p.to_json());
}

TEST_F(H5Test, BadProvenanceAttributeIsReportedWithFile) {
  const fs::path file = dir_ / "badprov.h5";
  {
    H5Writer w(file);
    w.set_attribute("", "provenance", "{\"program\": 1}");
    w.close();
  }
  EXPECT_THAT(runtime_error_of([&] { H5Reader(file).provenance(); }),
              HasSubstr(file.string() + ": attribute 'provenance': key 'program'"));
}

TEST_F(H5Test, CompressedDatasetsRoundTrip) {
  const fs::path file = dir_ / "gz.h5";
  std::vector<double> values(3000 * 3);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1e-3 * static_cast<double>(i % 17);
  {
    H5Writer w(file, uhpc::H5WriteOptions{6});
    w.write("position", values, {3000, 3}, "m");
    w.close();
  }
  {
    // The dataset is chunked and deflated (checked through the C API: the reader does not expose it).
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/position", H5P_DEFAULT);
    const hid_t dcpl = H5Dget_create_plist(d);
    EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
    EXPECT_GT(H5Pget_nfilters(dcpl), 0);
    H5Pclose(dcpl);
    H5Dclose(d);
    H5Fclose(f);
  }
  EXPECT_EQ(H5Reader(file).read_doubles("position").values, values);
  EXPECT_THROW(H5Writer(dir_ / "bad.h5", uhpc::H5WriteOptions{10}), std::invalid_argument);
}

// A dataset's declared shape is checked against what the file can hold before the reader allocates:
// a 4e9-value dataset that was never written (its storage unallocated) in a file of a few kB was read as
// 32 GB of fill values. Deflated data stays readable: deflate cannot compress more than 1032:1.
TEST_F(H5Test, ADatasetLargerThanItsFileCanHoldIsRefusedBeforeAnyAllocation) {
  const fs::path file = dir_ / "huge.h5";
  {
    const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t n = 4000000000ULL;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(f, "/x", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(d);
    H5Sclose(space);
    H5Fclose(f);
  }
  // A file of another program: checked whole in a child process first, which meets the same guard.
  const std::string error = runtime_error_of([&] { H5Reader(file, uhpc::H5Checksums::optional).read_doubles("x"); });
  EXPECT_THAT(error, HasSubstr(file.string() + ": dataset 'x': declares 4000000000 values (32 GB), more than a file of "));
  EXPECT_THAT(error, HasSubstr("bytes can hold: the file is corrupt"));

  const fs::path zeros = dir_ / "zeros.h5";
  const std::vector<double> values(4000000, 0.0);  // 32 MB of zeros, deflated to a few tens of kB
  {
    H5Writer w(zeros, uhpc::H5WriteOptions{9});
    w.write("z", values, {values.size()}, "1");
    w.close();
  }
  EXPECT_LT(fs::file_size(zeros), 32000000u / 100u);
  EXPECT_EQ(H5Reader(zeros).read_doubles("z").values, values);
}

// ---------------------------------------------------------------------------------------------------
// Checksums (hdf5_io.hpp, "Integrity")

std::string file_bytes(const fs::path& path) { return read_text(path); }

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// A file of the format before HDF5 1.8 (the library's defaults: superblock v0, symbol-table groups with
// v1 B-trees, no checksums), as other programs and earlier versions wrote them: /g/x = {1, 2, 3}.
void write_old_format_file(const fs::path& path) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t g = H5Gcreate2(f, "/g", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t n = 3;
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t d = H5Dcreate2(g, "x", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const double values[3] = {1.0, 2.0, 3.0};
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
  H5Dclose(d);
  H5Sclose(space);
  H5Gclose(g);
  H5Fclose(f);
}

// The offset of the root group's v1 B-tree address in its object header's symbol-table message.
std::size_t root_btree_address_offset(const std::string& bytes) {
  std::uint64_t header = 0;
  std::memcpy(&header, bytes.data() + 56 + 8, 8);  // the root entry's object header address
  std::uint16_t messages = 0;
  std::memcpy(&messages, bytes.data() + header + 2, 2);
  std::size_t at = header + 16;
  for (int m = 0; m < messages; ++m) {
    std::uint16_t kind = 0, size = 0;
    std::memcpy(&kind, bytes.data() + at, 2);
    std::memcpy(&size, bytes.data() + at + 2, 2);
    if (kind == 0x11) return at + 8;
    at += 8u + size;
  }
  ADD_FAILURE() << "no symbol-table message";
  return 0;
}

// Every value is checksummed: one byte of one value flipped in the file is a read error naming the file
// and the dataset, not another number. Metadata too: a byte of the superblock flipped is refused on open.
TEST_F(H5Test, WrittenFilesCarryChecksumsThatEveryReadVerifies) {
  const fs::path file = dir_ / "sums.h5";
  std::vector<double> values(1000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1.0 + static_cast<double>(i);
  values[500] = 123456.789;
  {
    H5Writer w(file);
    w.write("group/values", values, "Pa");
    w.write("empty", std::vector<double>{}, "m");
    w.close();
  }
  EXPECT_TRUE(H5Reader(file).checksummed());
  EXPECT_TRUE(H5Reader(file).read_doubles("empty").values.empty());
  const std::string intact = file_bytes(file);
  EXPECT_EQ(intact[8], 3) << "superblock version";

  std::string mutated = intact;
  char pattern[8];
  std::memcpy(pattern, &values[500], 8);
  const std::size_t at = mutated.find(std::string(pattern, 8));
  ASSERT_NE(at, std::string::npos);
  mutated[at + 3] ^= 0x10;  // a different, still finite double
  write_bytes(file, mutated);
  {
    // (Closed before the next open: HDF5 shares one open file between the opens of a process.)
    const H5Reader r(file);
    const std::string error = runtime_error_of([&] { r.read_doubles("group/values"); });
    EXPECT_EQ(error, file.string() + ": dataset 'group/values': cannot read (corrupt storage or checksum mismatch): "
                                     "data error detected by Fletcher32 checksum");
  }

  mutated = intact;
  mutated[30] ^= 0x01;  // the end-of-file address in the superblock (v3: checksummed)
  write_bytes(file, mutated);
  EXPECT_THAT(runtime_error_of([&] { H5Reader bad(file); }), HasSubstr(file.string() + ": cannot open as HDF5"));
}

// The datasets' digest: FNV-1a over 64-bit little-endian words, the tail byte by byte. Values computed
// by hand (Python: h = ((h ^ w) * 0x100000001b3) % 2**64 from 0xcbf29ce484222325).
TEST(Fnv1a64Words, MatchesHandComputedValuesAndCatchesAnyChangeWithinAWord) {
  EXPECT_EQ(uhpc::fnv1a64_words_hex(""), "cbf29ce484222325");
  EXPECT_EQ(uhpc::fnv1a64_words_hex(std::string("\x01\0\0\0\0\0\0\0ab", 10)), "d1139b1867863f8f");
  EXPECT_EQ(uhpc::fnv1a64_words_hex("ab"), uhpc::fnv1a64_hex("ab"));  // no whole word: bytewise FNV-1a
  std::string zeros(64, '\0');
  const std::string intact = uhpc::fnv1a64_words_hex(zeros);
  for (std::size_t word = 0; word < 8; ++word) {
    std::string changed = zeros;
    changed.replace(8 * word, 8, std::string(8, '\xff'));
    EXPECT_NE(uhpc::fnv1a64_words_hex(changed), intact) << word;
  }
}

// Fletcher32 sums 16-bit words modulo 65535 and cannot tell 0x0000 from 0xffff: a zero value overwritten
// with ff x 8 (NaN) passes the library's check (shown with the library directly), and the dataset's own
// digest refuses it.
TEST_F(H5Test, AZeroOverwrittenWithOnesPassesFletcher32AndIsCaughtByTheDigest) {
  const fs::path file = dir_ / "zeros.h5";
  const std::vector<double> values = {1.5, 0.0, 2.5};
  {
    H5Writer w(file);
    w.write("v", values, "1");
    w.close();
  }
  std::string bytes = file_bytes(file);
  std::string pattern(24, '\0');
  std::memcpy(pattern.data(), values.data(), 24);
  const std::size_t at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 8, 8, std::string(8, '\xff'));
  write_bytes(file, bytes);

  double read[3] = {0, 0, 0};
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "/v", H5P_DEFAULT);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, read), 0);
  EXPECT_TRUE(std::isnan(read[1]));
  H5Dclose(d);
  H5Fclose(f);

  EXPECT_EQ(runtime_error_of([&] { H5Reader(file).read_doubles("v"); }),
            file.string() + ": dataset 'v': checksum mismatch: its values are not those written (attribute "
                            "'checksum_fnv1a64_words')");
}

// A file without checksums: refused where they are required (the program's own files read back), read
// after a child process has read it whole where they are optional (files from elsewhere).
TEST_F(H5Test, AFileWithoutChecksumsIsRefusedOrCheckedInAChild) {
  const fs::path file = dir_ / "old.h5";
  write_old_format_file(file);
  EXPECT_THAT(runtime_error_of([&] { H5Reader r(file); }),
              HasSubstr(file.string() + ": carries no checksums (written by an earlier version or by another program)"));
  const H5Reader r(file, uhpc::H5Checksums::optional);
  EXPECT_FALSE(r.checksummed());
  EXPECT_EQ(r.read_doubles("g/x").values, (std::vector<double>{1.0, 2.0, 3.0}));
}

// The corruption that crashes libhdf5 1.10.8 (one bad B-tree address: SIGSEGV in H5Lexists) ends the
// checking child, and the reader reports it naming the file. The crash itself is shown first, in a
// child of the test's own that calls the library directly.
TEST_F(H5Test, CorruptMetadataOfTheOldFormatEndsTheCheckingChildNotTheProcess) {
  const fs::path file = dir_ / "btree.h5";
  write_old_format_file(file);
  std::string bytes = file_bytes(file);
  const std::size_t at = root_btree_address_offset(bytes);
  ASSERT_GT(at, 0u);
  bytes.replace(at, 8, std::string(8, '\xff'));
  write_bytes(file, bytes);

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) H5Lexists(f, "/g", H5P_DEFAULT);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer the SIGSEGV is caught by its handler, which reports it and exits with its
  // exit code instead of dying by the signal.
  const bool crashed = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0);
#else
  const bool crashed = WIFSIGNALED(status);
#endif
  EXPECT_TRUE(crashed) << "the library read this corruption without crashing: the test shows nothing";

  const std::string error = runtime_error_of([&] { H5Reader r(file, uhpc::H5Checksums::optional); });
  // "(signal 11, Segmentation fault)", or under AddressSanitizer "(the checking process ended with exit code 1)".
  EXPECT_EQ(error.rfind(file.string() + ": corrupt HDF5 file: reading it crashed the HDF5 library (", 0), 0u) << error;
  EXPECT_THAT(runtime_error_of([&] { H5Reader r(file); }), HasSubstr(file.string() + ": carries no checksums"));
}

TEST_F(H5Test, AppenderExtendsAnExistingFile) {
  const fs::path file = dir_ / "grow.h5";
  {
    auto a = uhpc::H5Appender::create(file);
    a.write("first", std::vector<double>{1.0}, "s");
    a.close();
  }
  {
    auto a = uhpc::H5Appender::open(file);
    EXPECT_TRUE(a.has("first"));
    a.write("second", std::vector<double>{2.0}, "s");
    a.remove("first");
    a.flush();
    a.close();
  }
  H5Reader r(file);
  EXPECT_FALSE(r.has("first"));
  EXPECT_THAT(r.read_doubles("second").values, ElementsAre(2.0));
  EXPECT_THROW(uhpc::H5Appender::open(dir_ / "absent.h5"), std::runtime_error);
}

// ---------------------------------------------------------------------------------------------------
// XDMF particle fields

namespace {

struct DataItemRef {
  std::string dimensions;
  std::string file;
  std::string dataset;
};

// Every <DataItem Dimensions="..." ...>file.h5:/path</DataItem>, in document order.
std::vector<DataItemRef> data_items(const std::string& xml) {
  static const std::regex item(R"(<DataItem ([^>]*)>([^<:]+):([^<]+)</DataItem>)");
  static const std::regex dims(R"(Dimensions="([^"]*)\")");
  std::vector<DataItemRef> refs;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it) {
    std::smatch d;
    const std::string attributes = (*it)[1];
    EXPECT_TRUE(std::regex_search(attributes, d, dims)) << attributes;
    refs.push_back({d[1], (*it)[2], (*it)[3]});
  }
  return refs;
}

H5Dims parse_dims(const std::string& text) {
  H5Dims dims;
  std::istringstream in(text);
  for (std::size_t d; in >> d;) dims.push_back(d);
  return dims;
}

// Particle i of step s at (i + s, 2i, -i); pressure 100 i + s; velocity (s, i, 1).
std::vector<double> positions(int step, std::size_t n) {
  std::vector<double> p;
  for (std::size_t i = 0; i < n; ++i) {
    p.insert(p.end(), {static_cast<double>(i) + step, 2.0 * static_cast<double>(i), -static_cast<double>(i)});
  }
  return p;
}
std::vector<double> pressure(int step, std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back(100.0 * static_cast<double>(i) + step);
  return v;
}
std::vector<double> velocity(int step, std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) v.insert(v.end(), {static_cast<double>(step), static_cast<double>(i), 1.0});
  return v;
}

void write_cloud_step(uhpc::ParticleFieldWriter& writer, int step, double time_s, std::size_t n = 5) {
  const std::vector<double> x = positions(step, n);
  const std::vector<double> p = pressure(step, n);
  const std::vector<double> v = velocity(step, n);
  writer.write_step(time_s, x, 3, {{"pressure", "Pa", 1, p.data()}, {"velocity", "m/s", 3, v.data()}});
}

}  // namespace

TEST_F(H5Test, XdmfDocumentListsTwoStepsOfAFiveParticleCloud) {
  uhpc::ParticleFieldWriter writer(dir_ / "run", "fields");
  write_cloud_step(writer, 0, 0.0);
  write_cloud_step(writer, 1, 2.5e-6);
  EXPECT_EQ(writer.steps_written(), 2u);

  const std::string xml = read_text(dir_ / "run" / "fields.xdmf");
  EXPECT_THAT(xml, HasSubstr("<?xml version=\"1.0\""));
  EXPECT_THAT(xml, HasSubstr("<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">"));
  EXPECT_EQ(count_of(xml, "GridType=\"Collection\" CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count_of(xml, "GridType=\"Uniform\""), 2u);
  EXPECT_EQ(count_of(xml, "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"5\" NodesPerElement=\"1\"/>"), 2u);
  EXPECT_EQ(count_of(xml, "<Geometry GeometryType=\"XYZ\">"), 2u);
  EXPECT_THAT(xml, HasSubstr("<Time Value=\"0\"/>"));
  EXPECT_THAT(xml, HasSubstr("<Time Value=\"2.5e-06\"/>"));
  EXPECT_LT(xml.find("<Time Value=\"0\"/>"), xml.find("<Time Value=\"2.5e-06\"/>"));
  EXPECT_EQ(count_of(xml, "<Attribute Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Node\">"), 2u);
  EXPECT_EQ(count_of(xml, "<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">"), 2u);
  EXPECT_EQ(count_of(xml, "<Grid "), count_of(xml, "</Grid>"));
  EXPECT_EQ(count_of(xml, "<DataItem "), count_of(xml, "</DataItem>"));

  const std::vector<DataItemRef> refs = data_items(xml);
  ASSERT_EQ(refs.size(), 6u);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"5 3", "/step_000000/position"}, {"5", "/step_000000/pressure"}, {"5 3", "/step_000000/velocity"},
      {"5 3", "/step_000001/position"}, {"5", "/step_000001/pressure"}, {"5 3", "/step_000001/velocity"}};
  for (std::size_t k = 0; k < refs.size(); ++k) {
    EXPECT_EQ(refs[k].file, "fields.h5");  // relative: the pair of files can be moved together
    EXPECT_EQ(refs[k].dimensions, expected[k].first);
    EXPECT_EQ(refs[k].dataset, expected[k].second);
  }
}

TEST_F(H5Test, EveryXdmfReferenceResolvesToTheWrittenData) {
  uhpc::ParticleFieldWriter writer(dir_ / "run", "fields");
  writer.write_provenance(sample_provenance());
  write_cloud_step(writer, 0, 0.0);
  write_cloud_step(writer, 1, 2.5e-6);

  const fs::path xdmf = dir_ / "run" / "fields.xdmf";
  for (const DataItemRef& ref : data_items(read_text(xdmf))) {
    H5Reader r(xdmf.parent_path() / ref.file);
    const uhpc::H5Array<double> a = r.read_doubles(ref.dataset);
    EXPECT_EQ(a.dims, parse_dims(ref.dimensions)) << ref.dataset;

    const int step = ref.dataset.find("step_000001") != std::string::npos ? 1 : 0;
    const std::string name = ref.dataset.substr(ref.dataset.rfind('/') + 1);
    const std::map<std::string, std::pair<std::vector<double>, std::string>> expected = {
        {"position", {positions(step, 5), "m"}},
        {"pressure", {pressure(step, 5), "Pa"}},
        {"velocity", {velocity(step, 5), "m/s"}}};
    ASSERT_EQ(expected.count(name), 1u) << name;
    EXPECT_EQ(a.values, expected.at(name).first) << ref.dataset;
    EXPECT_EQ(r.units(ref.dataset), expected.at(name).second) << ref.dataset;
  }
  H5Reader r(dir_ / "run" / "fields.h5");
  EXPECT_EQ(r.double_attribute("step_000001", "time_s"), 2.5e-6);
  EXPECT_EQ(r.provenance().seed, std::numeric_limits<std::uint64_t>::max());
}

TEST_F(H5Test, XdmfListsOnlyCompleteStepsAfterEachWrite) {
  uhpc::ParticleFieldWriter writer(dir_, "cloud");
  EXPECT_FALSE(fs::exists(dir_ / "cloud.xdmf"));  // no step yet, so no index
  write_cloud_step(writer, 0, 0.0);
  EXPECT_EQ(count_of(read_text(dir_ / "cloud.xdmf"), "GridType=\"Uniform\""), 1u);

  // A step rejected before writing leaves both files as they were.
  const std::vector<double> x = positions(1, 5);
  EXPECT_THROW(writer.write_step(0.0, x, 3, {}), std::invalid_argument);                       // time not increasing
  EXPECT_THROW(writer.write_step(1.0, x, 3, {{"p", "", 1, x.data()}}), std::invalid_argument);  // no units
  EXPECT_THROW(writer.write_step(1.0, x, 3, {{"a/b", "Pa", 1, x.data()}}), std::invalid_argument);
  EXPECT_THROW(writer.write_step(1.0, x, 3, {{"position", "m", 3, x.data()}}), std::invalid_argument);
  EXPECT_THROW(writer.write_step(1.0, x, 4, {}), std::invalid_argument);
  EXPECT_THROW(writer.write_step(1.0, std::vector<double>{}, 3, {}), std::invalid_argument);
  EXPECT_EQ(writer.steps_written(), 1u);
  EXPECT_EQ(count_of(read_text(dir_ / "cloud.xdmf"), "GridType=\"Uniform\""), 1u);
  EXPECT_FALSE(H5Reader(dir_ / "cloud.h5").has("step_000001"));

  write_cloud_step(writer, 1, 1.0);
  EXPECT_EQ(count_of(read_text(dir_ / "cloud.xdmf"), "GridType=\"Uniform\""), 2u);
  EXPECT_FALSE(fs::exists(uhpc::temporary_path_for(dir_ / "cloud.xdmf")));
  // Between steps the .h5 is closed and complete: it can be read while the writer lives.
  EXPECT_THAT(H5Reader(dir_ / "cloud.h5").children(""), ElementsAre("step_000000", "step_000001"));
}

TEST_F(H5Test, NewWriterReplacesAnEarlierRun) {
  {
    uhpc::ParticleFieldWriter first(dir_, "fields");
    write_cloud_step(first, 0, 0.0);
    write_cloud_step(first, 1, 1.0);
  }
  uhpc::ParticleFieldWriter second(dir_, "fields");
  EXPECT_FALSE(fs::exists(dir_ / "fields.xdmf"));
  EXPECT_TRUE(H5Reader(dir_ / "fields.h5").children("").empty());
  write_cloud_step(second, 0, 0.0, 3);
  EXPECT_EQ(count_of(read_text(dir_ / "fields.xdmf"), "GridType=\"Uniform\""), 1u);
  EXPECT_THAT(read_text(dir_ / "fields.xdmf"), HasSubstr("NumberOfElements=\"3\""));
}

TEST_F(H5Test, TwoDimensionalCloudUsesXyGeometryAndTensorTypes) {
  uhpc::ParticleFieldWriter writer(dir_, "micro");
  const std::vector<double> xy = {0, 0, 1, 0, 0, 1, 1, 1, 0.5, 0.5};  // 5 points in 2D
  const std::vector<double> stress6(5 * 6, 1.0);
  const std::vector<double> strain2d(5 * 2, 0.5);
  const std::vector<double> damage(5, 0.25);
  writer.write_step(0.0, xy, 2,
                    {{"stress", "Pa", 6, stress6.data()}, {"strain", "1", 2, strain2d.data()}, {"d+", "1", 1, damage.data()}});

  const std::string xml = read_text(dir_ / "micro.xdmf");
  EXPECT_THAT(xml, HasSubstr("<Geometry GeometryType=\"XY\">"));
  EXPECT_THAT(xml, HasSubstr("AttributeType=\"Tensor6\""));
  EXPECT_THAT(xml, HasSubstr("AttributeType=\"Matrix\""));
  const std::vector<DataItemRef> refs = data_items(xml);
  ASSERT_EQ(refs.size(), 4u);
  EXPECT_EQ(refs[0].dimensions, "5 2");
  EXPECT_EQ(refs[1].dimensions, "5 6");
  EXPECT_EQ(refs[2].dimensions, "5 2");
  EXPECT_EQ(refs[3].dataset, "/step_000000/d+");
  H5Reader r(dir_ / "micro.h5");
  EXPECT_EQ(r.read_doubles(refs[0].dataset).values, xy);
  EXPECT_EQ(r.read_doubles(refs[3].dataset).values, damage);
}

TEST(Xdmf, AttributeTypesAndStepNames) {
  EXPECT_STREQ(uhpc::xdmf_attribute_type(1), "Scalar");
  EXPECT_STREQ(uhpc::xdmf_attribute_type(3), "Vector");
  EXPECT_STREQ(uhpc::xdmf_attribute_type(6), "Tensor6");
  EXPECT_STREQ(uhpc::xdmf_attribute_type(9), "Tensor");
  EXPECT_STREQ(uhpc::xdmf_attribute_type(2), "Matrix");
  EXPECT_EQ(uhpc::ParticleFieldWriter::step_group(10), "step_000010");
  EXPECT_EQ(uhpc::ParticleFieldWriter::step_group(1234567), "step_1234567");
}

TEST(Xdmf, DocumentIsPureAndEscapesNames) {
  uhpc::XdmfStep step;
  step.time_s = 1.0 / 3.0;
  step.group = "step_000000";
  step.count = 2;
  step.attributes.push_back({"d+", 1});
  const std::string xml = uhpc::xdmf_document("a&b.h5", {step});
  EXPECT_THAT(xml, HasSubstr("a&amp;b.h5:/step_000000/position"));
  EXPECT_THAT(xml, HasSubstr("<Time Value=\"0.3333333333333333\"/>"));  // shortest exact form
  EXPECT_THAT(xml, HasSubstr("Name=\"d+\""));
  EXPECT_EQ(count_of(uhpc::xdmf_document("x.h5", {}), "<Grid "), 1u);
}
