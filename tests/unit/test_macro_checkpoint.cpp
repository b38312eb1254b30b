// Checkpoints and restarts of uhpc-macro (macro/app/checkpoint.hpp, ExplicitSolver::checkpoint/resume):
// a run split in two at a checkpoint equals the unsplit run bit for bit, at the solver and through the
// program (a run killed after its checkpoint and restarted with --restart); foreign checkpoints are
// refused with one line.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <hdf5.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "checkpoint.hpp"
#include "coarse_disc_solver.hpp"
#include "macro_run.hpp"
#include "material_factory.hpp"
#include "test_support.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hdf5_io.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace uhpc::macro {
namespace {

namespace fs = std::filesystem;
class MacroCheckpoint : public test::ScratchDirTest {};

const std::string& kCase = test::kCoarseDiscCase;
using test::coarse_disc_solver;
using test::same_bits;

// Runs uhpc-macro with `args` in a process of its own (fork + exec: OpenMP is not safe across a bare
// fork; its stdout and stderr go to the test's) and kills it once `ready()` holds, polled (at most 60 s).
// Returns whether the kill ended it, rather than the run finishing first.
bool killed_when(const std::vector<std::string>& args, const std::function<bool()>& ready) {
  const std::string program = std::string(UHPC_BINARY_DIR) + "/macro/uhpc-macro";
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) return false;
  if (child == 0) {
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!ready() && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  return WIFSIGNALED(status);
}

// Solver A steps 60 times, drops its shape cache and is checkpointed (through the file), then steps
// 60 more; solver B is built from the same case, resumed from the file and steps the same 60: every
// evolving field, the material states, the sphere and the ledger are the same bits.
TEST_F(MacroCheckpoint, ASolverResumedFromACheckpointFileGoesOnBitForBit) {
  ExplicitSolver a = coarse_disc_solver();
  for (int k = 0; k < 60; ++k) ASSERT_TRUE(a.step());
  a.drop_shape_cache();
  RunCheckpoint written;
  written.solver = a.checkpoint();
  written.history_text = "time_s\n";
  written.history_rows = 1;
  written.impact.thickness_m = 0.03175;
  written.balance.worst_energy = 1.5e-4;
  written.config_hash = "0123456789abcdef";
  written.build = checkpoint_build();
  write_checkpoint(dir_ / "checkpoint.h5", written);
  for (int k = 0; k < 60; ++k) ASSERT_TRUE(a.step());

  const RunCheckpoint read = read_checkpoint(dir_ / "checkpoint.h5", "0123456789abcdef");
  EXPECT_EQ(read.history_text, "time_s\n");
  EXPECT_EQ(read.balance.worst_energy, 1.5e-4);
  ExplicitSolver b = coarse_disc_solver();
  b.resume(read.solver);
  EXPECT_EQ(b.steps(), 60);
  for (int k = 0; k < 60; ++k) ASSERT_TRUE(b.step());

  const SolverCheckpoint end_a = a.checkpoint(), end_b = b.checkpoint();
  ASSERT_EQ(end_a.particle_fields.size(), end_b.particle_fields.size());
  for (std::size_t f = 0; f < end_a.particle_fields.size(); ++f)
    EXPECT_TRUE(same_bits(end_a.particle_fields[f].second, end_b.particle_fields[f].second))
        << end_a.particle_fields[f].first;
  EXPECT_TRUE(same_bits(end_a.material_states, end_b.material_states));
  EXPECT_EQ(std::memcmp(&end_a.state.ledger, &end_b.state.ledger, sizeof(EnergyLedger)), 0);
  EXPECT_EQ(std::memcmp(&*end_a.state.sphere, &*end_b.state.sphere, sizeof(RigidSphere)), 0);
  EXPECT_EQ(end_a.state.time_s, end_b.state.time_s);
  EXPECT_EQ(end_b.counters.steps, 120);
  // The sphere has hit the disc by then: the state resumed is a loaded one.
  EXPECT_GT(a.ledger().internal, 1.0);
}

// Through the program: a run killed right after its first checkpoint and restarted with --restart ends
// with the same history.csv, result.json (but for the clocks and the provenance's date) and fields as
// the run that was never stopped (the program's stdout and stderr go to the test's).
TEST_F(MacroCheckpoint, AKilledRunRestartedFromItsCheckpointEqualsTheUnstoppedRun) {
  // 60 us: the sphere is inside the disc, about 140 steps.
  const std::vector<std::string> overrides = {"run.checkpoint_interval_steps=10", "run.end_time_s=6e-5"};
  MacroRunArgs whole;
  whole.config_path = kCase;
  whole.overrides = overrides;
  whole.out = dir_ / "whole";
  whole.quiet = true;
  run_macro(whole);
  // 60 us does not decide the shot: the run keeps its last state as a checkpoint (a decided run removes it)
  EXPECT_EQ(nlohmann::json::parse(test::read_file(whole.out / "result.json")).at("outcome"), "undecided");
  EXPECT_TRUE(fs::exists(whole.out / "checkpoint.h5"));

  MacroRunArgs split = whole;
  split.out = dir_ / "split";
  // Killed as soon as the first checkpoint is on disk (written atomically: complete when it appears).
  ASSERT_TRUE(killed_when({"-q", "--config", kCase, "--set", overrides[0], "--set", overrides[1], "--out",
                           split.out.string()},
                          [&] { return fs::exists(split.out / "checkpoint.h5"); }))
      << "the run finished before it could be killed";
  ASSERT_TRUE(fs::exists(split.out / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(split.out / "result.json"));

  split.restart = true;
  run_macro(split);
  EXPECT_EQ(test::read_file(split.out / "history.csv"), test::read_file(whole.out / "history.csv"));
  EXPECT_EQ(test::read_file(split.out / "fields.xdmf"), test::read_file(whole.out / "fields.xdmf"));
  nlohmann::json a = nlohmann::json::parse(test::read_file(whole.out / "result.json"));
  nlohmann::json b = nlohmann::json::parse(test::read_file(split.out / "result.json"));
  for (const char* clock : {"wall_time_s", "particle_steps_per_s", "peak_memory_MB", "provenance"}) {
    a.erase(clock);
    b.erase(clock);
  }
  EXPECT_EQ(a, b);
  const H5Reader fa(whole.out / "fields.h5"), fb(split.out / "fields.h5");
  ASSERT_EQ(fa.children(""), fb.children(""));
  for (const std::string& step : fa.children(""))
    for (const std::string& field : fa.children(step))
      EXPECT_TRUE(same_bits(fa.read_doubles(step + "/" + field).values, fb.read_doubles(step + "/" + field).values))
          << step << "/" << field;
}

// The wall clock's checkpoints (--checkpoint-every-min) are not an input: a run that writes one at
// every step ends with the same bits as a run that writes none (they keep the lazy shape rows). A run
// killed after one goes on from it with --restart; with every row rebuilt each step
// (solver.shape_reuse_tolerance 0) it then ends with the same bits as the unstopped run (with lazy rows
// the resumed run rebuilds its rows where the killed one had kept them: the rows' tolerance apart).
TEST_F(MacroCheckpoint, WallClockCheckpointsChangeNothingAndAKilledRunGoesOnFromTheLast) {
  const auto args_for = [&](const std::string& name, std::vector<std::string> overrides, double every_s) {
    MacroRunArgs a;
    a.config_path = kCase;
    a.overrides = std::move(overrides);
    a.out = dir_ / name;
    a.quiet = true;
    a.checkpoint_every_s = every_s;
    return a;
  };
  const auto same_run = [](const fs::path& x, const fs::path& y) {
    EXPECT_EQ(test::read_file(x / "history.csv"), test::read_file(y / "history.csv")) << x << " " << y;
    nlohmann::json a = nlohmann::json::parse(test::read_file(x / "result.json"));
    nlohmann::json b = nlohmann::json::parse(test::read_file(y / "result.json"));
    for (const char* clock : {"wall_time_s", "particle_steps_per_s", "peak_memory_MB", "provenance"}) {
      a.erase(clock);
      b.erase(clock);
    }
    EXPECT_EQ(a, b) << x << " " << y;
  };
  const std::vector<std::string> lazy = {"run.end_time_s=3e-5"};  // 30 us: the sphere is in the disc
  const MacroRunArgs plain = args_for("plain", lazy, 0.0);
  run_macro(plain);
  const MacroRunArgs clocked = args_for("clocked", lazy, 1e-9);  // a checkpoint after every step
  run_macro(clocked);
  same_run(plain.out, clocked.out);
  // Both configurations record the same inputs: the clock is not one of them.
  EXPECT_EQ(test::read_file(plain.out / "config.json"), test::read_file(clocked.out / "config.json"));

  const std::vector<std::string> rebuilt = {"run.end_time_s=3e-5", "solver.shape_reuse_tolerance=0"};
  const MacroRunArgs whole = args_for("whole", rebuilt, 0.0);
  run_macro(whole);
  MacroRunArgs split = args_for("split", rebuilt, 0.0);
  // Killed once the history saved with the clock's checkpoints holds 20 steps (a row a step after the
  // header and the initial state; saved just before each checkpoint, which is written atomically): the
  // checkpoint on disk is then of about the 20th step.
  const auto rows = [&] {
    std::ifstream f(split.out / "history.csv");
    return std::count(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>(), '\n');
  };
  ASSERT_TRUE(killed_when({"-q", "--config", kCase, "--set", rebuilt[0], "--set", rebuilt[1], "--checkpoint-every-min",
                           "1e-7", "--out", split.out.string()},
                          [&] { return fs::exists(split.out / "checkpoint.h5") && rows() >= 22; }))
      << "the run finished before it could be killed";
  ASSERT_TRUE(fs::exists(split.out / "checkpoint.h5"));
  EXPECT_FALSE(fs::exists(split.out / "result.json"));
  split.restart_check = true;  // what pipelines/carried_shot.py asks first
  testing::internal::CaptureStdout();
  run_macro(split);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "restart\n");
  split.restart_check = false;
  split.restart = true;
  run_macro(split);
  same_run(whole.out, split.out);
}

// An undecided run keeps its last state as a checkpoint; --restart with a later end time carries it on
// and ends as the run made with that end time from the start (rows rebuilt every step, so that the
// checkpoint's dropped shape cache changes nothing): the same history.csv and result (but for the clocks,
// the provenance and the field outputs, which gain the first run's last state). Another end time is the
// only change of the case a restart takes: a decided run removes its checkpoint.
TEST_F(MacroCheckpoint, AnUndecidedRunIsExtendedByARestartWithALaterEndTime) {
  const auto args_to = [&](const std::string& name, const std::string& end_time) {
    MacroRunArgs a;
    a.config_path = kCase;
    a.overrides = {"solver.shape_reuse_tolerance=0", "run.end_time_s=" + end_time};
    a.out = dir_ / name;
    a.quiet = true;
    return a;
  };
  MacroRunArgs whole = args_to("whole", "6e-5");
  run_macro(whole);
  MacroRunArgs extended = args_to("extended", "3e-5");  // 30 us: the sphere is still in the disc
  run_macro(extended);
  const auto outcome = [](const fs::path& dir) {
    return nlohmann::json::parse(test::read_file(dir / "result.json")).at("outcome").get<std::string>();
  };
  ASSERT_EQ(outcome(extended.out), "undecided");
  ASSERT_TRUE(fs::exists(extended.out / "checkpoint.h5"));
  extended.overrides.back() = "run.end_time_s=6e-5";
  extended.restart = true;
  run_macro(extended);
  EXPECT_EQ(test::read_file(extended.out / "history.csv"), test::read_file(whole.out / "history.csv"));
  nlohmann::json a = nlohmann::json::parse(test::read_file(whole.out / "result.json"));
  nlohmann::json b = nlohmann::json::parse(test::read_file(extended.out / "result.json"));
  for (const char* clock : {"wall_time_s", "particle_steps_per_s", "peak_memory_MB", "provenance", "field_outputs"}) {
    a.erase(clock);
    b.erase(clock);
  }
  EXPECT_EQ(a, b);
  ASSERT_EQ(outcome(extended.out), "undecided");  // at 60 us: the checkpoint is kept again
  EXPECT_TRUE(fs::exists(extended.out / "checkpoint.h5"));
  // An end time the checkpoint has reached is refused, and the outputs are left as they were.
  const std::string result_before = test::read_file(extended.out / "result.json");
  extended.overrides.back() = "run.end_time_s=5e-5";
  const std::string reached = test::error_of<InputError>([&] { run_macro(extended); });
  EXPECT_NE(reached.find((extended.out / "checkpoint.h5").string() + ": solver/clock time_s = "), std::string::npos) << reached;
  EXPECT_NE(reached.find("at or past run.end_time_s = 5e-05 s"), std::string::npos) << reached;
  MacroRunArgs check = extended;  // --restart-check refuses it alike
  check.restart = false;
  check.restart_check = true;
  EXPECT_EQ(test::error_of<InputError>([&] { run_macro(check); }), reached);
  EXPECT_EQ(test::read_file(extended.out / "result.json"), result_before);
  // Anything else changed is another case.
  extended.overrides.back() = "run.end_time_s=9e-5";
  extended.overrides.push_back("projectile.velocity_m_s=800");
  const std::string other = test::error_of<InputError>([&] { run_macro(extended); });
  EXPECT_NE(other.find("written for a case whose hash is"), std::string::npos) << other;
  EXPECT_EQ(test::read_file(extended.out / "result.json"), result_before);
}

// A run whose outcome is decided removes its checkpoint: the elastic block's rebound at 45 us, with a
// checkpoint every 10 steps on the way.
TEST_F(MacroCheckpoint, ADecidedRunRemovesItsCheckpoint) {
  MacroRunArgs a;
  a.config_path = std::string(UHPC_DATA_DIR) + "/macro_elastic_block.json";
  a.overrides = {"run.checkpoint_interval_steps=10"};
  a.out = dir_ / "block";
  a.quiet = true;
  run_macro(a);
  EXPECT_EQ(nlohmann::json::parse(test::read_file(a.out / "result.json")).at("outcome"), "rebounded");
  EXPECT_FALSE(fs::exists(a.out / "checkpoint.h5"));
}

// A checkpoint of another case or another build is refused with one line naming the file. --restart-check
// answers "start" where only a run from t = 0 is left (no checkpoint, another build's) and refuses the rest
// as --restart does.
TEST_F(MacroCheckpoint, ACheckpointOfAnotherCaseOrBuildOrNoneIsRefused) {
  const auto args_for = [&](bool check) {
    MacroRunArgs args;
    args.config_path = kCase;
    args.out = dir_;
    args.quiet = true;
    args.restart = !check;
    args.restart_check = check;
    return args;
  };
  const auto restart_error = [&](const std::vector<std::string>& overrides) {
    MacroRunArgs args = args_for(false);
    args.overrides = overrides;
    return test::error_of<InputError>([&] { run_macro(args); });
  };
  const auto check_answer = [&] {
    testing::internal::CaptureStdout();
    run_macro(args_for(true));
    return testing::internal::GetCapturedStdout();
  };
  const auto check_error = [&] { return test::error_of<InputError>([&] { run_macro(args_for(true)); }); };
  const std::string file = (dir_ / "checkpoint.h5").string();
  EXPECT_EQ(restart_error({}), file + ": no checkpoint to restart from (the run wrote none: "
                                   "run.checkpoint_interval_steps, --checkpoint-every-min or an undecided end)");
  EXPECT_EQ(check_answer(), "start\n");

  RunCheckpoint c;
  c.solver = coarse_disc_solver().checkpoint();
  c.config_hash = "0123456789abcdef";
  c.build = checkpoint_build();
  write_checkpoint(file, c);
  const std::string other_case = restart_error({});
  EXPECT_EQ(other_case.rfind(file + ": written for a case whose hash is 0123456789abcdef, this case's is ", 0), 0u)
      << other_case;
  EXPECT_EQ(check_error(), other_case);
  c.build = "0.0.1 abc";
  write_checkpoint(file, c);
  EXPECT_EQ(restart_error({}), file + ": written by uhpc-macro 0.0.1 abc, this is " + checkpoint_build() +
                                   ": a checkpoint is resumed by the build that wrote it");
  EXPECT_EQ(check_answer(), "start\n");
  const hid_t old = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);  // no checksums: an
  ASSERT_GE(old, 0);                                                                   // earlier build's
  H5Fclose(old);
  EXPECT_EQ(check_answer(), "start\n");
  write_text_atomic(file, "not hdf5");
  EXPECT_EQ(restart_error({}).rfind(file + ": not a usable checkpoint: ", 0), 0u);
  EXPECT_EQ(check_error().rfind(file + ": not a usable checkpoint: ", 0), 0u);
  EXPECT_TRUE(fs::exists(file));  // the check writes and removes nothing
}

// A checkpoint's values are checked against the restarted run's own bounds (the edits the issue made:
// a time of -1 or 1e300, a step count of -1000 or 2^62, and a dt of 0 or NaN): each is refused naming
// the file and the value. The checkpoint is a real one (the elastic block stopped undecided), edited
// through the program's own writer, so its checksums are valid and only the values are wrong.
TEST_F(MacroCheckpoint, ACheckpointWhoseClockIsOutsideTheRunsBoundsIsRefusedNamingTheValue) {
  MacroRunArgs args;
  args.config_path = std::string(UHPC_DATA_DIR) + "/macro_elastic_block.json";
  args.overrides = {"run.checkpoint_interval_steps=5", "run.end_time_s=3e-7"};
  args.out = dir_ / "block";
  args.quiet = true;
  run_macro(args);
  const fs::path file = args.out / "checkpoint.h5";
  ASSERT_TRUE(fs::exists(file));
  const std::string hash = H5Reader(file).string_attribute("", "config_hash");
  const RunCheckpoint intact = read_checkpoint(file, hash);
  args.overrides.back() = "run.end_time_s=5e-7";
  args.restart = true;
  const auto refused = [&](const std::function<void(SolverCheckpoint&)>& edit) {
    RunCheckpoint c = intact;
    edit(c.solver);
    write_checkpoint(file, c);
    return test::error_of<InputError>([&] { run_macro(args); });
  };
  const std::string at = file.string() + ": ";
  EXPECT_EQ(refused([](SolverCheckpoint& s) { s.state.time_s = -1.0; }),
            at + "solver/clock time_s = -1: not a time >= 0 s: the checkpoint is corrupt or was edited");
  EXPECT_EQ(refused([](SolverCheckpoint& s) { s.state.time_s = 1e300; }),
            at + "solver/clock time_s = 1e+300 s: at or past run.end_time_s = 5e-07 s: a restart carries a run on to "
                 "a later end time");
  EXPECT_EQ(refused([](SolverCheckpoint& s) { s.counters.steps = -1000; }),
            at + "solver/counters steps = -1000: outside [0, run.max_steps = 1000000]: the checkpoint is corrupt or was "
                 "edited (a run that really took more steps goes on with a larger run.max_steps)");
  EXPECT_THAT(refused([](SolverCheckpoint& s) { s.counters.steps = std::int64_t{1} << 62; }),
              ::testing::StartsWith(at + "solver/counters steps = 4611686018427387904: outside [0, run.max_steps"));
  EXPECT_EQ(refused([](SolverCheckpoint& s) { s.state.dt_s = 0.0; }),
            at + "solver/clock dt_s = 0: not a step > 0 s: the checkpoint is corrupt or was edited");
  EXPECT_EQ(refused([](SolverCheckpoint& s) { s.state.dt_s = std::nan(""); }),
            at + "solver/clock dt_s = nan: not a step > 0 s: the checkpoint is corrupt or was edited");
  EXPECT_THAT(refused([](SolverCheckpoint& s) { s.counters.steps = 0; }),
              ::testing::HasSubstr(": a run is at time 0 exactly at step 0"));
  // The intact values restart.
  write_checkpoint(file, intact);
  run_macro(args);
  EXPECT_TRUE(fs::exists(args.out / "result.json"));
}

// The checkpoint's values are checksummed: one byte of a particle value flipped in the file is refused
// naming the file and the dataset (a checkpoint without checksums: regression.corrupted_files).
TEST_F(MacroCheckpoint, ACorruptedCheckpointIsRefusedNamingTheFile) {
  const fs::path file = dir_ / "checkpoint.h5";
  RunCheckpoint c;
  c.solver = coarse_disc_solver().checkpoint();
  c.config_hash = "0123456789abcdef";
  c.build = checkpoint_build();
  write_checkpoint(file, c);
  std::string bytes = test::read_file(file);
  // A value that is not zero (eight zero bytes are everywhere in a file), found in the file's bytes.
  std::size_t at = std::string::npos;
  for (const auto& field : c.solver.particle_fields) {
    const std::vector<double>& values = field.second;
    const double* value = values.data() + values.size() / 2;
    if (values.empty() || *value == 0.0) continue;
    at = bytes.find(std::string(reinterpret_cast<const char*>(value), 8));
    if (at != std::string::npos) break;
  }
  ASSERT_NE(at, std::string::npos);
  bytes[at + 2] ^= 0x04;
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  const std::string error = test::error_of<InputError>([&] { (void)read_checkpoint(file, c.config_hash); });
  EXPECT_EQ(error.rfind(file.string() + ": not a usable checkpoint: " + file.string() + ": dataset '", 0), 0u) << error;
  EXPECT_THAT(error, ::testing::HasSubstr("': cannot read (corrupt storage or checksum mismatch)"));
}

}  // namespace
}  // namespace uhpc::macro
