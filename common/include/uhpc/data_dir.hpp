#pragma once
// Where the shipped data (the project's data/ directory: the paper's tables, the default configs) is
// found by a program that needs it without being told, so that neither a build tree nor an installed
// copy carries an absolute path of the machine it was built on:
//   1. $UHPC_DATA_DIR, when set (it must then be a directory);
//   2. <dir of the executable>/../share/uhpc_multiscale/data: the installed layout (<prefix>/bin and
//      <prefix>/share), and the build tree's (CMake links <build>/share/uhpc_multiscale/data to the
//      sources' data/, and the programs sit one level below <build>).
// InputError (exit 2) when neither holds, naming both places and the variable.
#include <filesystem>

namespace uhpc {

std::filesystem::path shipped_data_dir();

}  // namespace uhpc
