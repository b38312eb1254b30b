#pragma once
// Particle fields over time for ParaView: "<dir>/<basename>.h5" holds the data, "<dir>/<basename>.xdmf"
// (XDMF 3) describes it: a Temporal collection of Uniform grids, one per output step, each with a
// Polyvertex topology over the N particles, XYZ (or XY) geometry and node-centred attributes, all
// pointing into the .h5 by relative file name (the pair can be moved together).
//
// Layout of the .h5, one group per step (steps numbered 0, 1, 2, ... in writing order):
//   /step_000010                attribute "time_s" (double)
//   /step_000010/position       N x dim, units "m"
//   /step_000010/<field>        N (scalar) or N x components, units as given
//   /                           attribute "provenance" (JSON) if write_provenance() was called
//
// Crash safety. A run that dies must keep the steps it finished, so the .h5 cannot be a temporary
// renamed at the end. Instead:
//   * The .h5 is opened, extended by one step and closed again in every write_step(); a closed HDF5
//     file is complete and consistent, and between steps no HDF5 handle is open, so a crash in the
//     solver (or a kill) between outputs cannot damage it, and ParaView can read it during the run.
//     Only a crash inside write_step() itself can leave the file damaged.
//   * After the step's data is closed and flushed to disk (fsync), the .xdmf is rewritten
//     atomically (temporary + rename), listing exactly the complete steps. A step that failed half
//     way is never listed; its partial group is removed when the step is written again.
//   * The constructor removes a stale .xdmf from an earlier run before truncating the .h5, so the
//     .xdmf never describes another run's data. The .xdmf exists once the first step is complete.
// Opening and closing the file per step costs milliseconds, negligible next to a solver step.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "uhpc/hdf5_io.hpp"
#include "uhpc/provenance.hpp"

namespace uhpc {

// One per-particle field of a step. `data` holds count x components doubles, row-major, and only
// needs to stay valid during the write_step() call (nothing is kept).
struct ParticleField {
  std::string name;    // dataset and ParaView array name: letters, digits, '_', '-', '+', '.' ("d+")
  std::string units;   // SI, "1" for dimensionless; never empty
  int components = 1;  // 1 Scalar, 3 Vector, 6 Tensor6, 9 Tensor; any other count is written as Matrix
  const double* data = nullptr;
};
// Tensor6 is XDMF's symmetric tensor in the order xx, xy, xz, yy, yz, zz (what ParaView expands to
// the full 3 x 3 tensor); convert from Voigt order (xx, yy, zz, yz, xz, xy) before writing.

// The XDMF attribute type for a component count: "Scalar", "Vector", "Tensor6", "Tensor" or "Matrix".
const char* xdmf_attribute_type(int components);

// What the .xdmf records about one step; enough to write its grid without reading the .h5.
struct XdmfStep {
  struct Attribute {
    std::string name;
    int components = 1;
  };
  double time_s = 0.0;
  std::string group;  // e.g. "step_000010"
  std::size_t count = 0;
  int dim = 3;  // 2: XY geometry, 3: XYZ
  std::vector<Attribute> attributes;
};

// The complete .xdmf document for `steps`, with data items "<h5_file_name>:/<group>/<dataset>".
// Pure (no I/O): the format can be checked without files.
std::string xdmf_document(const std::string& h5_file_name, const std::vector<XdmfStep>& steps);

class ParticleFieldWriter {
 public:
  // Creates `dir` if needed, removes an old "<basename>.xdmf" and creates an empty "<basename>.h5".
  // `basename` may use letters, digits, '_', '-', '+', '.'.
  explicit ParticleFieldWriter(std::filesystem::path dir, std::string basename = "fields",
                               H5WriteOptions options = {});
  // Goes on with the output of an interrupted run: keeps `steps` (what a checkpoint recorded of the
  // existing "<basename>.h5"), removes any later step group the run wrote after it, and rewrites the
  // .xdmf. The kept steps' values are read once, so that their checksums are verified (hdf5_io.hpp).
  // Throws std::runtime_error naming the file when the .h5 lacks one of `steps`, carries no checksums
  // or fails them.
  ParticleFieldWriter(std::filesystem::path dir, std::string basename, std::vector<XdmfStep> steps,
                      H5WriteOptions options = {});

  // Appends one step: `count` particles (count >= 1) with `dim` (2 or 3) coordinates each in
  // `positions` (count x dim, row-major, metres), plus `fields`. Times must increase strictly.
  // Bad arguments throw std::invalid_argument before anything is written; I/O errors throw
  // std::runtime_error, and the files then still describe the steps completed before.
  void write_step(double time_s, std::size_t count, int dim, const double* positions,
                  const std::vector<ParticleField>& fields);
  // Same, with count = positions.size() / dim.
  void write_step(double time_s, const std::vector<double>& positions, int dim,
                  const std::vector<ParticleField>& fields);

  // Stores the provenance JSON as the root attribute "provenance" of the .h5 (replacing an earlier one).
  void write_provenance(const Provenance& provenance);

  std::size_t steps_written() const { return steps_.size(); }
  const std::vector<XdmfStep>& steps() const { return steps_; }
  const std::filesystem::path& h5_path() const { return h5_path_; }
  const std::filesystem::path& xdmf_path() const { return xdmf_path_; }

  // The group name of step `index`: "step_" and six digits (more when index >= 10^6).
  static std::string step_group(std::size_t index);

 private:
  void check_step(double time_s, std::size_t count, int dim, const double* positions,
                  const std::vector<ParticleField>& fields) const;
  void append_to_h5(const XdmfStep& step, const double* positions, const std::vector<ParticleField>& fields);

  std::filesystem::path h5_path_;
  std::filesystem::path xdmf_path_;
  H5WriteOptions options_;
  std::vector<XdmfStep> steps_;
};

}  // namespace uhpc
