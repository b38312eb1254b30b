#pragma once
// What every program's main() shares: the exit-code policy and the --set option.
//
//   int main(int argc, char** argv) {
//     CLI::App app{"3D penetration run", "uhpc-macro"};
//     std::vector<std::string> overrides;
//     std::string config_path;
//     app.add_option("--config", config_path, "case configuration (JSON)")->required();
//     uhpc::add_set_option(app, overrides);
//     return uhpc::run_main(app, [&] {
//       app.parse(argc, argv);  // inside run_main, so --help and bad options get the policy below
//       const uhpc::Config config = uhpc::Config::load(config_path, overrides);
//       ...
//       return uhpc::kExitOk;
//     });
//   }
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace uhpc {

enum ExitCode : int { kExitOk = 0, kExitNumerical = 1, kExitBadInput = 2 };

// Runs `body` and maps failures to exit codes with exactly one line on stderr:
//   InputError              -> 2  "error: <message>"
//   std::filesystem::filesystem_error -> 2 "error: <path>: <reason>" (an unusable output path)
//   NumericalError          -> 1  "numerical failure: <message>"
//   CLI11 parse error       -> 2  "error: <CLI11's message>"
//   --help, --help-all, --version -> 0, CLI11 prints the help (or version) on stdout
//   other std::exception    -> 1  "internal error: <what>"   (a bug, not the user's input)
// Otherwise returns what `body` returns. Messages spanning lines are joined into one. Adds --version
// ("<program> <version> (git <commit>)") to an App that has none. With UHPC_PARSE_ONLY=1 in the
// environment the program stops, exit 0, once its command line has parsed and validated (options,
// subcommand, required options): the dry run with which ctest checks the README's commands.
int run_main(CLI::App& app, const std::function<int()>& body);

// The same for a body that does not parse a command line with CLI11 through an App run_main
// knows: --help cannot be printed here, so a CLI::CallForHelp reaching this overload is reported as
// an internal error naming `program`.
int run_main(const std::string& program, const std::function<int()>& body);

// Adds the repeatable `--set key.path=value` option to `app` (or a subcommand), collecting into
// `overrides` in command-line order (a later --set of the same key wins). Each --set takes exactly
// one value, so `--set a=1 input.json` leaves input.json to the positionals.
CLI::Option* add_set_option(CLI::App& app, std::vector<std::string>& overrides);

}  // namespace uhpc
