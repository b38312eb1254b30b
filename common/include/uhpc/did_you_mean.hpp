#pragma once
// "Did you mean": the suggestion of unknown configuration keys (Config) and of misspelt subcommands
// (run_main), one rule for both. Defined in config.cpp.
#include <set>
#include <string>

namespace uhpc {

// The closest of `candidates` to `name`, or "" when none is close enough to be a plausible typo: about one
// edit in three characters (at least one, at most three), and fewer edits than the shorter name has.
std::string closest_name(const std::string& name, const std::set<std::string>& candidates);

}  // namespace uhpc
