#include "uhpc/hdf5_io.hpp"

#include <hdf5.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <limits>
#include <set>
#include <string_view>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "uhpc/atomic_file.hpp"
#include "uhpc/hash.hpp"

namespace uhpc {
namespace detail {

struct H5FileState {
  hid_t file = H5I_INVALID_HID;
  std::string name;  // the name users know the file by (the target, not the temporary)
  H5WriteOptions options;

  H5FileState() = default;
  H5FileState(const H5FileState&) = delete;
  H5FileState& operator=(const H5FileState&) = delete;
  ~H5FileState() { close_quietly(); }

  void close_quietly() noexcept;
};

}  // namespace detail

namespace {

// The root attribute that marks a file written with checksums (see hdf5_io.hpp); its value names the
// scheme, so that another scheme can be told apart later.
constexpr const char* kChecksumAttribute = "checksums";
constexpr const char* kChecksumScheme = "hdf5-1.10 metadata checksums + fletcher32 datasets";

// After a checksum failure libhdf5 1.10.8 keeps the corrupt entry in its metadata cache, and its exit
// handler then loops "closing" it and prints "HDF5: infinite loop closing library" with a list of ids to
// stderr: noise after the program's one error line. Every file here is closed by its owner (RAII) before
// the process ends, so the handler has nothing to do and is switched off, before the library starts.
const bool kNoHdf5ExitHandler = [] {
  H5dont_atexit();
  return true;
}();

}  // namespace

#if defined(__SANITIZE_ADDRESS__)
// After a checksum failure libhdf5 1.10.8 also loses the corrupt cache entry (one direct leak of a few
// hundred bytes, allocated and dropped inside the library), so under LeakSanitizer every refused corrupt
// file would turn exit 2 into exit 1. The library's own allocations are not ours to fix: they are
// suppressed here, beside the code that reads through it. Handles our code leaves open are not hidden by
// this: without the exit handler they stay reachable from the library's id tables, never a leak report.
extern "C" const char* __lsan_default_suppressions() { return "leak:libhdf5\n"; }
// ... and without the report of the suppressions used, which would follow the program's one error line.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace {

// HDF5 prints its whole error stack to stderr by default. We report errors ourselves (with the
// innermost HDF5 message in the exception), so the printing is switched off while one of our calls
// runs and the caller's setting is restored afterwards: other code in the process keeps its handler.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* out) {
  if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(out) = error->desc;
  return 0;
}

// The most specific message on HDF5's error stack (e.g. "unable to open file: name = ..., errno = 2,
// error message = 'No such file or directory'"). Must be called right after the failing call: the
// next HDF5 call, including a close in a destructor, clears the stack.
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "HDF5 error" : reason;
}

// Owns one HDF5 identifier and closes it with the matching function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) noexcept : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&&) = delete;
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

// "a/b", "/a/b" and "a/b/" all name the same object; "" and "/" name the root (returned as "").
// Empty components and "." or ".." are rejected: HDF5 would read them differently from the user.
std::string normalize(const std::string& name, const std::string& file) {
  const std::size_t first = name.find_first_not_of('/');
  if (first == std::string::npos) return "";
  const std::size_t last = name.find_last_not_of('/');
  std::string path = name.substr(first, last - first + 1);
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t end = std::min(path.find('/', begin), path.size());
    const std::string part = path.substr(begin, end - begin);
    if (part.empty() || part == "." || part == "..") {
      throw std::invalid_argument(file + ": invalid object name '" + name + "'");
    }
    begin = end + 1;
  }
  return path;
}

std::string absolute(const std::string& normalized) { return "/" + normalized; }

// H5Lexists fails, rather than answering false, when a parent is missing: test each level in turn.
bool link_exists(hid_t file, const std::string& normalized) {
  if (normalized.empty()) return true;
  std::size_t end = 0;
  while (end != std::string::npos) {
    end = normalized.find('/', end + 1);
    const std::string prefix = absolute(normalized.substr(0, end));
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

std::string object_label(const std::string& name) { return name.empty() || name == "/" ? "/" : name; }

// "<file>: <kind> '<name>': " - the common head of every message about one object.
std::string prefix(const std::string& file, const char* kind, const std::string& name) {
  return file + ": " + kind + " '" + object_label(name) + "': ";
}

// Opens a dataset or group (any object) by normalized name; throws "not found" naming `kind`.
Handle open_object(const std::string& file_name, hid_t file, const std::string& name, const char* kind) {
  const std::string path = normalize(name, file_name);
  if (!link_exists(file, path)) throw std::runtime_error(prefix(file_name, kind, name) + "not found");
  Handle object(H5Oopen(file, absolute(path).c_str(), H5P_DEFAULT), H5Oclose);
  if (!object) throw std::runtime_error(prefix(file_name, kind, name) + "cannot open: " + hdf5_reason());
  return object;
}

Handle open_dataset(const std::string& file_name, hid_t file, const std::string& name) {
  Handle object = open_object(file_name, file, name, "dataset");
  if (H5Iget_type(object.get()) != H5I_DATASET) {
    throw std::runtime_error(prefix(file_name, "dataset", name) + "not a dataset");
  }
  return object;
}

Handle link_creation_with_parents() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  if (!lcpl || H5Pset_create_intermediate_group(lcpl.get(), 1) < 0) {
    throw std::runtime_error("HDF5: cannot set up group creation: " + hdf5_reason());
  }
  return lcpl;
}

std::size_t element_count(const H5Dims& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) n *= d;
  return n;
}

// Every dataset with values is chunked, for the Fletcher32 filter (a checksum per chunk, verified on
// every read; HDF5 allows filters only on chunked data). Chunks span whole rows and hold about 1 MiB, a
// size that compresses well and still lets a reader fetch a few rows cheaply. Empty datasets are
// compact (a chunk needs an extent of at least 1): their shape sits in the checksummed object header.
Handle dataset_creation(const H5WriteOptions& options, const H5Dims& dims, std::size_t element_size) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!dcpl) throw std::runtime_error("HDF5: cannot create dataset properties: " + hdf5_reason());
  if (element_count(dims) == 0) {
    if (H5Pset_layout(dcpl.get(), H5D_COMPACT) < 0)
      throw std::runtime_error("HDF5: cannot set up a compact dataset: " + hdf5_reason());
    return dcpl;
  }
  std::vector<hsize_t> chunk(dims.begin(), dims.end());
  const std::size_t row_bytes = element_size * element_count(H5Dims(dims.begin() + 1, dims.end()));
  const std::size_t rows = std::max<std::size_t>(1, (std::size_t{1} << 20) / std::max<std::size_t>(1, row_bytes));
  chunk[0] = std::min<hsize_t>(chunk[0], rows);
  if (H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0)
    throw std::runtime_error("HDF5: cannot set up chunked storage: " + hdf5_reason());
  const bool deflate_available = H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0;
  if (options.gzip_level > 0 && deflate_available &&
      (H5Pset_shuffle(dcpl.get()) < 0 || H5Pset_deflate(dcpl.get(), static_cast<unsigned>(options.gzip_level)) < 0)) {
    throw std::runtime_error("HDF5: cannot set up compression: " + hdf5_reason());
  }
  // Last in the pipeline: the checksum covers the bytes as stored and is verified first on reading.
  if (H5Pset_fletcher32(dcpl.get()) < 0) throw std::runtime_error("HDF5: cannot set up checksums: " + hdf5_reason());
  return dcpl;
}

void delete_attribute_if_present(hid_t object, const std::string& name, const std::string& where) {
  const htri_t exists = H5Aexists(object, name.c_str());
  if (exists < 0) throw std::runtime_error(where + "cannot query attribute '" + name + "': " + hdf5_reason());
  if (exists > 0 && H5Adelete(object, name.c_str()) < 0) {
    throw std::runtime_error(where + "cannot replace attribute '" + name + "': " + hdf5_reason());
  }
}

// One value of `type` under `name` on `object`, replacing an existing attribute of that name.
void write_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type, const void* value,
                     const std::string& where) {
  delete_attribute_if_present(object, name, where);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attribute || H5Awrite(attribute.get(), memory_type, value) < 0) {
    throw std::runtime_error(where + "cannot write attribute '" + name + "': " + hdf5_reason());
  }
}

// Strings are stored fixed-length, null-terminated, UTF-8: the simplest form every reader
// (h5py, h5dump, ParaView) understands, with no variable-length memory to free.
void write_string_attribute(hid_t object, const std::string& name, const std::string& value,
                            const std::string& where) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type || H5Tset_size(type.get(), value.size() + 1) < 0 || H5Tset_strpad(type.get(), H5T_STR_NULLTERM) < 0 ||
      H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0) {
    throw std::runtime_error(where + "cannot make a string type: " + hdf5_reason());
  }
  write_attribute(object, name, type.get(), type.get(), value.c_str(), where);
}

Handle open_attribute(hid_t object, const std::string& name, const std::string& where) {
  const htri_t exists = H5Aexists(object, name.c_str());
  if (exists <= 0) throw std::runtime_error(where + "attribute '" + name + "': not found");
  Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attribute) throw std::runtime_error(where + "attribute '" + name + "': cannot open: " + hdf5_reason());
  return attribute;
}

// Reads fixed-length and variable-length strings alike, so files from other tools (h5py writes
// variable-length strings) are read too.
std::string read_string_attribute(hid_t attribute, const std::string& where) {
  Handle type(H5Aget_type(attribute), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) throw std::runtime_error(where + "is not a string");
  Handle space(H5Aget_space(attribute), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) throw std::runtime_error(where + "is not a single string");

  if (H5Tis_variable_str(type.get()) > 0) {
    Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attribute, memory.get(), &text) < 0) throw std::runtime_error(where + "cannot read: " + hdf5_reason());
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  if (size > 0 && H5Aread(attribute, type.get(), value.data()) < 0) {
    throw std::runtime_error(where + "cannot read: " + hdf5_reason());
  }
  value.resize(std::min(size, value.find('\0')));
  if (H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD) value.erase(value.find_last_not_of(' ') + 1);
  return value;
}

template <typename T>
T read_number_attribute(hid_t attribute, hid_t memory_type, bool integers_only, const std::string& where) {
  Handle type(H5Aget_type(attribute), H5Tclose);
  const H5T_class_t kind = H5Tget_class(type.get());
  if (kind != H5T_INTEGER && (integers_only || kind != H5T_FLOAT)) {
    throw std::runtime_error(where + (integers_only ? "is not an integer" : "is not a number"));
  }
  Handle space(H5Aget_space(attribute), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) throw std::runtime_error(where + "is not a single value");
  T value{};
  if (H5Aread(attribute, memory_type, &value) < 0) throw std::runtime_error(where + "cannot read: " + hdf5_reason());
  return value;
}

// A dataset's declared shape is checked against what the file can hold before anything is allocated:
// a file of a few kB that declares 4e9 values (unallocated storage reads as fill values) made a reader
// allocate 32 GB. The bound is deflate's largest compression ratio (1032:1) on the whole file, plus 1 MiB
// for tiny files; HDF5 fill values of unwritten datasets are not data and are not allowed beyond it.
void check_fits_in_file(hid_t file, hssize_t count, std::size_t value_bytes, const std::string& where) {
  constexpr double kMaxCompression = 1032.0;
  hsize_t file_bytes = 0;
  if (H5Fget_filesize(file, &file_bytes) < 0) throw std::runtime_error(where + "cannot read the file's size");
  const double bytes = static_cast<double>(count) * static_cast<double>(value_bytes);
  if (count < 0 || bytes > kMaxCompression * static_cast<double>(file_bytes) + 1048576.0) {
    throw std::runtime_error(where + fmt::format("declares {} values ({:.3g} GB), more than a file of {} bytes can "
                                                 "hold: the file is corrupt",
                                                 count, bytes * 1e-9, file_bytes));
  }
}

// Fletcher32 sums 16-bit words modulo 65535, so it cannot tell a word 0x0000 from 0xffff: eight zero
// bytes of a value overwritten with ff (a zero double become NaN) pass it. Every dataset therefore also
// carries the 64-bit FNV-1a over the 64-bit words of its values as stored (the file type's little-endian
// bytes, so the digest is the same on every machine; words, not bytes: 8x faster, and any change within
// one word is always caught) in the attribute below, inside its checksummed object header.
constexpr const char* kDigestAttribute = "checksum_fnv1a64_words";

// The digest of `count` values of `memory_type` at `data`, taken over their bytes in `file_type`.
std::string values_digest(hid_t memory_type, hid_t file_type, const void* data, std::size_t count,
                          const std::string& where) {
  const std::size_t bytes = count * H5Tget_size(file_type);
  if (H5Tequal(memory_type, file_type) > 0)
    return fnv1a64_words_hex(std::string_view(static_cast<const char*>(data), bytes));
  std::vector<char> converted(count * std::max(H5Tget_size(memory_type), H5Tget_size(file_type)));
  if (count > 0) std::memcpy(converted.data(), data, count * H5Tget_size(memory_type));
  if (count > 0 && H5Tconvert(memory_type, file_type, count, converted.data(), nullptr, H5P_DEFAULT) < 0)
    throw std::runtime_error(where + "cannot convert to its file type: " + hdf5_reason());
  return fnv1a64_words_hex(std::string_view(converted.data(), bytes));
}

// A dataset of a checksummed file is verified twice over: the library checks its Fletcher32 sums while
// reading, and its values as stored must match its digest. A dataset without either was written by
// another program into a file marked as ours. Returns the digest written with the dataset.
std::string written_digest(hid_t dataset, const std::string& where) {
  const htri_t has_digest = H5Aexists(dataset, kDigestAttribute);
  Handle dcpl(H5Dget_create_plist(dataset), H5Pclose);
  unsigned flags = 0;
  std::size_t n = 0;
  const H5D_layout_t layout = dcpl ? H5Pget_layout(dcpl.get()) : H5D_LAYOUT_ERROR;
  const bool fletcher = layout == H5D_CHUNKED && H5Pget_filter_by_id2(dcpl.get(), H5Z_FILTER_FLETCHER32, &flags, &n,
                                                                      nullptr, 0, nullptr, nullptr) >= 0;
  H5Eclear2(H5E_DEFAULT);
  if (has_digest <= 0 || !(fletcher || layout == H5D_COMPACT))
    throw std::runtime_error(where + "carries no checksum in a file marked as checksummed: the file was altered");
  Handle attribute = open_attribute(dataset, kDigestAttribute, where);
  return read_string_attribute(attribute.get(), where + "attribute '" + kDigestAttribute + "': ");
}

// The digest of the values as stored, from `values` read as `memory_type` when that reading is exact
// (the dataset's own type in native byte order: the usual case); otherwise the dataset is read once more
// in that type (an integer dataset read as doubles).
std::string read_digest(hid_t dataset, hid_t file_type, hid_t memory_type, const void* values, std::size_t count,
                        const std::string& where) {
  Handle native(H5Tget_native_type(file_type, H5T_DIR_ASCEND), H5Tclose);
  if (!native) throw std::runtime_error(where + "cannot read its type: " + hdf5_reason());
  if (H5Tequal(native.get(), memory_type) > 0) return values_digest(memory_type, file_type, values, count, where);
  std::vector<char> stored(count * H5Tget_size(native.get()));
  if (!stored.empty() && H5Dread(dataset, native.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, stored.data()) < 0)
    throw std::runtime_error(where + "cannot read (corrupt storage or checksum mismatch): " + hdf5_reason());
  return values_digest(native.get(), file_type, stored.data(), count, where);
}

template <typename T>
H5Array<T> read_array(const std::string& file_name, hid_t file, const std::string& name, hid_t memory_type,
                      bool integers_only, bool checksummed) {
  Handle dataset = open_dataset(file_name, file, name);
  const std::string where = prefix(file_name, "dataset", name);
  Handle type(H5Dget_type(dataset.get()), H5Tclose);
  const H5T_class_t kind = H5Tget_class(type.get());
  if (kind != H5T_INTEGER && (integers_only || kind != H5T_FLOAT)) {
    throw std::runtime_error(where + (integers_only ? "holds no integers" : "holds no numbers"));
  }
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error(where + "cannot read its shape: " + hdf5_reason());
  std::vector<hsize_t> extents(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), extents.data(), nullptr);

  H5Array<T> array;
  array.dims.assign(extents.begin(), extents.end());
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  check_fits_in_file(file, count, sizeof(T), where);
  const std::string expected = checksummed ? written_digest(dataset.get(), where) : std::string();
  array.values.resize(static_cast<std::size_t>(std::max<hssize_t>(count, 0)));
  if (!array.values.empty() &&
      H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, array.values.data()) < 0) {
    // A Fletcher32 mismatch ends here too ("data error detected by Fletcher32 checksum").
    throw std::runtime_error(where + "cannot read (corrupt storage or checksum mismatch): " + hdf5_reason());
  }
  if (checksummed &&
      read_digest(dataset.get(), type.get(), memory_type, array.values.data(), array.values.size(), where) != expected)
    throw std::runtime_error(where + "checksum mismatch: its values are not those written (attribute '" +
                             kDigestAttribute + "')");
  return array;
}

// The names of a group's members, sorted.
std::vector<std::string> member_names(hid_t group, const std::string& where) {
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) throw std::runtime_error(where + "cannot list: " + hdf5_reason());
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (length < 0) throw std::runtime_error(where + "cannot list: " + hdf5_reason());
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    if (H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT) < 0)
      throw std::runtime_error(where + "cannot list: " + hdf5_reason());
    name.resize(static_cast<std::size_t>(length));
    names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

// ---------------------------------------------------------------------------------------------------
// Checking a file without checksums in a child process

// Reads every attribute of `object` (strings as strings, numbers as doubles, anything else as raw bytes).
void read_all_attributes(hid_t file, hid_t object, unsigned long long count, const std::string& where) {
  for (unsigned long long i = 0; i < count; ++i) {
    Handle attribute(H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (!attribute) throw std::runtime_error(where + "attribute " + std::to_string(i) + ": cannot open: " + hdf5_reason());
    const std::string at = where + "attribute " + std::to_string(i) + ": ";
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    Handle space(H5Aget_space(attribute.get()), H5Sclose);
    if (!type || !space) throw std::runtime_error(at + "cannot read its type: " + hdf5_reason());
    const H5T_class_t kind = H5Tget_class(type.get());
    const hssize_t points = H5Sget_simple_extent_npoints(space.get());
    if (kind == H5T_STRING && points == 1) {
      read_string_attribute(attribute.get(), at);
    } else if (kind == H5T_INTEGER || kind == H5T_FLOAT) {
      check_fits_in_file(file, points, sizeof(double), at);
      std::vector<double> values(static_cast<std::size_t>(std::max<hssize_t>(points, 0)));
      if (!values.empty() && H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
        throw std::runtime_error(at + "cannot read: " + hdf5_reason());
    } else if (H5Tdetect_class(type.get(), H5T_VLEN) <= 0 && H5Tis_variable_str(type.get()) <= 0) {
      const std::size_t size = H5Tget_size(type.get());
      check_fits_in_file(file, points, size, at);
      std::vector<unsigned char> bytes(static_cast<std::size_t>(std::max<hssize_t>(points, 0)) * size);
      if (!bytes.empty() && H5Aread(attribute.get(), type.get(), bytes.data()) < 0)
        throw std::runtime_error(at + "cannot read: " + hdf5_reason());
    }
  }
}

// Reads the object at `path` (normalized) the way the readers do (H5Lexists level by level, then open),
// its attributes, and all its values or members, recursively. `seen` holds the objects' addresses:
// a group linked into itself is walked once.
void walk_object(const std::string& file_name, hid_t file, const std::string& path, std::set<haddr_t>& seen) {
  Handle object = open_object(file_name, file, path, "object");
  const std::string where = prefix(file_name, "object", path);
  H5O_info_t info;
  if (H5Oget_info2(object.get(), &info, H5O_INFO_BASIC | H5O_INFO_NUM_ATTRS) < 0)
    throw std::runtime_error(where + "cannot read its header: " + hdf5_reason());
  if (!seen.insert(info.addr).second) return;
  read_all_attributes(file, object.get(), info.num_attrs, where);
  const H5I_type_t type = H5Iget_type(object.get());
  if (type == H5I_GROUP) {
    for (const std::string& name : member_names(object.get(), where))
      walk_object(file_name, file, path.empty() ? name : path + "/" + name, seen);
  } else if (type == H5I_DATASET) {
    Handle data_type(H5Dget_type(object.get()), H5Tclose);
    const H5T_class_t kind = H5Tget_class(data_type.get());
    if (kind == H5T_INTEGER || kind == H5T_FLOAT) {
      read_array<double>(file_name, file, path, H5T_NATIVE_DOUBLE, false, false);
    } else if (H5Tdetect_class(data_type.get(), H5T_VLEN) <= 0 && H5Tis_variable_str(data_type.get()) <= 0) {
      Handle space(H5Dget_space(object.get()), H5Sclose);
      const hssize_t points = H5Sget_simple_extent_npoints(space.get());
      const std::size_t size = H5Tget_size(data_type.get());
      check_fits_in_file(file, points, size, where);
      std::vector<unsigned char> bytes(static_cast<std::size_t>(std::max<hssize_t>(points, 0)) * size);
      if (!bytes.empty() && H5Dread(object.get(), data_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0)
        throw std::runtime_error(where + "cannot read: " + hdf5_reason());
    }
  }
}

// The child's part: "" when the whole file reads, else the first error.
std::string read_whole_file(const std::filesystem::path& path) {
  try {
    QuietErrors quiet;
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file) return path.string() + ": cannot open as HDF5: " + hdf5_reason();
    std::set<haddr_t> seen;
    walk_object(path.string(), file.get(), "", seen);
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

void create_parent_directories(const std::filesystem::path& file) {
  const std::filesystem::path parent = file.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) {
    throw std::runtime_error(file.string() + ": cannot create directory '" + parent.string() + "': " + ec.message());
  }
}

}  // namespace

void detail::H5FileState::close_quietly() noexcept {
  if (file < 0) return;
  QuietErrors quiet;
  H5Fclose(file);
  file = H5I_INVALID_HID;
}

// ---------------------------------------------------------------------------------------------------
// H5Output

H5Output::H5Output() : state_(std::make_unique<detail::H5FileState>()) {}
H5Output::H5Output(H5Output&&) noexcept = default;
H5Output& H5Output::operator=(H5Output&&) noexcept = default;
H5Output::~H5Output() = default;

void H5Output::open_file(const std::filesystem::path& path, bool create, std::string display_name,
                         H5WriteOptions options) {
  if (options.gzip_level < 0 || options.gzip_level > 9) {
    throw std::invalid_argument(display_name + ": gzip level must be in [0, 9], got " +
                                std::to_string(options.gzip_level));
  }
  QuietErrors quiet;
  // With the strong close degree, H5Fclose really closes the file (and reports errors) even if an
  // object was left open, instead of silently deferring the close.
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // The 1.10 file format throughout: superblock v3 and object headers, groups and chunk indices that
  // carry checksums (the format before 1.8 has none; its B-trees, once corrupt, can crash the library).
  if (!fapl || H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0 ||
      H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_V110) < 0) {
    throw std::runtime_error(display_name + ": cannot set up file access: " + hdf5_reason());
  }
#if H5_VERSION_GE(1, 10, 7)
  // An existing file is extended while a viewer (ParaView) may have it open: a reader's lock must
  // not stop a simulation. A new file has no readers, and keeps the default locking.
  if (!create) H5Pset_file_locking(fapl.get(), false, true);
#endif
  const hid_t file = create ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get())
                            : H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get());
  if (file < 0) {
    const std::string what = create ? ": cannot create HDF5 file '" : ": cannot open HDF5 file '";
    throw std::runtime_error(display_name + what + path.string() + "': " + hdf5_reason());
  }
  state_->close_quietly();
  state_->file = file;
  state_->name = std::move(display_name);
  state_->options = options;
  if (create) write_string_attribute(file, kChecksumAttribute, kChecksumScheme, prefix(state_->name, "object", ""));
}

void H5Output::close_file() {
  if (!is_open()) return;
  QuietErrors quiet;
  const herr_t status = H5Fclose(state_->file);
  state_->file = H5I_INVALID_HID;
  if (status < 0) throw std::runtime_error(state_->name + ": cannot finish writing: " + hdf5_reason());
}

void H5Output::flush_file() {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  QuietErrors quiet;
  if (H5Fflush(state_->file, H5F_SCOPE_LOCAL) < 0) {
    throw std::runtime_error(state_->name + ": cannot flush: " + hdf5_reason());
  }
}

void H5Output::close_file_quietly() noexcept {
  if (state_) state_->close_quietly();
}

bool H5Output::is_open() const { return state_ && state_->file >= 0; }

const std::string& H5Output::file_name() const {
  static const std::string none = "(closed HDF5 file)";
  return state_ ? state_->name : none;
}

std::int64_t H5Output::checked_int64(std::uint64_t value) const {
  if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw std::out_of_range(file_name() + ": attribute value " + std::to_string(value) + " does not fit in int64");
  }
  return static_cast<std::int64_t>(value);
}

namespace {

// Everything the write() overloads share: checks, dataset creation, data, and the "units" attribute.
void write_dataset(const detail::H5FileState* state, bool open, const std::string& name, hid_t memory_type,
                   hid_t file_type, std::size_t element_size, const void* data, const H5Dims& dims,
                   const std::string& units) {
  if (!open) throw std::logic_error((state ? state->name : std::string("HDF5 output")) + ": file is closed");
  const std::string& file_name = state->name;
  const std::string where = prefix(file_name, "dataset", name);
  const std::string path = normalize(name, file_name);
  if (path.empty()) throw std::invalid_argument(file_name + ": a dataset needs a name");
  if (units.empty()) throw std::invalid_argument(where + "units must not be empty (\"1\" for dimensionless)");
  if (dims.empty() || dims.size() > H5S_MAX_RANK) {
    throw std::invalid_argument(where + "needs between 1 and " + std::to_string(H5S_MAX_RANK) + " dimensions");
  }
  if (data == nullptr && element_count(dims) > 0) throw std::invalid_argument(where + "no data given");

  QuietErrors quiet;
  if (link_exists(state->file, path)) throw std::invalid_argument(where + "already exists");
  const std::vector<hsize_t> extents(dims.begin(), dims.end());
  Handle space(H5Screate_simple(static_cast<int>(extents.size()), extents.data(), nullptr), H5Sclose);
  if (!space) throw std::runtime_error(where + "cannot make its dataspace: " + hdf5_reason());
  Handle lcpl = link_creation_with_parents();
  Handle dcpl = dataset_creation(state->options, dims, element_size);
  Handle dataset(H5Dcreate2(state->file, absolute(path).c_str(), file_type, space.get(), lcpl.get(), dcpl.get(),
                            H5P_DEFAULT),
                 H5Dclose);
  if (!dataset) throw std::runtime_error(where + "cannot create: " + hdf5_reason());
  if (element_count(dims) > 0 && H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    throw std::runtime_error(where + "cannot write: " + hdf5_reason());
  }
  write_string_attribute(dataset.get(), "units", units, where);
  write_string_attribute(dataset.get(), kDigestAttribute,
                         values_digest(memory_type, file_type, data, element_count(dims), where), where);
}

template <typename T>
const T* checked_data(const std::vector<T>& values, const H5Dims& dims, const std::string& file_name,
                      const std::string& name) {
  if (values.size() != element_count(dims)) {
    std::string shape;
    for (std::size_t d : dims) shape += (shape.empty() ? "" : " x ") + std::to_string(d);
    throw std::invalid_argument(prefix(file_name, "dataset", name) + std::to_string(values.size()) +
                                " values do not fill dims " + shape);
  }
  return values.data();
}

}  // namespace

// The file types are fixed little-endian, so files compare byte for byte across machines; HDF5
// converts from the native memory types.
void H5Output::write(const std::string& name, const double* data, const H5Dims& dims, const std::string& units) {
  write_dataset(state_.get(), is_open(), name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, sizeof(double), data, dims, units);
}
void H5Output::write(const std::string& name, const std::int64_t* data, const H5Dims& dims,
                     const std::string& units) {
  write_dataset(state_.get(), is_open(), name, H5T_NATIVE_INT64, H5T_STD_I64LE, sizeof(std::int64_t), data, dims,
                units);
}
void H5Output::write(const std::string& name, const std::int32_t* data, const H5Dims& dims,
                     const std::string& units) {
  write_dataset(state_.get(), is_open(), name, H5T_NATIVE_INT32, H5T_STD_I32LE, sizeof(std::int32_t), data, dims,
                units);
}
void H5Output::write(const std::string& name, const std::uint8_t* data, const H5Dims& dims,
                     const std::string& units) {
  write_dataset(state_.get(), is_open(), name, H5T_NATIVE_UINT8, H5T_STD_U8LE, sizeof(std::uint8_t), data, dims,
                units);
}

void H5Output::write(const std::string& name, const std::vector<double>& values, const std::string& units) {
  write(name, values.data(), {values.size()}, units);
}
void H5Output::write(const std::string& name, const std::vector<std::int64_t>& values, const std::string& units) {
  write(name, values.data(), {values.size()}, units);
}
void H5Output::write(const std::string& name, const std::vector<std::int32_t>& values, const std::string& units) {
  write(name, values.data(), {values.size()}, units);
}
void H5Output::write(const std::string& name, const std::vector<std::uint8_t>& values, const std::string& units) {
  write(name, values.data(), {values.size()}, units);
}
void H5Output::write(const std::string& name, const std::vector<double>& values, const H5Dims& dims,
                     const std::string& units) {
  write(name, checked_data(values, dims, file_name(), name), dims, units);
}
void H5Output::write(const std::string& name, const std::vector<std::int64_t>& values, const H5Dims& dims,
                     const std::string& units) {
  write(name, checked_data(values, dims, file_name(), name), dims, units);
}

void H5Output::create_group(const std::string& path) {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  const std::string normalized = normalize(path, state_->name);
  QuietErrors quiet;
  if (link_exists(state_->file, normalized)) {
    Handle object = open_object(state_->name, state_->file, path, "group");
    if (H5Iget_type(object.get()) != H5I_GROUP) {
      throw std::invalid_argument(prefix(state_->name, "group", path) + "exists and is not a group");
    }
    return;
  }
  Handle lcpl = link_creation_with_parents();
  Handle group(H5Gcreate2(state_->file, absolute(normalized).c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
               H5Gclose);
  if (!group) throw std::runtime_error(prefix(state_->name, "group", path) + "cannot create: " + hdf5_reason());
}

void H5Output::remove(const std::string& name) {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  const std::string normalized = normalize(name, state_->name);
  if (normalized.empty()) throw std::invalid_argument(state_->name + ": the root group cannot be removed");
  QuietErrors quiet;
  if (!link_exists(state_->file, normalized)) return;
  if (H5Ldelete(state_->file, absolute(normalized).c_str(), H5P_DEFAULT) < 0) {
    throw std::runtime_error(prefix(state_->name, "object", name) + "cannot remove: " + hdf5_reason());
  }
}

bool H5Output::has(const std::string& name) const {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  const std::string normalized = normalize(name, state_->name);
  QuietErrors quiet;
  return link_exists(state_->file, normalized);
}

void H5Output::set_attribute(const std::string& object, const std::string& name, const std::string& value) {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  write_string_attribute(target.get(), name, value, prefix(state_->name, "object", object));
}

void H5Output::set_attribute(const std::string& object, const std::string& name, double value) {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  write_attribute(target.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, prefix(state_->name, "object", object));
}

void H5Output::set_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  if (!is_open()) throw std::logic_error(file_name() + ": file is closed");
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  write_attribute(target.get(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, prefix(state_->name, "object", object));
}

void H5Output::write_provenance(const Provenance& provenance) {
  set_attribute("", "provenance", provenance.to_json().dump());
}

// ---------------------------------------------------------------------------------------------------
// H5Writer

H5Writer::H5Writer(std::filesystem::path target, H5WriteOptions options)
    : target_(std::move(target)), temporary_(temporary_path_for(target_)) {
  create_parent_directories(target_);
  open_file(temporary_, true, target_.string(), options);
}

H5Writer::H5Writer(H5Writer&& other) noexcept
    : H5Output(std::move(other)), target_(std::move(other.target_)), temporary_(std::move(other.temporary_)) {}

H5Writer& H5Writer::operator=(H5Writer&& other) noexcept {
  if (this != &other) {
    discard();
    H5Output::operator=(std::move(other));
    target_ = std::move(other.target_);
    temporary_ = std::move(other.temporary_);
  }
  return *this;
}

H5Writer::~H5Writer() { discard(); }

void H5Writer::discard() noexcept {
  if (!is_open()) return;
  close_file_quietly();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void H5Writer::close() {
  if (!is_open()) throw std::logic_error(target_.string() + ": already closed");
  try {
    close_file();
    sync_to_disk(temporary_);
    commit_temporary(temporary_, target_);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw;
  }
}

// ---------------------------------------------------------------------------------------------------
// H5Appender

H5Appender::H5Appender(const std::filesystem::path& path, bool create, H5WriteOptions options) : path_(path) {
  if (create) create_parent_directories(path_);
  open_file(path_, create, path_.string(), options);
}

H5Appender H5Appender::create(const std::filesystem::path& path, H5WriteOptions options) {
  return H5Appender(path, true, options);
}

H5Appender H5Appender::open(const std::filesystem::path& path, H5WriteOptions options) {
  return H5Appender(path, false, options);
}

void H5Appender::flush() { flush_file(); }

void H5Appender::close() {
  if (!is_open()) throw std::logic_error(path_.string() + ": already closed");
  close_file();
  sync_to_disk(path_);
}

// ---------------------------------------------------------------------------------------------------
// H5Reader

namespace {

// The version of the file's superblock (0..3; -1 when it has no HDF5 signature), read from its bytes
// without the library. It sits at offset 0 or a power of two from 512 (after a user block).
int superblock_version(const std::filesystem::path& path) {
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return -1;
  int version = -1;
  for (long offset = 0; version < 0; offset = offset == 0 ? 512 : offset * 2) {
    char head[9];
    if (std::fseek(f, offset, SEEK_SET) != 0 || std::fread(head, 1, sizeof head, f) != sizeof head) break;
    if (std::memcmp(head, kSignature, sizeof kSignature) == 0) version = static_cast<unsigned char>(head[8]);
  }
  std::fclose(f);
  return version;
}

}  // namespace

void check_hdf5_file_in_child(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error(name + ": cannot read: " + ec.message());
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error(name + ": cannot check the file: pipe: " + std::strerror(errno));
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw std::runtime_error(name + ": cannot check the file: fork: " + std::strerror(errno));
  }
  if (child == 0) {
    // Only HDF5 and this thread run here; _exit skips every handler of the parent's. The verdict goes
    // through the pipe; whatever the library (or a sanitizer) prints while it fails is the child's
    // noise and would break the parent's one error line, so the child's stderr goes nowhere.
    ::close(pipe_fds[0]);
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) ::dup2(devnull, STDERR_FILENO);
    const std::string error = read_whole_file(path);
    write_all(pipe_fds[1], error);
    ::_exit(error.empty() ? 0 : 3);
  }
  ::close(pipe_fds[1]);
  // A corrupt file may also send the library round in circles: the child gets a minute plus a second
  // per 20 MB, far more than a healthy read needs.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60 + bytes / 20000000);
  std::string message;
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{pipe_fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child has finished (or died)
    message.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(pipe_fds[0]);
  if (timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) throw std::runtime_error(name + ": corrupt HDF5 file: reading it did not end in time");
  if (WIFSIGNALED(status)) {
    throw std::runtime_error(fmt::format("{}: corrupt HDF5 file: reading it crashed the HDF5 library (signal {}, {})",
                                         name, WTERMSIG(status), ::strsignal(WTERMSIG(status))));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (!message.empty()) throw std::runtime_error(message);  // the child's own report of what it could not read
  // Ended otherwise without a word: a crash that a handler turned into an exit (AddressSanitizer's).
  throw std::runtime_error(fmt::format("{}: corrupt HDF5 file: reading it crashed the HDF5 library (the checking "
                                       "process ended with exit code {})",
                                       name, WIFEXITED(status) ? WEXITSTATUS(status) : -1));
}

namespace {

hid_t open_for_reading(const std::string& name, const std::filesystem::path& path) {
  QuietErrors quiet;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error(name + ": cannot open as HDF5: " + hdf5_reason());
  return file;
}

// True when the root carries the checksum mark of the scheme this version writes.
bool carries_checksum_mark(const std::string& name, hid_t file) {
  QuietErrors quiet;
  const htri_t exists = H5Aexists(file, kChecksumAttribute);
  if (exists < 0) throw std::runtime_error(name + ": cannot read the root group: " + hdf5_reason());
  if (exists == 0) return false;
  Handle attribute = open_attribute(file, kChecksumAttribute, name + ": ");
  const std::string scheme = read_string_attribute(attribute.get(), name + ": attribute 'checksums': ");
  if (scheme != kChecksumScheme)
    throw std::runtime_error(name + ": attribute 'checksums': unknown scheme '" + scheme + "' (this version knows '" +
                             kChecksumScheme + "')");
  return true;
}

}  // namespace

// A file whose superblock is older than v2 has no metadata checksums and is never one of ours (we write
// v3): when checksums are required it is refused unopened. A file from elsewhere (checksums optional)
// is first read whole by a child process, so that corrupt metadata ends the child, not this process.
H5Reader::H5Reader(const std::filesystem::path& path, H5Checksums checksums)
    : path_(path), state_(std::make_unique<detail::H5FileState>()) {
  state_->name = path_.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path_, ec)) throw std::runtime_error(state_->name + ": no such file");
  const std::string no_checksums =
      ": carries no checksums (written by an earlier version or by another program), so it cannot be verified; "
      "this file is only read with checksums";
  if (checksums == H5Checksums::required) {
    const int version = superblock_version(path_);
    if (version >= 0 && version < 2)
      throw std::runtime_error(state_->name + no_checksums + " (HDF5 superblock version " + std::to_string(version) + ")");
  } else {
    check_hdf5_file_in_child(path_);
  }
  state_->file = open_for_reading(state_->name, path_);
  checksummed_ = carries_checksum_mark(state_->name, state_->file);
  if (!checksummed_ && checksums == H5Checksums::required) throw std::runtime_error(state_->name + no_checksums);
}

H5Reader::H5Reader(H5Reader&&) noexcept = default;
H5Reader& H5Reader::operator=(H5Reader&&) noexcept = default;
H5Reader::~H5Reader() = default;

bool H5Reader::has(const std::string& name) const {
  const std::string normalized = normalize(name, state_->name);
  QuietErrors quiet;
  return link_exists(state_->file, normalized);
}

std::vector<std::string> H5Reader::children(const std::string& group) const {
  QuietErrors quiet;
  Handle object = open_object(state_->name, state_->file, group, "group");
  const std::string where = prefix(state_->name, "group", group);
  if (H5Iget_type(object.get()) != H5I_GROUP) throw std::runtime_error(where + "not a group");
  return member_names(object.get(), where);
}

H5Dims H5Reader::dims(const std::string& dataset) const {
  QuietErrors quiet;
  Handle object = open_dataset(state_->name, state_->file, dataset);
  Handle space(H5Dget_space(object.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error(prefix(state_->name, "dataset", dataset) + "cannot read its shape");
  std::vector<hsize_t> extents(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), extents.data(), nullptr);
  return H5Dims(extents.begin(), extents.end());
}

H5Array<double> H5Reader::read_doubles(const std::string& dataset) const {
  QuietErrors quiet;
  return read_array<double>(state_->name, state_->file, dataset, H5T_NATIVE_DOUBLE, false, checksummed_);
}

H5Array<std::uint8_t> H5Reader::read_bytes(const std::string& dataset) const {
  QuietErrors quiet;
  return read_array<std::uint8_t>(state_->name, state_->file, dataset, H5T_NATIVE_UINT8, true, checksummed_);
}

H5Array<std::int64_t> H5Reader::read_int64(const std::string& dataset) const {
  QuietErrors quiet;
  return read_array<std::int64_t>(state_->name, state_->file, dataset, H5T_NATIVE_INT64, true, checksummed_);
}

std::string H5Reader::units(const std::string& dataset) const {
  QuietErrors quiet;
  Handle object = open_dataset(state_->name, state_->file, dataset);
  const std::string where = prefix(state_->name, "dataset", dataset);
  if (H5Aexists(object.get(), "units") <= 0) throw std::runtime_error(where + "no 'units' attribute");
  Handle attribute = open_attribute(object.get(), "units", where);
  return read_string_attribute(attribute.get(), where + "attribute 'units': ");
}

bool H5Reader::has_attribute(const std::string& object, const std::string& name) const {
  QuietErrors quiet;
  if (!link_exists(state_->file, normalize(object, state_->name))) return false;
  Handle target = open_object(state_->name, state_->file, object, "object");
  return H5Aexists(target.get(), name.c_str()) > 0;
}

std::string H5Reader::string_attribute(const std::string& object, const std::string& name) const {
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  const std::string where = prefix(state_->name, "object", object);
  Handle attribute = open_attribute(target.get(), name, where);
  return read_string_attribute(attribute.get(), where + "attribute '" + name + "': ");
}

double H5Reader::double_attribute(const std::string& object, const std::string& name) const {
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  const std::string where = prefix(state_->name, "object", object);
  Handle attribute = open_attribute(target.get(), name, where);
  return read_number_attribute<double>(attribute.get(), H5T_NATIVE_DOUBLE, false,
                                       where + "attribute '" + name + "': ");
}

std::int64_t H5Reader::int64_attribute(const std::string& object, const std::string& name) const {
  QuietErrors quiet;
  Handle target = open_object(state_->name, state_->file, object, "object");
  const std::string where = prefix(state_->name, "object", object);
  Handle attribute = open_attribute(target.get(), name, where);
  return read_number_attribute<std::int64_t>(attribute.get(), H5T_NATIVE_INT64, true,
                                             where + "attribute '" + name + "': ");
}

Provenance H5Reader::provenance() const {
  const std::string text = string_attribute("", "provenance");
  const std::string where = state_->name + ": attribute 'provenance': ";
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw std::runtime_error(where + "not valid JSON");
  try {
    return Provenance::from_json(j);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(where + e.what());
  }
}

}  // namespace uhpc
