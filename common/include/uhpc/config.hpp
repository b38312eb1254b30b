#pragma once
// JSON configuration with validation. Every problem is reported as one InputError whose message names
// the file, the key (dotted path) and the reason, in the format of input_message():
//   "<file>: key 'target.thickness_m': expected a number, got a string"
// Reading is by explicit typed getters; the keys read are recorded, and finish() rejects any key in
// the file that no getter asked for (a misspelt key is an error, never silently ignored).
//
// Typical use in a driver:
//   Config cfg = Config::load(path, overrides);          // overrides from --set
//   const Config target = cfg.section("target");
//   const double h = target.number("thickness_m", Range::positive());
//   ...
//   cfg.finish();                                         // unknown keys, e.g. a typo in --set
//
// The reasons used in messages (after "<file>: key '<key>': "):
//   required key is missing
//   expected a number, got a string        (also: an integer, a boolean, a string, an object,
//                                           an array of numbers, an array of objects)
//   expected a finite number, got inf
//   expected an integer, got 2.5
//   value -1 is out of range, must be > 0
//   value 'foo' is not one of: linear, quadratic
//   expected at least 2 numbers, got 1
//   unknown key (did you mean 'thickness_m'?)
// Keys inside arrays are written with an index: "cell_sizes_m[2]", "layers[0].thickness_m".
//
// A Config and its sections share one record of what was read; the getters update that record
// through const methods, so a Config must not be read from several threads at once.
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace uhpc {

// A closed/open interval for range checks, with a human description used in error messages.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }

  bool contains(double v) const;
  // "must be > 0", "must be in [0, 1]", "must be in (0, 0.3)", "must be >= 2", "" for any().
  std::string describe() const;
};

class Config {
 public:
  // Reads and parses `path`, then applies the overrides ("key.path=value", the value parsed as JSON
  // when it is valid JSON, else taken as a string). Errors: file missing/unreadable, invalid JSON
  // (with line and column), top level not an object, malformed override.
  static Config load(const std::string& path, const std::vector<std::string>& overrides = {});
  // Same validation for an in-memory document; `source` names it in error messages.
  static Config from_json(nlohmann::json document, std::string source,
                          const std::vector<std::string>& overrides = {});

  // Typed getters for required keys. `key` is a dotted path relative to this config's root.
  double number(const std::string& key, const Range& range = Range::any()) const;  // finite
  long long integer(const std::string& key, const Range& range = Range::any()) const;
  bool flag(const std::string& key) const;
  std::string text(const std::string& key) const;
  // A string that must be one of `allowed`; the error lists them.
  std::string choice(const std::string& key, std::initializer_list<std::string_view> allowed) const;
  // A non-empty array of numbers, each in `each`, with at least `min_size` entries.
  std::vector<double> numbers(const std::string& key, const Range& each = Range::any(),
                              std::size_t min_size = 1) const;

  bool has(const std::string& key) const;
  // True when the key exists (an optional entry); records the key for finish()'s suggestions but
  // does not count it as read.
  // A nested object as a Config that shares this one's record of read keys and its source name.
  Config section(const std::string& key) const;
  // A non-empty array of objects (e.g. layers), each as a section named "key[i]", with at least
  // `min_size` entries.
  std::vector<Config> sections(const std::string& key, std::size_t min_size = 1) const;
  // Marks a whole subtree as read without validating it (for free-form blocks such as notes).
  // Does nothing when the key is absent, so such blocks stay optional.
  void accept_any(const std::string& key) const;

  // Throws for the first key below this config's root that no getter read, in depth-first order
  // with keys sorted (nlohmann::json keeps objects sorted, so "document order" is key order).
  // An unread object that was never entered is reported as a whole ("targt", not "targt.x").
  // Call once all reading is done.
  void finish() const;

  // Builds an InputError message for this config's file and a key below this config's root.
  std::string error_message(const std::string& key, const std::string& reason) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  const nlohmann::json& json() const;   // the effective document (overrides applied), this root
  const std::string& source() const;    // the file name (or source given to from_json)
  // fnv1a64_hex of the effective whole document, dumped canonically (sorted keys, no spaces), without
  // its free text: every member named "notes", at any depth, is left out. Notes document a file (the
  // programs accept them and never read them), so editing one changes no hash and makes no result stale.
  std::string hash() const;
  // The same with the notes: how results were hashed before 2026-12-06, only to recognise finished work
  // recorded then (a reloaded cell, a kept run), which is re-stamped with hash().
  std::string hash_including_notes() const;

 private:
  struct Shared;
  struct Found;  // a resolved key: its node, JSON pointer and dotted name
  Config(std::shared_ptr<Shared> shared, nlohmann::json::json_pointer pointer, std::string prefix);
  Found at(const std::string& key) const;  // throws "required key is missing"
  std::string full_key(const std::string& key) const;
  [[noreturn]] void fail_at(const Found& found, const std::string& reason) const;
  void mark_read(const Found& found) const;
  void check_read(const nlohmann::json& node, const nlohmann::json::json_pointer& pointer,
                  const std::string& name) const;

  std::shared_ptr<Shared> shared_;
  nlohmann::json::json_pointer pointer_;  // where this section's root is in the document
  std::string prefix_;  // dotted path of this section within the document ("" at the root)
};

// Applies one "key.path=value" override to a document (used by Config::load; exposed for tests and
// for programs that build their configs in memory). Throws InputError naming `source`.
void apply_override(nlohmann::json& document, const std::string& assignment, const std::string& source);

// `doc` without its free text: every object member named "notes", at any depth (what Config::hash
// leaves out; for other documents that identify a result, such as a section hashed on its own).
nlohmann::json without_notes(const nlohmann::json& doc);

}  // namespace uhpc
