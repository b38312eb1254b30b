// Test helper: copies a valid ensemble file and breaks it in one way, to check that uhpc-calibrate
// rejects it with one clear line and exit code 2.
//   calibrate-corrupt-ensemble IN OUT drop DATASET         removes DATASET
//   calibrate-corrupt-ensemble IN OUT nan DATASET ROW COL  sets DATASET[ROW, COL] (a 2D double dataset) to NaN
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "uhpc/hdf5_io.hpp"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s IN OUT drop|nan DATASET [ROW COL]\n", argv[0]);
    return 2;
  }
  const std::string in = argv[1], out = argv[2], mode = argv[3], dataset = argv[4];
  std::filesystem::create_directories(std::filesystem::path(out).parent_path());
  std::filesystem::copy_file(in, out, std::filesystem::copy_options::overwrite_existing);
  uhpc::H5Array<double> values;
  std::string units;
  {
    const uhpc::H5Reader r(out);
    values = r.read_doubles(dataset);
    units = r.units(dataset);
  }
  auto file = uhpc::H5Appender::open(out);
  file.remove(dataset);
  if (mode == "nan" && argc == 7 && values.dims.size() == 2) {
    const std::size_t row = std::stoul(argv[5]), col = std::stoul(argv[6]);
    values.values.at(row * values.dims[1] + col) = std::numeric_limits<double>::quiet_NaN();
    file.write(dataset, values.values, values.dims, units);
  } else if (mode != "drop") {
    std::fprintf(stderr, "unknown mode or arguments\n");
    return 2;
  }
  file.close();
  return 0;
}
