#include "uhpc/cli.hpp"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <set>

#include "uhpc/build_info.hpp"
#include "uhpc/did_you_mean.hpp"
#include "uhpc/errors.hpp"

namespace uhpc {

namespace {

// Scripts grep stderr line by line: one failure, one line.
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

int report(const std::string& prefix, const std::string& message, int code) {
  // One write: under mpirun a line written in pieces can be split by the launcher's own messages.
  std::cerr << (prefix + one_line(message) + "\n") << std::flush;
  return code;
}

// --help, --help-all and --version arrive as exceptions (CLI::Success and its subclasses, exit
// code 0). Only the App can print its help, and App::exit() picks the selected subcommand's help.
int on_success_request(const CLI::App* app, const std::string& program, const CLI::ParseError& e) {
  if (app != nullptr) return app->exit(e);
  if (e.get_name() == "CallForVersion") {
    std::cout << e.what() << std::endl;
    return kExitOk;
  }
  return report("internal error: ", program + ": " + e.get_name() + " needs run_main(app, body) to print the help", kExitNumerical);
}

// A command line of a program with subcommands whose first word is none of them ("uhpc-micro generat")
// fails in CLI11 as "A subcommand is required" or as an unexpected argument, neither naming the word as
// the command meant. Returns the message that does ("'generat' is not one of uhpc-micro's commands:
// elastic, ..., run (did you mean 'generate'?)"), or "" when the parse failed for another reason.
std::string unknown_subcommand_message(const CLI::App& app) {
  if (!app.get_subcommands().empty()) return {};  // a subcommand was recognised: its own error stands
  std::set<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.insert(sub->get_name());
  const std::vector<std::string> rest = app.remaining();
  if (names.empty() || rest.empty() || rest.front().empty() || rest.front()[0] == '-') return {};
  const std::string& word = rest.front();
  std::string message = "'" + word + "' is not one of " + app.get_name() + "'s commands:";
  for (const std::string& name : names) message += (name == *names.begin() ? " " : ", ") + name;
  if (const std::string guess = closest_name(word, names); !guess.empty()) message += " (did you mean '" + guess + "'?)";
  return message;
}

// Thrown by the final callback under UHPC_PARSE_ONLY: the command line parsed, nothing runs.
struct ParsedOnly {};

int run(const CLI::App* app, const std::string& program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const ParsedOnly&) {
    std::cout << program << ": command line parsed (UHPC_PARSE_ONLY)" << std::endl;
    return kExitOk;
  } catch (const InputError& e) {
    return report("error: ", e.what(), kExitBadInput);
  } catch (const NumericalError& e) {
    return report("numerical failure: ", e.what(), kExitNumerical);
  } catch (const std::filesystem::filesystem_error& e) {
    // An output path that cannot be made or written (a file in the way, /proc, no permission).
    return report("error: ", (e.path1().empty() ? std::string() : e.path1().string() + ": ") + e.code().message(),
                  kExitBadInput);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return on_success_request(app, program, e);
    if (app != nullptr)
      if (const std::string unknown = unknown_subcommand_message(*app); !unknown.empty())
        return report("error: ", unknown, kExitBadInput);
    return report("error: ", e.what(), kExitBadInput);
  } catch (const std::exception& e) {
    return report("internal error: ", e.what(), kExitNumerical);
  } catch (...) {
    return report("internal error: ", "unknown exception", kExitNumerical);
  }
}

}  // namespace

int run_main(CLI::App& app, const std::function<int()>& body) {
  // Every program answers --version the same way: its name, the project version and the git commit
  // it was built from (the provenance block of its results carries the same two).
  if (app.get_version_ptr() == nullptr)
    app.set_version_flag("--version", app.get_name() + " " + build_version() + " (git " + build_git_commit() + ")",
                         "Print the program's version and git commit and exit");
  // The README check (tests/regression/check_readme_commands.py): parse, validate the options and
  // the subcommand, then stop before any work.
  if (const char* only = std::getenv("UHPC_PARSE_ONLY"); only != nullptr && *only != '\0' && *only != '0')
    app.final_callback([] { throw ParsedOnly{}; });
  return run(&app, app.get_name(), body);
}

int run_main(const std::string& program, const std::function<int()>& body) { return run(nullptr, program, body); }

CLI::Option* add_set_option(CLI::App& app, std::vector<std::string>& overrides) {
  return app
      .add_option("--set", overrides,
                  "Override one configuration entry; repeatable, later wins. KEY.PATH is the dotted "
                  "key from the file's root (target.thickness_m); VALUE is read as JSON when it is "
                  "valid JSON (0.05, true, [1,2], {\"a\":1}) and as plain text otherwise "
                  "(material.model=afc). A key the program does not use is an error.")
      ->type_name("KEY.PATH=VALUE")
      ->allow_extra_args(false)
      ->take_all();
}

}  // namespace uhpc
