#pragma once
// A small RAII layer over the HDF5 C API for result files. Every dataset carries a string attribute
// "units" (SI, "1" for dimensionless), so a file read years later still says what its numbers are.
//
//   H5Writer w(dir / "curves.h5");          // writes "<dir>/.curves.h5.tmp.<pid>"
//   w.write("size_0.01/strain", strain, "1");
//   w.write("size_0.01/stress", stress.data(), {n_steps, n_cells}, "Pa");
//   w.write_provenance(Provenance::make("uhpc-micro run", cfg.hash()));
//   w.close();                              // renames the finished file onto curves.h5
//
//   H5Reader r(dir / "curves.h5");
//   H5Array<double> s = r.read_doubles("size_0.01/stress");   // s.values, s.dims
//
// Names are paths relative to the root ("a/b/c" or "/a/b/c"); the root itself is "" or "/".
// Arrays are row-major (C order) with dims outermost first, e.g. {n_particles, 3}.
// Errors: std::invalid_argument for programming errors (empty units, dims not matching the data,
// a dataset written twice), std::runtime_error naming the file and the object for everything the
// file or the library reports ("<file>: dataset '<name>': not found"). The HDF5 library's own error
// printing is suppressed during these calls; its innermost message is put into the exception.
// Not thread-safe: use one object from one thread (the serial HDF5 library is not thread-safe).
//
// Integrity (docs/architecture.md, section 2.7): every file written here carries checksums that every
// read verifies. The file format is pinned to HDF5 1.10's (superblock v3, object headers, groups and
// chunk indices with Jenkins checksums over all metadata, attributes included), every dataset with
// values is chunked with the Fletcher32 filter (empty ones are compact: their shape is in the
// checksummed object header) and carries the attribute "checksum_fnv1a64_words", a 64-bit FNV-1a over
// the words of its values as stored (Fletcher32 cannot tell a 16-bit word 0x0000 from 0xffff), and the root attribute
// "checksums" marks the file as such. A mismatch is a std::runtime_error naming the file. Files without the mark (written before, or by another
// program) are read only when the reader allows it (H5Checksums::optional), and only after a forked
// child process has read every object of the file: corrupt metadata of the older formats can crash
// libhdf5 (a SIGSEGV in H5Lexists for one bad B-tree address), which then ends the child, not the
// program, and becomes a std::runtime_error naming the file.
// <hdf5.h> stays out of this header on purpose: users of the library do not need HDF5 to compile.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "uhpc/provenance.hpp"

namespace uhpc {

// Extents of an array, outermost first.
using H5Dims = std::vector<std::size_t>;

// A dataset read back: the values in row-major order and their extents (empty dims for a scalar).
template <typename T>
struct H5Array {
  std::vector<T> values;
  H5Dims dims;
};

struct H5WriteOptions {
  // 0: uncompressed (default: fastest). 1..9: shuffle + gzip at that level (smaller files for smooth
  // fields). Either way the datasets are chunked and checksummed (Fletcher32).
  int gzip_level = 0;
};

// Whether a reader accepts a file that carries no checksums (no root attribute "checksums": written by
// an earlier version or another program). A file that carries them is verified whatever this says.
enum class H5Checksums {
  required,  // our own files read back (checkpoints, fields appended on restart): refused without
  optional,  // files from elsewhere (a user's ensemble.h5, archived cells): checked in a child process
};

namespace detail {
struct H5FileState;  // the open file id and its name for messages; defined in hdf5_io.cpp
}

// Writing datasets and attributes into an open file; shared by H5Writer (a new file committed at
// the end) and H5Appender (an existing file extended in place). Not usable on its own.
class H5Output {
 public:
  // `data` holds product(dims) values, row-major. `units` must not be empty. Missing parent groups
  // are created. Writing a name that already exists is an error.
  void write(const std::string& name, const double* data, const H5Dims& dims, const std::string& units);
  void write(const std::string& name, const std::int64_t* data, const H5Dims& dims, const std::string& units);
  void write(const std::string& name, const std::int32_t* data, const H5Dims& dims, const std::string& units);
  void write(const std::string& name, const std::uint8_t* data, const H5Dims& dims, const std::string& units);

  // 1D datasets of the vector's length.
  void write(const std::string& name, const std::vector<double>& values, const std::string& units);
  void write(const std::string& name, const std::vector<std::int64_t>& values, const std::string& units);
  void write(const std::string& name, const std::vector<std::int32_t>& values, const std::string& units);
  void write(const std::string& name, const std::vector<std::uint8_t>& values, const std::string& units);
  // Any shape; the vector's size must equal product(dims).
  void write(const std::string& name, const std::vector<double>& values, const H5Dims& dims,
             const std::string& units);
  void write(const std::string& name, const std::vector<std::int64_t>& values, const H5Dims& dims,
             const std::string& units);

  // Creates the group and any missing parents; does nothing if the group exists.
  void create_group(const std::string& path);
  // Removes a dataset or group (with its contents) if present. The space is not reclaimed in the file.
  void remove(const std::string& name);
  // True if a dataset or group of that name exists.
  bool has(const std::string& name) const;

  // Scalar attributes on an existing group or dataset ("" or "/" for the root). Setting an existing
  // attribute replaces it.
  void set_attribute(const std::string& object, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object, const std::string& name, double value);
  void set_attribute(const std::string& object, const std::string& name, std::int64_t value);
  // Other integer types (int, unsigned, ...) are stored as int64; values that do not fit throw.
  template <typename T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool> &&
                                             !std::is_same_v<T, std::int64_t>,
                                         int> = 0>
  void set_attribute(const std::string& object, const std::string& name, T value) {
    if constexpr (std::is_signed_v<T>) {
      set_attribute(object, name, static_cast<std::int64_t>(value));
    } else {
      set_attribute(object, name, checked_int64(static_cast<std::uint64_t>(value)));
    }
  }

  // The provenance JSON as the root string attribute "provenance".
  void write_provenance(const Provenance& provenance);

  // The name used in messages (the final file name, not a temporary one).
  const std::string& file_name() const;
  bool is_open() const;

 protected:
  H5Output();
  H5Output(H5Output&&) noexcept;
  H5Output& operator=(H5Output&&) noexcept;
  ~H5Output();  // closes the file without checking; derived classes decide what a close means

  // Opens `path` (creating or truncating it when `create`), naming it `display_name` in messages.
  void open_file(const std::filesystem::path& path, bool create, std::string display_name, H5WriteOptions options);
  // Closes the file, throwing std::runtime_error if HDF5 cannot finish writing it.
  void close_file();
  // Writes buffered data and metadata to the operating system.
  void flush_file();
  // Closes without reporting errors (for destructors and error paths).
  void close_file_quietly() noexcept;

 private:
  std::int64_t checked_int64(std::uint64_t value) const;  // throws std::out_of_range above 2^63-1
  std::unique_ptr<detail::H5FileState> state_;
};

// A new result file. It is built under temporary_path_for(target) and appears under its real name
// only in close(); a writer destroyed without close() (an exception, a failed run) deletes the
// temporary, so a half-written result never carries the real name.
class H5Writer : public H5Output {
 public:
  explicit H5Writer(std::filesystem::path target, H5WriteOptions options = {});
  H5Writer(H5Writer&& other) noexcept;
  H5Writer& operator=(H5Writer&& other) noexcept;
  ~H5Writer();

  // Finishes the file, flushes it to disk and renames it onto the target. Further writes throw.
  void close();
  const std::filesystem::path& target() const { return target_; }

 private:
  void discard() noexcept;
  std::filesystem::path target_;
  std::filesystem::path temporary_;
};

// An HDF5 file modified in place, for outputs that grow during a run (see ParticleFieldWriter).
// Whatever was written before a crash inside an append may be lost, so keep appends short and close
// the file between them: a closed HDF5 file is complete and consistent.
class H5Appender : public H5Output {
 public:
  // Creates `path` (truncating an existing file) and its parent directories.
  static H5Appender create(const std::filesystem::path& path, H5WriteOptions options = {});
  // Opens an existing file for reading and writing.
  static H5Appender open(const std::filesystem::path& path, H5WriteOptions options = {});

  H5Appender(H5Appender&&) noexcept = default;
  H5Appender& operator=(H5Appender&&) noexcept = default;
  ~H5Appender() = default;  // closes quietly; call close() to learn about errors

  // Writes everything to the operating system; the file is then readable as it stands.
  void flush();
  // Closes the file and flushes it to disk (fsync).
  void close();
  const std::filesystem::path& path() const { return path_; }

 private:
  H5Appender(const std::filesystem::path& path, bool create, H5WriteOptions options);
  std::filesystem::path path_;
};

// Read-only access to a result file.
class H5Reader {
 public:
  // Throws std::runtime_error naming the file when it is missing, not HDF5, fails its checksums, carries
  // none and `checksums` is required, or (without them) cannot be read whole by the checking child.
  explicit H5Reader(const std::filesystem::path& path, H5Checksums checksums = H5Checksums::required);
  H5Reader(H5Reader&&) noexcept;
  H5Reader& operator=(H5Reader&&) noexcept;
  ~H5Reader();

  // True if a dataset or group of that name exists.
  bool has(const std::string& name) const;
  // Names of the members of a group, sorted ("" for the root).
  std::vector<std::string> children(const std::string& group) const;

  H5Dims dims(const std::string& dataset) const;
  // Floating-point or integer datasets, converted to double.
  H5Array<double> read_doubles(const std::string& dataset) const;
  // Integer datasets only (a floating-point dataset throws rather than truncating).
  H5Array<std::int64_t> read_int64(const std::string& dataset) const;
  // An integer dataset as bytes (values outside 0..255 are a conversion error).
  H5Array<std::uint8_t> read_bytes(const std::string& dataset) const;
  // The dataset's "units" attribute; throws if it is missing.
  std::string units(const std::string& dataset) const;

  bool has_attribute(const std::string& object, const std::string& name) const;
  std::string string_attribute(const std::string& object, const std::string& name) const;
  double double_attribute(const std::string& object, const std::string& name) const;
  std::int64_t int64_attribute(const std::string& object, const std::string& name) const;
  // The root attribute "provenance", parsed and validated.
  Provenance provenance() const;

  const std::filesystem::path& path() const { return path_; }
  // True when the file carries checksums (the root attribute "checksums"), all verified on reading.
  bool checksummed() const { return checksummed_; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<detail::H5FileState> state_;
  bool checksummed_ = false;
};

// Opens `path` in a forked child process and reads every group, dataset and attribute in it; throws
// std::runtime_error naming the file when that fails or the child dies (a signal, or no end within a
// time proportional to the file's size). The parent process never parses the file.
void check_hdf5_file_in_child(const std::filesystem::path& path);

}  // namespace uhpc
