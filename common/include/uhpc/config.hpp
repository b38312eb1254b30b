#pragma once
// JSON configuration with validation. Every problem is reported as one InputError whose message names
// the file, the key (dotted path) and the reason, in the format of input_message():
//   "<file>: key 'target.thickness_m': expected a number, got a string"
// Reading is by explicit typed getters; the keys read are recorded, and finish() rejects any key in
// the file that no getter asked for (a misspelt key is an error, never silently ignored).
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
  // A nested object as a Config that shares this one's record of read keys and its source name.
  Config section(const std::string& key) const;
  // Marks a whole subtree as read without validating it (for free-form blocks such as notes).
  void accept_any(const std::string& key) const;

  // Throws for the first key (in document order) that no getter read. Call once all reading is done.
  void finish() const;

  // Builds an InputError message for this config's file and a key below this config's root.
  std::string error_message(const std::string& key, const std::string& reason) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  const nlohmann::json& json() const;   // the effective document (overrides applied), this root
  const std::string& source() const;    // the file name (or source given to from_json)
  // fnv1a64_hex of the effective whole document, dumped canonically (sorted keys, no spaces).
  std::string hash() const;

 private:
  struct Shared;
  Config(std::shared_ptr<Shared> shared, std::string prefix);
  const nlohmann::json& at(const std::string& key) const;  // throws "missing"
  std::string full_key(const std::string& key) const;

  std::shared_ptr<Shared> shared_;
  std::string prefix_;  // dotted path of this section within the document ("" at the root)
};

// Applies one "key.path=value" override to a document (used by Config::load; exposed for tests and
// for programs that build their configs in memory). Throws InputError naming `source`.
void apply_override(nlohmann::json& document, const std::string& assignment, const std::string& source);

}  // namespace uhpc
