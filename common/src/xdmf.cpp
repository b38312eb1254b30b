#include "uhpc/xdmf.hpp"

#include <cmath>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "uhpc/atomic_file.hpp"

namespace uhpc {
namespace {

// Names end up in HDF5 paths and in "file.h5:/group/name" references, where '/', ':' or spaces
// would be misread; a conservative character set keeps every reader happy.
bool is_safe_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '+' || c == '.';
    if (!ok) return false;
  }
  return name != "." && name != "..";
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// A reference to one float64 dataset: dims "N" for one component, "N C" otherwise.
std::string data_item(const std::string& h5_file, const std::string& group, const std::string& dataset,
                      std::size_t count, int components, const char* indent) {
  const std::string dims = components == 1 ? fmt::format("{}", count) : fmt::format("{} {}", count, components);
  return fmt::format("{}<DataItem DataType=\"Float\" Precision=\"8\" Format=\"HDF\" Dimensions=\"{}\">{}:/{}/{}</DataItem>\n",
                     indent, dims, xml_escaped(h5_file), xml_escaped(group), xml_escaped(dataset));
}

std::string grid(const std::string& h5_file, const XdmfStep& step) {
  std::string out;
  out += fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n", xml_escaped(step.group));
  // "{}" prints the shortest text that reads back as the same double.
  out += fmt::format("        <Time Value=\"{}\"/>\n", step.time_s);
  out += fmt::format("        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n",
                     step.count);
  out += fmt::format("        <Geometry GeometryType=\"{}\">\n", step.dim == 2 ? "XY" : "XYZ");
  out += data_item(h5_file, step.group, "position", step.count, step.dim, "          ");
  out += "        </Geometry>\n";
  for (const XdmfStep::Attribute& a : step.attributes) {
    out += fmt::format("        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n", xml_escaped(a.name),
                       xdmf_attribute_type(a.components));
    out += data_item(h5_file, step.group, a.name, step.count, a.components, "          ");
    out += "        </Attribute>\n";
  }
  out += "      </Grid>\n";
  return out;
}

}  // namespace

const char* xdmf_attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

std::string xdmf_document(const std::string& h5_file_name, const std::vector<XdmfStep>& steps) {
  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfStep& step : steps) out += grid(h5_file_name, step);
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

std::string ParticleFieldWriter::step_group(std::size_t index) { return fmt::format("step_{:06d}", index); }

ParticleFieldWriter::ParticleFieldWriter(std::filesystem::path dir, std::string basename, H5WriteOptions options)
    : h5_path_(dir / (basename + ".h5")), xdmf_path_(dir / (basename + ".xdmf")), options_(options) {
  if (!is_safe_name(basename)) {
    throw std::invalid_argument("particle field output: invalid base name '" + basename +
                                "' (use letters, digits, '_', '-', '+', '.')");
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create directory: " + ec.message());
  // The stale index goes first: at no moment may an .xdmf point into a truncated or foreign .h5.
  std::filesystem::remove(xdmf_path_, ec);
  if (ec) throw std::runtime_error(xdmf_path_.string() + ": cannot remove the previous run's file: " + ec.message());
  H5Appender::create(h5_path_, options_).close();
}

ParticleFieldWriter::ParticleFieldWriter(std::filesystem::path dir, std::string basename, std::vector<XdmfStep> steps,
                                         H5WriteOptions options)
    : h5_path_(dir / (basename + ".h5")), xdmf_path_(dir / (basename + ".xdmf")), options_(options),
      steps_(std::move(steps)) {
  std::set<std::string> kept;
  for (const XdmfStep& s : steps_) kept.insert(s.group);
  std::vector<std::string> later;
  {
    const H5Reader h5(h5_path_, H5Checksums::required);
    for (const XdmfStep& s : steps_) {
      if (!h5.has(s.group)) throw std::runtime_error(h5_path_.string() + ": step group '" + s.group + "' is missing");
      for (const std::string& dataset : h5.children(s.group)) h5.read_doubles(s.group + "/" + dataset);
    }
    for (const std::string& group : h5.children(""))
      if (group.rfind("step_", 0) == 0 && kept.count(group) == 0) later.push_back(group);
  }
  if (!later.empty()) {
    H5Appender h5 = H5Appender::open(h5_path_, options_);
    for (const std::string& group : later) h5.remove(group);
    h5.close();
  }
  write_text_atomic(xdmf_path_, xdmf_document(h5_path_.filename().string(), steps_));
}

void ParticleFieldWriter::check_step(double time_s, std::size_t count, int dim, const double* positions,
                                     const std::vector<ParticleField>& fields) const {
  const std::string where = h5_path_.string() + ": step " + std::to_string(steps_.size()) + ": ";
  if (!std::isfinite(time_s)) throw std::invalid_argument(where + "time is not finite");
  if (!steps_.empty() && !(time_s > steps_.back().time_s)) {
    throw std::invalid_argument(where + fmt::format("time {} s does not follow the previous step's {} s", time_s,
                                                    steps_.back().time_s));
  }
  if (count == 0) throw std::invalid_argument(where + "no particles");
  if (dim != 2 && dim != 3) throw std::invalid_argument(where + "positions must have 2 or 3 coordinates");
  if (positions == nullptr) throw std::invalid_argument(where + "no positions given");
  std::set<std::string> names;
  for (const ParticleField& f : fields) {
    const std::string at = where + "field '" + f.name + "': ";
    if (!is_safe_name(f.name)) throw std::invalid_argument(at + "invalid name (use letters, digits, '_', '-', '+', '.')");
    if (f.name == "position") throw std::invalid_argument(at + "the name is reserved for the geometry");
    if (!names.insert(f.name).second) throw std::invalid_argument(at + "given twice");
    if (f.units.empty()) throw std::invalid_argument(at + "units must not be empty (\"1\" for dimensionless)");
    if (f.components < 1) throw std::invalid_argument(at + "needs at least one component");
    if (f.data == nullptr) throw std::invalid_argument(at + "no data given");
  }
}

void ParticleFieldWriter::append_to_h5(const XdmfStep& step, const double* positions,
                                       const std::vector<ParticleField>& fields) {
  H5Appender h5 = H5Appender::open(h5_path_, options_);
  h5.remove(step.group);  // what an earlier, failed attempt at this step may have left
  h5.create_group(step.group);
  h5.set_attribute(step.group, "time_s", step.time_s);
  h5.write(step.group + "/position", positions, {step.count, static_cast<std::size_t>(step.dim)}, "m");
  for (const ParticleField& f : fields) {
    const H5Dims dims = f.components == 1 ? H5Dims{step.count} : H5Dims{step.count, static_cast<std::size_t>(f.components)};
    h5.write(step.group + "/" + f.name, f.data, dims, f.units);
  }
  h5.close();  // complete, consistent and on disk before the index mentions it
}

void ParticleFieldWriter::write_step(double time_s, std::size_t count, int dim, const double* positions,
                                     const std::vector<ParticleField>& fields) {
  check_step(time_s, count, dim, positions, fields);
  XdmfStep step;
  step.time_s = time_s;
  step.group = step_group(steps_.size());
  step.count = count;
  step.dim = dim;
  for (const ParticleField& f : fields) step.attributes.push_back({f.name, f.components});

  append_to_h5(step, positions, fields);
  steps_.push_back(std::move(step));
  // Should this fail, the step stays recorded: the next successful write lists it again.
  write_text_atomic(xdmf_path_, xdmf_document(h5_path_.filename().string(), steps_));
}

void ParticleFieldWriter::write_step(double time_s, const std::vector<double>& positions, int dim,
                                     const std::vector<ParticleField>& fields) {
  if (dim != 2 && dim != 3) {
    throw std::invalid_argument(h5_path_.string() + ": positions must have 2 or 3 coordinates");
  }
  if (positions.size() % static_cast<std::size_t>(dim) != 0) {
    throw std::invalid_argument(h5_path_.string() + fmt::format(": {} position values do not make whole {}D points",
                                                                positions.size(), dim));
  }
  write_step(time_s, positions.size() / static_cast<std::size_t>(dim), dim, positions.data(), fields);
}

void ParticleFieldWriter::write_provenance(const Provenance& provenance) {
  H5Appender h5 = H5Appender::open(h5_path_, options_);
  h5.write_provenance(provenance);
  h5.close();
}

}  // namespace uhpc
