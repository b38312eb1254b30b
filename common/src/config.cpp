#include "uhpc/config.hpp"
#include "uhpc/did_you_mean.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"

namespace uhpc {

namespace {

using Json = nlohmann::json;
using Pointer = Json::json_pointer;

// ---------------------------------------------------------------------------------------------
// Wording shared by all messages

// Shortest text that reads back to the same double ("300", "0.1", "1e-05"): users see the value
// they wrote, not "300.000000".
std::string format_number(double value) { return fmt::format("{}", value); }

// "a string", "an object", ... as in "expected a number, got a string".
std::string type_phrase(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::object: return "an object";
    case Json::value_t::array: return "an array";
    case Json::value_t::string: return "a string";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return "a number";
    default: return "an unsupported value";
  }
}

std::string expected(const std::string& what, const Json& got) { return "expected " + what + ", got " + type_phrase(got); }

std::string out_of_range(const std::string& value_text, const Range& range) {
  return "value " + value_text + " is out of range, " + range.describe();
}

// "a.b" + "c" -> "a.b.c"; names inside arrays carry their index instead ("a[2]").
std::string child_name(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
std::string element_name(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

// Splits a dotted key. An empty segment ("a..b", ".a", "") can only come from the program, never
// from the user, so it is a logic error rather than an InputError.
std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (parts.back().empty()) throw std::invalid_argument("uhpc::Config: malformed key '" + key + "'");
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

// ---------------------------------------------------------------------------------------------
// "Did you mean" for unknown keys

// Optimal string alignment distance: Levenshtein plus adjacent transpositions, the usual typos.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

// The closest of `candidates` to `name`, or "" when none is close enough to be a plausible typo:
// about one edit in three characters (at least one, at most three), and fewer edits than the
// shorter name has characters ("x" is not a typo of "y").
std::string closest_key(const std::string& name, const std::set<std::string>& candidates) {
  const std::size_t limit = std::clamp<std::size_t>(name.size() / 3, 1, 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& candidate : candidates) {  // sorted: ties go to the first alphabetically
    if (candidate == name) continue;
    const std::size_t distance = edit_distance(name, candidate);
    if (distance < best_distance && distance < std::min(name.size(), candidate.size())) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Reading a file

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

std::string errno_text() { return std::error_code(errno, std::generic_category()).message(); }

std::string read_text_file(const std::string& path) {
  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw_input_error(path, "", "cannot open file (" + errno_text() + ")");
  std::string text;
  char buffer[1 << 16];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, count);
  // A directory opens fine on Linux and fails only here, with EISDIR.
  if (std::ferror(file.get())) throw_input_error(path, "", "cannot read file (" + errno_text() + ")");
  return text;
}

// nlohmann reports the byte offset of the offending character; users need line and column.
std::string line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t index = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(index), '\n'));
  const std::size_t last_newline = index == 0 ? std::string::npos : text.rfind('\n', index - 1);
  const std::size_t column = last_newline == std::string::npos ? index + 1 : index - last_newline;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message is "[json.exception.parse_error.101] parse error at line 3, column 1: syntax
// error while parsing object key - unexpected '}'; expected string literal"; keep the part after
// " - ", which is what the user has to fix.
std::string short_parse_reason(const std::string& what) {
  const std::size_t dash = what.find(" - ");
  if (dash != std::string::npos) return what.substr(dash + 3);
  const std::size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// Documents nest a few levels; one nested thousands deep (a hostile or corrupt input) would overflow
// the stack of every recursive walk (dump for the config hash, copies, flattening), so the parser
// refuses it as it reads, before anything is built.
constexpr int kMaxJsonDepth = 64;
std::string nesting_reason() { return "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"; }

// nlohmann keeps the last of two equal keys without a word; a key written twice is almost always
// an editing mistake (the earlier value silently ignored), so it is rejected. Driven by the
// parser's callback, which reports containers, keys and scalar values as they are read.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string source) : source_(std::move(source)) {}

  bool operator()(int depth, Json::parse_event_t event, Json& parsed) {
    if (depth > kMaxJsonDepth) throw_input_error(source_, current_name(), nesting_reason());
    switch (event) {
      case Json::parse_event_t::object_start: begin_value(); frames_.push_back({false, {}, {}, 0}); break;
      case Json::parse_event_t::array_start: begin_value(); frames_.push_back({true, {}, {}, 0}); break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end: frames_.pop_back(); break;
      case Json::parse_event_t::key: on_key(parsed.get<std::string>()); break;
      case Json::parse_event_t::value: begin_value(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    std::set<std::string> keys;
    std::string key;       // the object's member being read
    std::size_t count;     // the array's elements begun so far
  };

  void begin_value() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().count;
  }

  void on_key(const std::string& key) {
    Frame& frame = frames_.back();
    frame.key = key;
    if (!frame.keys.insert(key).second) throw_input_error(source_, current_name(), "duplicate key");
  }

  std::string current_name() const {
    std::string name;
    for (const Frame& frame : frames_) {
      name = frame.is_array ? element_name(name, frame.count - 1) : child_name(name, frame.key);
    }
    return name;
  }

  std::string source_;
  std::vector<Frame> frames_;
};

Json parse_document(const std::string& text, const std::string& source) {
  DuplicateKeyCheck check(source);
  try {
    return Json::parse(text, [&check](int depth, Json::parse_event_t event, Json& parsed) {
      return check(depth, event, parsed);
    });
  } catch (const Json::parse_error& e) {
    throw_input_error(source, "", "invalid JSON at " + line_and_column(text, e.byte) + ": " + short_parse_reason(e.what()));
  } catch (const Json::exception& e) {  // e.g. "number overflow parsing '1e400'", which has no position
    throw_input_error(source, "", "invalid JSON: " + short_parse_reason(e.what()));
  }
}

void require_object_document(const Json& document, const std::string& source) {
  if (!document.is_object()) throw_input_error(source, "", "top level must be a JSON object, got " + type_phrase(document));
}

std::string trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// An override value is JSON when it parses as JSON (3.5, true, [1,2], {"a":1}, "\"quoted\""), else
// the plain text: --set material.model=afc needs no shell-quoted JSON string.
Json override_value(const std::string& text, const std::string& source, const std::string& key) {
  const auto shallow = [&](int depth, Json::parse_event_t, Json&) {
    if (depth > kMaxJsonDepth) throw_input_error(source, key, "--set value " + nesting_reason());
    return true;
  };
  Json value = Json::parse(text, shallow, /*allow_exceptions=*/false);
  return value.is_discarded() ? Json(text) : value;
}

}  // namespace

std::string closest_name(const std::string& name, const std::set<std::string>& candidates) {
  return closest_key(name, candidates);
}

// ---------------------------------------------------------------------------------------------
// Range

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo);
  const bool has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return "must be in " + std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
           (hi_open ? ")" : "]");
  }
  if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return "";
}

// ---------------------------------------------------------------------------------------------
// Config: shared state and key resolution

struct Config::Shared {
  Json document;
  std::string source;
  // Subtrees read in full (leaves read by a getter, arrays by numbers(), blocks by accept_any()),
  // as JSON pointer strings.
  std::set<std::string> read;
  // Containers a getter went into (section(), or on the way to a nested key): finish() reports
  // their unread members one by one; a container never entered is reported as a whole.
  std::set<std::string> entered;
  // Every member name a getter or has() asked for, by the pointer of its parent: the candidates
  // for "did you mean".
  std::map<std::string, std::set<std::string>> asked;
};

struct Config::Found {
  const Json* node;
  Pointer pointer;
  std::string name;  // dotted, from the document root
};

Config::Config(std::shared_ptr<Shared> shared, Pointer pointer, std::string prefix)
    : shared_(std::move(shared)), pointer_(std::move(pointer)), prefix_(std::move(prefix)) {}

Config Config::load(const std::string& path, const std::vector<std::string>& overrides) {
  return from_json(parse_document(read_text_file(path), path), path, overrides);
}

Config Config::from_json(Json document, std::string source, const std::vector<std::string>& overrides) {
  require_object_document(document, source);
  for (const std::string& assignment : overrides) apply_override(document, assignment, source);
  auto shared = std::make_shared<Shared>();
  shared->document = std::move(document);
  shared->source = std::move(source);
  return Config(std::move(shared), Pointer(), "");
}

std::string Config::full_key(const std::string& key) const {
  if (key.empty()) return prefix_;
  return child_name(prefix_, key);
}

Config::Found Config::at(const std::string& key) const {
  Found found{&shared_->document.at(pointer_), pointer_, prefix_};
  for (const std::string& part : split_key(key)) {
    shared_->asked[found.pointer.to_string()].insert(part);
    if (!found.node->is_object()) fail_at(found, expected("an object", *found.node));
    shared_->entered.insert(found.pointer.to_string());
    found.pointer /= part;
    found.name = child_name(found.name, part);
    const auto it = found.node->find(part);
    if (it == found.node->end()) fail_at(found, "required key is missing");
    found.node = &*it;
  }
  return found;
}

void Config::fail_at(const Found& found, const std::string& reason) const {
  throw_input_error(shared_->source, found.name, reason);
}

void Config::mark_read(const Found& found) const { shared_->read.insert(found.pointer.to_string()); }

// ---------------------------------------------------------------------------------------------
// Typed getters

double Config::number(const std::string& key, const Range& range) const {
  const Found found = at(key);
  if (!found.node->is_number()) fail_at(found, expected("a number", *found.node));
  const double value = found.node->get<double>();
  if (!std::isfinite(value)) fail_at(found, "expected a finite number, got " + format_number(value));
  if (!range.contains(value)) fail_at(found, out_of_range(format_number(value), range));
  mark_read(found);
  return value;
}

long long Config::integer(const std::string& key, const Range& range) const {
  const Found found = at(key);
  const Json& node = *found.node;
  if (!node.is_number()) fail_at(found, expected("an integer", node));
  long long value = 0;
  if (node.is_number_unsigned()) {
    const auto raw = node.get<unsigned long long>();
    if (raw > static_cast<unsigned long long>(LLONG_MAX)) fail_at(found, "value " + std::to_string(raw) + " is too large for an integer");
    value = static_cast<long long>(raw);
  } else if (node.is_number_integer()) {
    value = node.get<long long>();
  } else {
    // Integral floats are accepted: "steps": 1e6 is a natural way to write a count.
    const double real = node.get<double>();
    if (!std::isfinite(real) || real != std::floor(real)) fail_at(found, "expected an integer, got " + format_number(real));
    if (std::fabs(real) >= 9.2e18) fail_at(found, "value " + format_number(real) + " is too large for an integer");
    value = static_cast<long long>(real);
  }
  if (!range.contains(static_cast<double>(value))) fail_at(found, out_of_range(std::to_string(value), range));
  mark_read(found);
  return value;
}

bool Config::flag(const std::string& key) const {
  const Found found = at(key);
  if (!found.node->is_boolean()) fail_at(found, expected("a boolean", *found.node));
  mark_read(found);
  return found.node->get<bool>();
}

std::string Config::text(const std::string& key) const {
  const Found found = at(key);
  if (!found.node->is_string()) fail_at(found, expected("a string", *found.node));
  mark_read(found);
  return found.node->get<std::string>();
}

std::string Config::choice(const std::string& key, std::initializer_list<std::string_view> allowed) const {
  const std::string value = text(key);
  std::string list;
  for (const std::string_view option : allowed) {
    if (value == option) return value;
    list += (list.empty() ? "" : ", ") + std::string(option);
  }
  fail(key, "value '" + value + "' is not one of: " + list);
}

std::vector<double> Config::numbers(const std::string& key, const Range& each, std::size_t min_size) const {
  const Found found = at(key);
  const Json& node = *found.node;
  if (!node.is_array()) fail_at(found, expected("an array of numbers", node));
  if (node.size() < min_size) {
    fail_at(found, "expected at least " + std::to_string(min_size) + (min_size == 1 ? " number" : " numbers") +
                       ", got " + std::to_string(node.size()));
  }
  std::vector<double> values;
  values.reserve(node.size());
  for (std::size_t i = 0; i < node.size(); ++i) {
    const Found element{&node[i], found.pointer / i, element_name(found.name, i)};
    if (!node[i].is_number()) fail_at(element, expected("a number", node[i]));
    const double value = node[i].get<double>();
    if (!std::isfinite(value)) fail_at(element, "expected a finite number, got " + format_number(value));
    if (!each.contains(value)) fail_at(element, out_of_range(format_number(value), each));
    values.push_back(value);
  }
  mark_read(found);
  return values;
}

// ---------------------------------------------------------------------------------------------
// Structure

bool Config::has(const std::string& key) const {
  const Json* node = &shared_->document.at(pointer_);
  Pointer pointer = pointer_;
  for (const std::string& part : split_key(key)) {
    shared_->asked[pointer.to_string()].insert(part);
    if (!node->is_object()) return false;
    const auto it = node->find(part);
    if (it == node->end()) return false;
    node = &*it;
    pointer /= part;
  }
  return true;
}

Config Config::section(const std::string& key) const {
  const Found found = at(key);
  if (!found.node->is_object()) fail_at(found, expected("an object", *found.node));
  shared_->entered.insert(found.pointer.to_string());
  return Config(shared_, found.pointer, found.name);
}

std::vector<Config> Config::sections(const std::string& key, std::size_t min_size) const {
  const Found found = at(key);
  const Json& node = *found.node;
  if (!node.is_array()) fail_at(found, expected("an array of objects", node));
  if (node.size() < min_size) {
    fail_at(found, "expected at least " + std::to_string(min_size) + (min_size == 1 ? " object" : " objects") +
                       ", got " + std::to_string(node.size()));
  }
  shared_->entered.insert(found.pointer.to_string());
  std::vector<Config> result;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const Found element{&node[i], found.pointer / i, element_name(found.name, i)};
    if (!node[i].is_object()) fail_at(element, expected("an object", node[i]));
    shared_->entered.insert(element.pointer.to_string());
    result.push_back(Config(shared_, element.pointer, element.name));
  }
  return result;
}

void Config::accept_any(const std::string& key) const {
  if (has(key)) mark_read(at(key));
}

// Depth first over `node`; throws at the first member not covered by a read.
void Config::check_read(const Json& node, const Pointer& pointer, const std::string& name) const {
  const std::string id = pointer.to_string();
  if (shared_->read.count(id) != 0) return;
  const bool entered = pointer == pointer_ || shared_->entered.count(id) != 0;
  if (entered && node.is_object()) {
    for (const auto& [key, child] : node.items()) check_read(child, pointer / key, child_name(name, key));
    return;
  }
  if (entered && node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i) check_read(node[i], pointer / i, element_name(name, i));
    return;
  }
  std::string reason = "unknown key";
  if (!pointer.empty()) {
    const auto asked = shared_->asked.find(pointer.parent_pointer().to_string());
    const std::string suggestion = asked == shared_->asked.end() ? "" : closest_key(pointer.back(), asked->second);
    if (!suggestion.empty()) reason += " (did you mean '" + suggestion + "'?)";
  }
  throw_input_error(shared_->source, name, reason);
}

void Config::finish() const { check_read(json(), pointer_, prefix_); }

// ---------------------------------------------------------------------------------------------
// Messages and access

std::string Config::error_message(const std::string& key, const std::string& reason) const {
  return input_message(shared_->source, full_key(key), reason);
}

void Config::fail(const std::string& key, const std::string& reason) const { throw InputError(error_message(key, reason)); }

const Json& Config::json() const { return std::as_const(shared_->document).at(pointer_); }

const std::string& Config::source() const { return shared_->source; }

Json without_notes(const Json& doc) {
  if (doc.is_object()) {
    Json out = Json::object();
    for (const auto& [key, value] : doc.items())
      if (key != "notes") out[key] = without_notes(value);
    return out;
  }
  if (doc.is_array()) {
    Json out = Json::array();
    for (const Json& value : doc) out.push_back(without_notes(value));
    return out;
  }
  return doc;
}

std::string Config::hash() const { return fnv1a64_hex(without_notes(shared_->document).dump()); }

std::string Config::hash_including_notes() const { return fnv1a64_hex(shared_->document.dump()); }

// ---------------------------------------------------------------------------------------------
// Overrides

namespace {

[[noreturn]] void malformed_override(const std::string& assignment, const std::string& source) {
  throw_input_error(source, "", "--set '" + assignment + "': expected key.path=value");
}

struct Assignment {
  std::vector<std::string> key;  // dotted path, split
  Json value;
};

// Splits "key.path=value". The user typed the key, so a malformed one is an InputError (split_key's
// logic_error is meant for keys written in the program).
Assignment parse_assignment(const std::string& assignment, const std::string& source) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) malformed_override(assignment, source);
  try {
    const std::string key = trim(assignment.substr(0, equals));
    return {split_key(key), override_value(trim(assignment.substr(equals + 1)), source, key)};
  } catch (const std::invalid_argument&) {
    malformed_override(assignment, source);
  }
}

}  // namespace

void apply_override(Json& document, const std::string& assignment, const std::string& source) {
  Assignment parsed = parse_assignment(assignment, source);
  const std::vector<std::string>& parts = parsed.key;
  require_object_document(document, source);

  Json* node = &document;
  std::string name;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    name = child_name(name, parts[i]);
    auto it = node->find(parts[i]);
    if (it == node->end()) it = node->emplace(parts[i], Json::object()).first;  // created as needed
    if (!it->is_object()) {
      throw_input_error(source, name, "expected an object for --set '" + assignment + "', got " + type_phrase(*it));
    }
    node = &*it;
  }
  (*node)[parts.back()] = std::move(parsed.value);
}

}  // namespace uhpc
