#pragma once
// What every program's main() shares: the exit-code policy and the --set option.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace uhpc {

enum ExitCode : int { kExitOk = 0, kExitNumerical = 1, kExitBadInput = 2 };

// Runs `body` and maps failures to exit codes with one clear line on stderr:
// InputError -> 2 ("error: <message>"), NumericalError -> 1 ("numerical failure: <message>"),
// CLI11 parse errors -> 2 with CLI11's message (--help prints the help and gives 0),
// any other std::exception -> 1 ("internal error: <what>").
int run_main(const std::string& program, const std::function<int()>& body);

// Adds the repeatable `--set key.path=value` option to `app` (or a subcommand), collecting into
// `overrides`.
CLI::Option* add_set_option(CLI::App& app, std::vector<std::string>& overrides);

}  // namespace uhpc
