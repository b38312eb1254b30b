// run_main's exit-code policy (docs/architecture.md section 2: 0 ok, 2 bad input, 1 numerical failure)
// with exactly one line on stderr, and the --set option.
#include "uhpc/cli.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "uhpc/build_info.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

struct Outcome {
  int code;
  std::string err;
  std::string out;
};

// Runs run_main(app, body) with stdout and stderr captured.
Outcome run_captured(CLI::App& app, const std::function<int()>& body) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int code = run_main(app, body);
  std::string err = ::testing::internal::GetCapturedStderr();
  std::string out = ::testing::internal::GetCapturedStdout();
  return {code, err, out};
}

Outcome run_captured(const std::function<int()>& body) {
  CLI::App app{"test program", "uhpc-test"};
  return run_captured(app, body);
}

// A typical main: options, --set, parse inside run_main. `argv` without the program name.
struct Program {
  CLI::App app{"test program", "uhpc-test"};
  std::string config;
  std::vector<std::string> overrides;

  Program() {
    app.add_option("--config", config, "configuration file");
    add_set_option(app, overrides);
  }

  Outcome run(std::vector<std::string> args) {
    args.insert(args.begin(), "uhpc-test");
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    return run_captured(app, [&] {
      app.parse(static_cast<int>(argv.size()), argv.data());
      return kExitOk;
    });
  }
};

// An output path the program cannot make (a file in the way, /proc) is the user's to fix: exit 2.
TEST(RunMain, AnUnusableOutputPathIsBadInput) {
  const Outcome outcome = run_captured([]() -> int {
    throw std::filesystem::filesystem_error("cannot create directories", "/proc/x",
                                            std::make_error_code(std::errc::no_such_file_or_directory));
  });
  EXPECT_EQ(outcome.code, 2);
  EXPECT_EQ(outcome.err, "error: /proc/x: No such file or directory\n");
}

TEST(RunMain, ReturnsTheBodysCode) {
  EXPECT_EQ(run_captured([] { return 0; }).code, 0);
  const Outcome outcome = run_captured([] { return 7; });
  EXPECT_EQ(outcome.code, 7);
  EXPECT_EQ(outcome.err, "");
}

TEST(RunMain, InputErrorIsExitTwo) {
  const Outcome outcome = run_captured([]() -> int {
    throw InputError("case.json: key 'target.thickness_m': value -1 is out of range, must be > 0");
  });
  EXPECT_EQ(outcome.code, kExitBadInput);
  EXPECT_EQ(outcome.err, "error: case.json: key 'target.thickness_m': value -1 is out of range, must be > 0\n");
}

TEST(RunMain, ConfigErrorsReachStderrUnchanged) {
  const Outcome outcome = run_captured([]() -> int {
    const Config config = Config::from_json(nlohmann::json::object(), "case.json");
    return static_cast<int>(config.number("velocity_m_s"));
  });
  EXPECT_EQ(outcome.code, 2);
  EXPECT_EQ(outcome.err, "error: case.json: key 'velocity_m_s': required key is missing\n");
}

TEST(RunMain, NumericalErrorIsExitOne) {
  const Outcome outcome = run_captured([]() -> int { throw NumericalError("step 12: NaN in velocity at node 4"); });
  EXPECT_EQ(outcome.code, kExitNumerical);
  EXPECT_EQ(outcome.err, "numerical failure: step 12: NaN in velocity at node 4\n");
}

TEST(RunMain, OtherExceptionIsAnInternalError) {
  const Outcome outcome = run_captured([]() -> int { throw std::logic_error("index out of bounds"); });
  EXPECT_EQ(outcome.code, 1);
  EXPECT_EQ(outcome.err, "internal error: index out of bounds\n");
  const Outcome unknown = run_captured([]() -> int { throw 42; });
  EXPECT_EQ(unknown.code, 1);
  EXPECT_EQ(unknown.err, "internal error: unknown exception\n");
}

TEST(RunMain, MultiLineMessageBecomesOneLine) {
  const Outcome outcome = run_captured([]() -> int { throw InputError("first\nsecond\n"); });
  EXPECT_EQ(outcome.err, "error: first second\n");
}

TEST(RunMain, ProgramNameOverload) {
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(run_main("uhpc-test", []() -> int { throw InputError("bad.json: unreadable"); }), 2);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "error: bad.json: unreadable\n");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(run_main("uhpc-test", []() -> int { throw CLI::CallForHelp(); }), 1);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "internal error: uhpc-test: CallForHelp needs run_main(app, body) to print the help\n");
  ::testing::internal::CaptureStdout();
  EXPECT_EQ(run_main("uhpc-test", []() -> int { throw CLI::CallForVersion("uhpc 0.1.0", 0); }), 0);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "uhpc 0.1.0\n");
}

TEST(Cli, SetIsRepeatable) {
  Program program;
  const Outcome outcome = program.run({"--config", "case.json", "--set", "target.thickness_m=0.2", "--set=a.b=[1,2]"});
  EXPECT_EQ(outcome.code, 0);
  EXPECT_EQ(outcome.err, "");
  EXPECT_EQ(program.config, "case.json");
  EXPECT_EQ(program.overrides, (std::vector<std::string>{"target.thickness_m=0.2", "a.b=[1,2]"}));
}

TEST(Cli, SetTakesOneValuePerOccurrence) {
  Program program;
  std::vector<std::string> inputs;
  program.app.add_option("inputs", inputs, "positional inputs");
  EXPECT_EQ(program.run({"--set", "a=1", "extra.json"}).code, 0);
  EXPECT_EQ(program.overrides, (std::vector<std::string>{"a=1"}));
  EXPECT_EQ(inputs, (std::vector<std::string>{"extra.json"}));
}

TEST(Cli, BadOptionIsExitTwoWithOneLine) {
  Program program;
  const Outcome outcome = program.run({"--bogus"});
  EXPECT_EQ(outcome.code, kExitBadInput);
  EXPECT_EQ(outcome.err, "error: The following argument was not expected: --bogus\n");
}

TEST(Cli, MissingValueIsExitTwo) {
  Program program;
  const Outcome outcome = program.run({"--set"});
  EXPECT_EQ(outcome.code, 2);
  EXPECT_EQ(outcome.err.rfind("error: --set", 0), 0u) << outcome.err;
  EXPECT_EQ(outcome.err.find('\n'), outcome.err.size() - 1) << outcome.err;
}

TEST(Cli, HelpPrintsUsageAndExitsZero) {
  Program program;
  const Outcome outcome = program.run({"--help"});
  EXPECT_EQ(outcome.code, 0);
  EXPECT_EQ(outcome.err, "");
  EXPECT_NE(outcome.out.find("--set KEY.PATH=VALUE"), std::string::npos) << outcome.out;
  EXPECT_NE(outcome.out.find("Override one configuration entry"), std::string::npos) << outcome.out;
}

TEST(Cli, VersionPrintsTheProgramVersionAndCommitAndExitsZero) {
  Program program;
  const Outcome outcome = program.run({"--version"});
  EXPECT_EQ(outcome.code, 0);
  EXPECT_EQ(outcome.err, "");
  EXPECT_EQ(outcome.out, std::string("uhpc-test ") + build_version() + " (git " + build_git_commit() + ")\n");
  EXPECT_FALSE(std::string(build_git_commit()).empty());
}

// UHPC_PARSE_ONLY: the README check's dry run. A valid command line stops after parsing (the body's
// work does not happen); a bad one is still exit 2.
TEST(Cli, ParseOnlyStopsAfterAValidCommandLine) {
  ::setenv("UHPC_PARSE_ONLY", "1", 1);
  for (const bool valid : {true, false}) {
    CLI::App app{"test program", "uhpc-test"};
    std::string config;
    app.add_option("--config", config, "case")->required();
    std::vector<std::string> args{"uhpc-test"};
    if (valid) args.insert(args.end(), {"--config", "case.json"});
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    bool worked = false;
    const Outcome outcome = run_captured(app, [&] {
      app.parse(static_cast<int>(argv.size()), argv.data());
      worked = true;
      return 5;
    });
    EXPECT_FALSE(worked);
    EXPECT_EQ(outcome.code, valid ? 0 : 2) << outcome.err;
    if (valid) {
      EXPECT_EQ(outcome.out, "uhpc-test: command line parsed (UHPC_PARSE_ONLY)\n");
    }
  }
  ::unsetenv("UHPC_PARSE_ONLY");
}

TEST(Cli, HelpOfASubcommand) {
  CLI::App app{"test program", "uhpc-test"};
  std::vector<std::string> overrides;
  CLI::App* run = app.add_subcommand("run", "run one cell");
  add_set_option(*run, overrides);
  std::vector<std::string> args{"uhpc-test", "run", "--help"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  const Outcome outcome = run_captured(app, [&] {
    app.parse(static_cast<int>(argv.size()), argv.data());
    return 0;
  });
  EXPECT_EQ(outcome.code, 0);
  EXPECT_NE(outcome.out.find("run one cell"), std::string::npos) << outcome.out;
  EXPECT_NE(outcome.out.find("--set"), std::string::npos) << outcome.out;
}

// A program whose first word must be one of its commands (uhpc-micro): a misspelt one is named, with the
// closest command and the list; a parse that fails otherwise keeps CLI11's message.
Outcome run_commands_program(std::vector<std::string> args, std::size_t required_min) {
  CLI::App app{"test program", "uhpc-test"};
  app.require_subcommand(required_min, 1);
  bool quiet = false;
  app.add_flag("-q", quiet, "quiet");
  std::string config;
  for (const char* name : {"generate", "generate-ensemble", "run"})
    app.add_subcommand(name, "a command")->add_option("--config", config, "configuration file");
  args.insert(args.begin(), "uhpc-test");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  return run_captured(app, [&] {
    app.parse(static_cast<int>(argv.size()), argv.data());
    return 0;
  });
}

TEST(Cli, MisspeltSubcommandIsNamed) {
  const std::string list = " is not one of uhpc-test's commands: generate, generate-ensemble, run";
  Outcome o = run_commands_program({"generat", "--config", "x.json"}, 1);
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_EQ(o.err, "error: 'generat'" + list + " (did you mean 'generate'?)\n");
  o = run_commands_program({"-q", "rnu"}, 1);
  EXPECT_EQ(o.err, "error: 'rnu'" + list + " (did you mean 'run'?)\n");
  o = run_commands_program({"simulate"}, 0);  // a subcommand is optional: CLI11 called it unexpected
  EXPECT_EQ(o.err, "error: 'simulate'" + list + "\n");
  o = run_commands_program({}, 1);
  EXPECT_EQ(o.err, "error: A subcommand is required\n");
  o = run_commands_program({"--bogus"}, 1);
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_EQ(o.err.find("error: '"), std::string::npos) << o.err;
  o = run_commands_program({"run", "--config"}, 1);  // the command is known: its own error stands
  EXPECT_EQ(o.err.rfind("error: --config", 0), 0u) << o.err;
}

TEST(Cli, VersionExitsZero) {
  Program program;
  program.app.set_version_flag("--version", "uhpc-test 0.1.0");
  const Outcome outcome = program.run({"--version"});
  EXPECT_EQ(outcome.code, 0);
  EXPECT_EQ(outcome.out, "uhpc-test 0.1.0\n");
  EXPECT_EQ(outcome.err, "");
}

}  // namespace
}  // namespace uhpc
