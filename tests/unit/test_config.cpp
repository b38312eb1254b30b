// Config: typed getters, range checks, overrides, unknown keys and the exact wording of every error
// message (scripts and users read them, so they are part of the contract).
#include "uhpc/config.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "test_support.hpp"
#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

using nlohmann::json;

// The message of the InputError thrown by `action`, or a marker when none (or another kind) is thrown.
std::string input_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("unexpected exception: ") + e.what();
  }
  return "no error";
}

Config make(const char* text, const std::vector<std::string>& overrides = {}) {
  return Config::from_json(json::parse(text), "case.json", overrides);
}

// A file in a fresh directory, removed with the fixture.
class ConfigFile : public uhpc::test::ScratchDirTest {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
};

// ---------------------------------------------------------------------------------------------
// Range

TEST(Range, ContainsRespectsOpenAndClosedEnds) {
  EXPECT_TRUE(Range::any().contains(-1e300));
  EXPECT_FALSE(Range::any().contains(std::nan("")));
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_TRUE(Range::positive().contains(1e-300));
  EXPECT_TRUE(Range::non_negative().contains(0.0));
  EXPECT_TRUE(Range::closed(0, 1).contains(1.0));
  EXPECT_FALSE(Range::open(0, 0.3).contains(0.3));
  EXPECT_TRUE(Range::at_least(2).contains(2.0));
  EXPECT_FALSE(Range::at_least(2).contains(1.999));
}

TEST(Range, Describe) {
  EXPECT_EQ(Range::any().describe(), "");
  EXPECT_EQ(Range::positive().describe(), "must be > 0");
  EXPECT_EQ(Range::non_negative().describe(), "must be >= 0");
  EXPECT_EQ(Range::closed(0, 1).describe(), "must be in [0, 1]");
  EXPECT_EQ(Range::open(0, 0.3).describe(), "must be in (0, 0.3)");
  EXPECT_EQ(Range::at_least(2).describe(), "must be >= 2");
  EXPECT_EQ((Range{-std::numeric_limits<double>::infinity(), 5.0, false, true}).describe(), "must be < 5");
  EXPECT_EQ((Range{-std::numeric_limits<double>::infinity(), 1e-6, false, false}).describe(), "must be <= 1e-06");
  EXPECT_EQ((Range{0.5, 2.5e9, true, false}).describe(), "must be in (0.5, 2500000000]");
}

// ---------------------------------------------------------------------------------------------
// Getters: values

TEST(Config, ReadsEveryType) {
  const Config c = make(R"({"h_m": 0.05, "n": 12, "big": 1e6, "on": true, "name": "afc",
                            "order": "quadratic", "sizes_m": [0.01, 0.02, 0.04]})");
  EXPECT_DOUBLE_EQ(c.number("h_m", Range::positive()), 0.05);
  EXPECT_EQ(c.integer("n", Range::at_least(1)), 12);
  EXPECT_EQ(c.integer("big"), 1000000);  // an integral float is an integer
  EXPECT_TRUE(c.flag("on"));
  EXPECT_EQ(c.text("name"), "afc");
  EXPECT_EQ(c.choice("order", {"linear", "quadratic"}), "quadratic");
  EXPECT_EQ(c.numbers("sizes_m", Range::positive(), 3), (std::vector<double>{0.01, 0.02, 0.04}));
  EXPECT_NO_THROW(c.finish());
}

TEST(Config, IntegerValueIsANumberToo) {
  const Config c = make(R"({"v": 3})");
  EXPECT_DOUBLE_EQ(c.number("v"), 3.0);
}

TEST(Config, DottedKeysAndSectionsReachNestedValues) {
  const Config c = make(R"({"target": {"thickness_m": 0.1, "material": {"density_kg_m3": 2400}}})");
  EXPECT_DOUBLE_EQ(c.number("target.thickness_m"), 0.1);
  const Config material = c.section("target").section("material");
  EXPECT_DOUBLE_EQ(material.number("density_kg_m3"), 2400.0);
  EXPECT_EQ(material.json(), json::parse(R"({"density_kg_m3": 2400})"));
  EXPECT_EQ(material.source(), "case.json");
  EXPECT_NO_THROW(c.finish());
}

TEST(Config, Has) {
  const Config c = make(R"({"a": {"b": 1}, "s": "x"})");
  EXPECT_TRUE(c.has("a"));
  EXPECT_TRUE(c.has("a.b"));
  EXPECT_FALSE(c.has("a.c"));
  EXPECT_FALSE(c.has("s.t"));  // through a non-object: simply absent
  EXPECT_TRUE(c.section("a").has("b"));
}

TEST(Config, SectionsOfAnArray) {
  const Config c = make(R"({"layers": [{"thickness_m": 0.1}, {"thickness_m": 0.2}]})");
  const std::vector<Config> layers = c.sections("layers");
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_DOUBLE_EQ(layers[1].number("thickness_m"), 0.2);
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'layers[0].thickness_m': unknown key");
  EXPECT_DOUBLE_EQ(layers[0].number("thickness_m"), 0.1);
  EXPECT_NO_THROW(c.finish());
}

// ---------------------------------------------------------------------------------------------
// Getters: errors, exact messages

TEST(ConfigErrors, MissingKey) {
  const Config c = make(R"({"target": {"thickness_m": 0.1}})");
  EXPECT_EQ(input_error_of([&] { c.number("velocity_m_s"); }), "case.json: key 'velocity_m_s': required key is missing");
  EXPECT_EQ(input_error_of([&] { c.number("target.width_m"); }), "case.json: key 'target.width_m': required key is missing");
  EXPECT_EQ(input_error_of([&] { c.section("target").number("width_m"); }),
            "case.json: key 'target.width_m': required key is missing");
  EXPECT_EQ(input_error_of([&] { c.section("projectile"); }), "case.json: key 'projectile': required key is missing");
}

TEST(ConfigErrors, WrongType) {
  const Config c = make(R"({"t": {"s": "thick", "n": 1.5, "b": 1, "o": 3, "a": [1, "x"], "l": [1]}})");
  const Config t = c.section("t");
  EXPECT_EQ(input_error_of([&] { t.number("s"); }), "case.json: key 't.s': expected a number, got a string");
  EXPECT_EQ(input_error_of([&] { t.integer("s"); }), "case.json: key 't.s': expected an integer, got a string");
  EXPECT_EQ(input_error_of([&] { t.flag("b"); }), "case.json: key 't.b': expected a boolean, got a number");
  EXPECT_EQ(input_error_of([&] { t.text("n"); }), "case.json: key 't.n': expected a string, got a number");
  EXPECT_EQ(input_error_of([&] { t.choice("b", {"x"}); }), "case.json: key 't.b': expected a string, got a number");
  EXPECT_EQ(input_error_of([&] { t.section("o"); }), "case.json: key 't.o': expected an object, got a number");
  EXPECT_EQ(input_error_of([&] { t.numbers("s"); }), "case.json: key 't.s': expected an array of numbers, got a string");
  EXPECT_EQ(input_error_of([&] { t.numbers("a"); }), "case.json: key 't.a[1]': expected a number, got a string");
  EXPECT_EQ(input_error_of([&] { t.number("a"); }), "case.json: key 't.a': expected a number, got an array");
  EXPECT_EQ(input_error_of([&] { t.sections("o"); }), "case.json: key 't.o': expected an array of objects, got a number");
  EXPECT_EQ(input_error_of([&] { t.sections("l"); }), "case.json: key 't.l[0]': expected an object, got a number");
  EXPECT_EQ(input_error_of([&] { c.number("t"); }), "case.json: key 't': expected a number, got an object");
}

TEST(ConfigErrors, NullAndBooleanAreNotNumbers) {
  const Config c = make(R"({"a": null, "b": false})");
  EXPECT_EQ(input_error_of([&] { c.number("a"); }), "case.json: key 'a': expected a number, got null");
  EXPECT_EQ(input_error_of([&] { c.number("b"); }), "case.json: key 'b': expected a number, got a boolean");
}

TEST(ConfigErrors, PathThroughANonObject) {
  const Config c = make(R"({"target": 5})");
  EXPECT_EQ(input_error_of([&] { c.number("target.thickness_m"); }),
            "case.json: key 'target': expected an object, got a number");
}

TEST(ConfigErrors, NonIntegral) {
  const Config c = make(R"({"steps": 2.5, "huge": 1e300, "max": 18446744073709551615})");
  EXPECT_EQ(input_error_of([&] { c.integer("steps"); }), "case.json: key 'steps': expected an integer, got 2.5");
  EXPECT_EQ(input_error_of([&] { c.integer("huge"); }), "case.json: key 'huge': value 1e+300 is too large for an integer");
  EXPECT_EQ(input_error_of([&] { c.integer("max"); }),
            "case.json: key 'max': value 18446744073709551615 is too large for an integer");
}

TEST(ConfigErrors, OutOfRange) {
  const Config c = make(R"({"h": -1, "nu": 0.5, "n": 1, "sizes": [0.1, -0.2], "p": 0})");
  EXPECT_EQ(input_error_of([&] { c.number("h", Range::positive()); }),
            "case.json: key 'h': value -1 is out of range, must be > 0");
  EXPECT_EQ(input_error_of([&] { c.number("nu", Range::open(0, 0.5)); }),
            "case.json: key 'nu': value 0.5 is out of range, must be in (0, 0.5)");
  EXPECT_EQ(input_error_of([&] { c.integer("n", Range::at_least(2)); }),
            "case.json: key 'n': value 1 is out of range, must be >= 2");
  EXPECT_EQ(input_error_of([&] { c.numbers("sizes", Range::positive()); }),
            "case.json: key 'sizes[1]': value -0.2 is out of range, must be > 0");
  EXPECT_EQ(input_error_of([&] { c.number("p", Range::closed(1e-3, 1)); }),
            "case.json: key 'p': value 0 is out of range, must be in [0.001, 1]");
}

TEST(ConfigErrors, NonFiniteNeverAccepted) {
  json document = {{"x", std::numeric_limits<double>::infinity()},
                   {"v", {1.0, std::nan("")}}};
  const Config c = Config::from_json(document, "memory");
  EXPECT_EQ(input_error_of([&] { c.number("x"); }), "memory: key 'x': expected a finite number, got inf");
  EXPECT_EQ(input_error_of([&] { c.integer("x"); }), "memory: key 'x': expected an integer, got inf");
  EXPECT_EQ(input_error_of([&] { c.numbers("v"); }), "memory: key 'v[1]': expected a finite number, got nan");
}

TEST(ConfigErrors, ArraySize) {
  const Config c = make(R"({"empty": [], "one": [1], "none": []})");
  EXPECT_EQ(input_error_of([&] { c.numbers("empty"); }), "case.json: key 'empty': expected at least 1 number, got 0");
  EXPECT_EQ(input_error_of([&] { c.numbers("one", Range::any(), 2); }),
            "case.json: key 'one': expected at least 2 numbers, got 1");
  EXPECT_EQ(input_error_of([&] { c.sections("none"); }), "case.json: key 'none': expected at least 1 object, got 0");
  EXPECT_TRUE(c.numbers("none", Range::any(), 0).empty());
}

TEST(ConfigErrors, Choice) {
  const Config c = make(R"({"shape": {"order": "foo"}})");
  EXPECT_EQ(input_error_of([&] { c.section("shape").choice("order", {"linear", "quadratic"}); }),
            "case.json: key 'shape.order': value 'foo' is not one of: linear, quadratic");
}

TEST(ConfigErrors, ProgramChecks) {
  const Config c = make(R"({"target": {"thickness_m": 0.1}})");
  const Config target = c.section("target");
  EXPECT_EQ(target.error_message("thickness_m", "must exceed the projectile radius"),
            "case.json: key 'target.thickness_m': must exceed the projectile radius");
  EXPECT_EQ(target.error_message("", "needs a material"), "case.json: key 'target': needs a material");
  EXPECT_EQ(c.error_message("", "is empty"), "case.json: is empty");
  EXPECT_EQ(input_error_of([&] { target.fail("thickness_m", "too thin"); }),
            "case.json: key 'target.thickness_m': too thin");
}

TEST(ConfigErrors, MalformedKeyInTheProgramIsALogicError) {
  const Config c = make(R"({"a": 1})");
  EXPECT_THROW(c.number("a..b"), std::invalid_argument);
  EXPECT_THROW(c.number(""), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// finish(): unknown keys

TEST(ConfigFinish, ReportsTheFirstUnreadKeyDepthFirst) {
  const Config c = make(R"({"a": {"x": 1, "y": 2}, "b": 3})");
  c.number("b");
  c.number("a.y");
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'a.x': unknown key");
  c.number("a.x");
  EXPECT_NO_THROW(c.finish());
}

TEST(ConfigFinish, AnObjectNeverEnteredIsReportedWhole) {
  const Config c = make(R"({"target": {"thickness_m": 0.1}, "zeta": {"q": 1}})");
  c.number("target.thickness_m");
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'zeta': unknown key");
}

TEST(ConfigFinish, SuggestsACloseKeyReadAtTheSameLevel) {
  const Config c = make(R"({"target": {"thickness_m": 0.1, "thicknes_m": 0.2}})");
  c.section("target").number("thickness_m");
  EXPECT_EQ(input_error_of([&] { c.finish(); }),
            "case.json: key 'target.thicknes_m': unknown key (did you mean 'thickness_m'?)");
}

TEST(ConfigFinish, SuggestsAnOptionalKeyAskedWithHas) {
  const Config c = make(R"({"dampnig": 0.1})");
  EXPECT_FALSE(c.has("damping"));
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'dampnig': unknown key (did you mean 'damping'?)");
}

TEST(ConfigFinish, NoSuggestionWhenNothingIsClose) {
  const Config c = make(R"({"velocity_m_s": 800, "colour": "red"})");
  c.number("velocity_m_s");
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'colour': unknown key");
}

TEST(ConfigFinish, UnreadArrayAndEmptyObject) {
  const Config c = make(R"({"a": [1, 2], "e": {}, "n": {}})");
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'a': unknown key");
  c.numbers("a");
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'e': unknown key");
  c.section("e");  // an empty block the program looked at is read
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'n': unknown key");
  c.accept_any("n");
  EXPECT_NO_THROW(c.finish());
}

TEST(ConfigFinish, AcceptAnyCoversASubtreeAndToleratesAbsence) {
  const Config c = make(R"({"notes": {"author": "x", "refs": [1, {"k": 2}]}, "v": 1})");
  c.number("v");
  c.accept_any("notes");
  c.accept_any("comment");  // absent: nothing to do
  EXPECT_NO_THROW(c.finish());
}

TEST(ConfigFinish, SectionSharesTheRecordAndChecksItsOwnSubtree) {
  const Config c = make(R"({"target": {"thickness_m": 0.1, "extra": 1}, "other": 2})");
  const Config target = c.section("target");
  target.number("thickness_m");
  EXPECT_EQ(input_error_of([&] { target.finish(); }), "case.json: key 'target.extra': unknown key");
  c.number("target.extra");  // read through the root: the section sees it
  EXPECT_NO_THROW(target.finish());
  EXPECT_EQ(input_error_of([&] { c.finish(); }), "case.json: key 'other': unknown key");
}

TEST(ConfigFinish, CopiesShareTheRecord) {
  const Config c = make(R"({"a": 1})");
  const Config copy = c;  // NOLINT(performance-unnecessary-copy-initialization)
  copy.number("a");
  EXPECT_NO_THROW(c.finish());
}

// ---------------------------------------------------------------------------------------------
// Overrides

TEST(ConfigOverride, ValuesAreJsonWhenValidElseText) {
  const Config c = make(R"({"a": {"b": 1}})",
                        {"a.b=2.5", "flag=true", "list=[1, 2]", "obj={\"k\": 3}", "word=afc", "quoted=\"7\"",
                         "empty=", "spaced = 4 "});
  EXPECT_DOUBLE_EQ(c.number("a.b"), 2.5);
  EXPECT_TRUE(c.flag("flag"));
  EXPECT_EQ(c.numbers("list"), (std::vector<double>{1, 2}));
  EXPECT_EQ(c.integer("obj.k"), 3);
  EXPECT_EQ(c.text("word"), "afc");
  EXPECT_EQ(c.text("quoted"), "7");
  EXPECT_EQ(c.text("empty"), "");
  EXPECT_EQ(c.integer("spaced"), 4);
  EXPECT_NO_THROW(c.finish());
}

TEST(ConfigOverride, CreatesIntermediateObjectsAndLaterWins) {
  const Config c = make(R"({})", {"x.y.z=1", "x.y.z=2", "x.w=\"s\""});
  EXPECT_EQ(c.json(), json::parse(R"({"x": {"y": {"z": 2}, "w": "s"}})"));
}

TEST(ConfigOverride, ReplacingAnObjectGivesATypeErrorLater) {
  const Config c = make(R"({"target": {"thickness_m": 0.1}})", {"target=5"});
  EXPECT_EQ(input_error_of([&] { c.section("target"); }), "case.json: key 'target': expected an object, got a number");
}

TEST(ConfigOverride, TypoIsCaughtByFinish) {
  const Config c = make(R"({"target": {"thickness_m": 0.1}})", {"target.thicknes_m=0.2"});
  EXPECT_DOUBLE_EQ(c.number("target.thickness_m"), 0.1);
  EXPECT_EQ(input_error_of([&] { c.finish(); }),
            "case.json: key 'target.thicknes_m': unknown key (did you mean 'thickness_m'?)");
}

TEST(ConfigOverride, Malformed) {
  EXPECT_EQ(input_error_of([&] { make("{}", {"foo"}); }), "case.json: --set 'foo': expected key.path=value");
  EXPECT_EQ(input_error_of([&] { make("{}", {"=3"}); }), "case.json: --set '=3': expected key.path=value");
  EXPECT_EQ(input_error_of([&] { make("{}", {"a..b=3"}); }), "case.json: --set 'a..b=3': expected key.path=value");
  EXPECT_EQ(input_error_of([&] { make("{}", {"a.=3"}); }), "case.json: --set 'a.=3': expected key.path=value");
}

TEST(ConfigOverride, DescendingIntoANonObjectNamesTheKey) {
  EXPECT_EQ(input_error_of([&] { make(R"({"a": {"b": 3}})", {"a.b.c=1"}); }),
            "case.json: key 'a.b': expected an object for --set 'a.b.c=1', got a number");
  EXPECT_EQ(input_error_of([&] { make(R"({"a": [1]})", {"a.x=1"}); }),
            "case.json: key 'a': expected an object for --set 'a.x=1', got an array");
}

TEST(ConfigOverride, ApplyOverrideDirectly) {
  json document = json::object();
  apply_override(document, "solver.cfl=0.4", "built-in");
  EXPECT_EQ(document, json::parse(R"({"solver": {"cfl": 0.4}})"));
  json array = json::array();
  EXPECT_EQ(input_error_of([&] { apply_override(array, "a=1", "built-in"); }),
            "built-in: top level must be a JSON object, got an array");
}

// ---------------------------------------------------------------------------------------------
// Documents and files

TEST(ConfigDocument, TopLevelMustBeAnObject) {
  EXPECT_EQ(input_error_of([] { Config::from_json(json::parse("[1, 2]"), "list.json"); }),
            "list.json: top level must be a JSON object, got an array");
}

TEST_F(ConfigFile, LoadsAndAppliesOverrides) {
  const std::string path = write("case.json", R"({"target": {"thickness_m": 0.1}, "velocity_m_s": 800})");
  const Config c = Config::load(path, {"velocity_m_s=1000"});
  EXPECT_EQ(c.source(), path);
  EXPECT_DOUBLE_EQ(c.number("target.thickness_m"), 0.1);
  EXPECT_DOUBLE_EQ(c.number("velocity_m_s"), 1000.0);
  EXPECT_NO_THROW(c.finish());
}

TEST_F(ConfigFile, OverrideErrorsNameTheFile) {
  const std::string path = write("case.json", R"({"a": 1})");
  EXPECT_EQ(input_error_of([&] { Config::load(path, {"nonsense"}); }), path + ": --set 'nonsense': expected key.path=value");
  EXPECT_EQ(input_error_of([&] { Config::load(path, {"a.b=2"}); }),
            path + ": key 'a': expected an object for --set 'a.b=2', got a number");
}

TEST_F(ConfigFile, MissingFile) {
  const std::string path = (dir_ / "absent.json").string();
  EXPECT_EQ(input_error_of([&] { Config::load(path); }), path + ": cannot open file (No such file or directory)");
}

TEST_F(ConfigFile, DirectoryIsNotAFile) {
  EXPECT_EQ(input_error_of([&] { Config::load(dir_.string()); }), dir_.string() + ": cannot read file (Is a directory)");
}

TEST_F(ConfigFile, InvalidJsonGivesLineAndColumn) {
  const std::string trailing_comma = write("comma.json", "{\n  \"a\": 1,\n}\n");
  EXPECT_EQ(input_error_of([&] { Config::load(trailing_comma); }),
            trailing_comma + ": invalid JSON at line 3, column 1: unexpected '}'; expected string literal");
  const std::string unterminated = write("open.json", "{\n  \"a\": 1\n");
  EXPECT_EQ(input_error_of([&] { Config::load(unterminated); }),
            unterminated + ": invalid JSON at line 3, column 1: unexpected end of input; expected '}'");
  const std::string empty = write("empty.json", "");
  EXPECT_EQ(input_error_of([&] { Config::load(empty); }),
            empty + ": invalid JSON at line 1, column 1: unexpected end of input; expected '[', '{', or a literal");
  const std::string overflow = write("overflow.json", R"({"a": 1e400})");
  EXPECT_EQ(input_error_of([&] { Config::load(overflow); }), overflow + ": invalid JSON: number overflow parsing '1e400'");
}

TEST_F(ConfigFile, TopLevelNotAnObject) {
  const std::string path = write("list.json", "[1, 2, 3]");
  EXPECT_EQ(input_error_of([&] { Config::load(path); }), path + ": top level must be a JSON object, got an array");
}

TEST_F(ConfigFile, DuplicateKey) {
  const std::string top = write("top.json", R"({"v": 1, "w": 2, "v": 3})");
  EXPECT_EQ(input_error_of([&] { Config::load(top); }), top + ": key 'v': duplicate key");
  const std::string nested = write("nested.json", R"({"a": [0, [5], {"b": {"c": 1, "c": 2}}], "v": 1})");
  EXPECT_EQ(input_error_of([&] { Config::load(nested); }), nested + ": key 'a[2].b.c': duplicate key");
  // The same name in different objects is fine.
  const std::string fine = write("fine.json", R"({"a": {"x": 1}, "b": {"x": 2}, "l": [{"x": 1}, {"x": 2}]})");
  EXPECT_NO_THROW(Config::load(fine));
}

// A document nested 60 000 deep (in a file or a --set value) crashed the recursive walks (the config
// hash's dump): it is refused as it is read, with the key where it got too deep. 64 levels still load.
TEST_F(ConfigFile, DeepNestingIsRefusedAsItIsRead) {
  const auto nested = [](int depth) { return std::string(depth, '[') + "1" + std::string(depth, ']'); };
  const std::string deep = write("deep.json", "{\"a\": " + nested(60000) + "}");
  const std::string message = input_error_of([&] { Config::load(deep); });
  EXPECT_EQ(message.rfind(deep + ": key 'a[0][0]", 0), 0u) << message.substr(0, 200);
  EXPECT_NE(message.find("': nested deeper than 64 levels"), std::string::npos) << message.substr(0, 200);
  const std::string ok = write("ok.json", "{\"a\": " + nested(63) + "}");
  EXPECT_EQ(Config::load(ok).hash().size(), 16u);
  const std::string set = input_error_of([&] { Config::load(ok, {"b=" + nested(60000)}); });
  EXPECT_EQ(set, ok + ": key 'b': --set value nested deeper than 64 levels");
}

// ---------------------------------------------------------------------------------------------
// hash()

TEST(ConfigHash, IndependentOfKeyOrderAndChangedByOverrides) {
  const Config a = make(R"({"x": 1, "y": {"p": [1, 2], "q": "s"}})");
  const Config b = make(R"({"y": {"q": "s", "p": [1, 2]}, "x": 1})");
  const Config c = make(R"({"x": 1, "y": {"p": [1, 2], "q": "s"}})", {"x=2"});
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_NE(a.hash(), c.hash());
  EXPECT_EQ(a.hash().size(), 16u);
  EXPECT_EQ(a.section("y").hash(), a.hash());  // always the whole document
  EXPECT_EQ(a.hash(), make(R"({"x": 1, "y": {"p": [1, 2], "q": "s"}})", {"x=1"}).hash());
}

// A docs edit makes no result stale (issue 50): the notes, at any depth, are not hashed; every value is.
TEST(ConfigHash, LeavesOutTheNotesAtAnyDepth) {
  const Config plain = make(R"({"x": 1, "y": {"p": [1, {"q": 2}]}})");
  const Config noted = make(R"({"notes": "why x is 1", "x": 1, "y": {"notes": "a", "p": [1, {"q": 2, "notes": "b"}]}})");
  const Config edited = make(R"({"notes": "edited", "x": 1, "y": {"notes": "c", "p": [1, {"q": 2, "notes": "d"}]}})");
  EXPECT_EQ(plain.hash(), noted.hash());
  EXPECT_EQ(noted.hash(), edited.hash());
  EXPECT_NE(noted.hash(), make(R"({"notes": "why x is 1", "x": 1, "y": {"notes": "a", "p": [1, {"q": 3}]}})").hash());
  EXPECT_NE(noted.hash(), make(R"({"notes": "why x is 1", "x": 1, "y": {"p": [1, {"q": 2}]}, "z": "text"})").hash());
  // The former scheme hashed the whole document, notes too: only to recognise results recorded then.
  EXPECT_EQ(plain.hash_including_notes(), plain.hash());
  EXPECT_NE(noted.hash_including_notes(), edited.hash_including_notes());
  EXPECT_NE(noted.hash_including_notes(), noted.hash());
}

}  // namespace
}  // namespace uhpc
