// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace quad::common {
namespace {

ParamSchema vehicleSchema()
{
  ParamSchema schema;
  schema.addDouble("mass", std::nullopt, 0.01, 100.0, "kg", "vehicle mass")
      .addDouble("rotor.k_f", 8.0e-6, 0.0, 1.0, "N s^2/rad^2", "thrust coefficient")
      .addInt("rotor.count", 4, 3, 8, "", "number of rotors")
      .addVector("inertia", std::vector<double>{0.01, 0.01, 0.02}, 3, 0.0, 10.0, "kg m^2",
                 "principal moments of inertia")
      .addString("frame", "x", {"x", "plus"}, "rotor layout")
      .addBool("armed_at_start", false, "arm without a command");
  return schema;
}

/// Expects parsing to fail with exactly one problem, and returns it.
std::string onlyProblem(const std::string& yaml)
{
  try {
    parseParams(yaml, "vehicle.yaml", vehicleSchema());
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().size(), 1U) << e.what();
    return e.problems().empty() ? "" : e.problems().front();
  }
  ADD_FAILURE() << "accepted: " << yaml;
  return "";
}

TEST(Params, ValidFileLoadsWithDefaultsForKeysLeftOut)
{
  // GIVEN a file that sets some keys, nested and flat
  const Params p = loadParams(QUAD_TEST_DATA_DIR "/vehicle_ok.yaml", vehicleSchema());
  // THEN the given values are read, and the others take their declared defaults
  EXPECT_DOUBLE_EQ(p.getDouble("mass"), 1.5);
  EXPECT_DOUBLE_EQ(p.getDouble("rotor.k_f"), 8.5e-6);
  EXPECT_EQ(p.getInt("rotor.count"), 4);
  EXPECT_EQ(p.getVector("inertia"), (std::vector<double>{0.02, 0.02, 0.04}));
  EXPECT_EQ(p.getString("frame"), "x");
  EXPECT_FALSE(p.getBool("armed_at_start"));
}

TEST(Params, IntegerIsAcceptedWhereANumberIsDeclared)
{
  const Params p = parseParams("mass: 2", "vehicle.yaml", vehicleSchema());
  EXPECT_DOUBLE_EQ(p.getDouble("mass"), 2.0);
}

TEST(Params, UnknownKeyIsRefusedWithASuggestion)
{
  EXPECT_EQ(onlyProblem("mass: 1\nrotor: {kf: 1e-6}"),
            "vehicle.yaml:rotor.kf: 1e-6: unknown key (did you mean 'rotor.k_f'?)");
}

TEST(Params, WrongTypeIsRefused)
{
  EXPECT_EQ(onlyProblem("mass: heavy"), "vehicle.yaml:mass: heavy: expected number");
  EXPECT_EQ(onlyProblem("mass: 1\nrotor: {count: 4.5}"),
            "vehicle.yaml:rotor.count: 4.5: expected integer");
  EXPECT_EQ(onlyProblem("mass: 1\narmed_at_start: maybe"),
            "vehicle.yaml:armed_at_start: maybe: expected bool (true or false)");
  EXPECT_EQ(onlyProblem("mass: [1, 2]"), "vehicle.yaml:mass: [1, 2]: expected number");
}

TEST(Params, OverridesReplaceNestedAndFlatKeysBeforeValidation)
{
  // GIVEN a file and command-line overrides of a nested key, a new key and a map key
  const Params p = parseParams("mass: 1\nrotor: {k_f: 1.0e-6}", "vehicle.yaml", vehicleSchema(),
                               {parseOverride("rotor.k_f=2.0e-6"), parseOverride("frame=plus"),
                                parseOverride("inertia=[1, 2, 3]")});
  // THEN the overrides win and the rest of the file stays
  EXPECT_DOUBLE_EQ(p.getDouble("rotor.k_f"), 2.0e-6);
  EXPECT_EQ(p.getString("frame"), "plus");
  EXPECT_EQ(p.getVector("inertia"), (std::vector<double>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(p.getDouble("mass"), 1.0);
}

TEST(Params, BadOverrideIsRefusedLikeABadFileValue)
{
  try {
    parseParams("mass: 1", "vehicle.yaml", vehicleSchema(), {parseOverride("mass=250")});
    FAIL() << "an out-of-range override was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().front(), "vehicle.yaml:mass: 250: out of range [0.01, 100] kg");
  }
  EXPECT_THROW(parseOverride("mass"), ConfigError);
  EXPECT_THROW(parseOverride("=3"), ConfigError);
}

TEST(Params, OutOfRangeIsRefusedWithTheRangeAndUnit)
{
  EXPECT_EQ(onlyProblem("mass: 250"), "vehicle.yaml:mass: 250: out of range [0.01, 100] kg");
  EXPECT_EQ(onlyProblem("mass: 1\nrotor: {count: 2}"),
            "vehicle.yaml:rotor.count: 2: out of range [3, 8]");
}

TEST(Params, NonFiniteNumbersAreRefused)
{
  EXPECT_EQ(onlyProblem("mass: .nan"), "vehicle.yaml:mass: .nan: not a finite number");
  EXPECT_EQ(onlyProblem("mass: .inf"), "vehicle.yaml:mass: .inf: not a finite number");
  EXPECT_EQ(onlyProblem("mass: 1\ninertia: [0.1, -.inf, 0.1]"),
            "vehicle.yaml:inertia[1]: -.inf: not a finite number");
}

TEST(Params, MissingRequiredKeyIsRefused)
{
  EXPECT_EQ(onlyProblem("frame: x"), "vehicle.yaml:mass: (missing): required key not set");
}

TEST(Params, VectorOfWrongLengthIsRefused)
{
  EXPECT_EQ(onlyProblem("mass: 1\ninertia: [0.1, 0.1]"),
            "vehicle.yaml:inertia: [0.1, 0.1]: expected 3 numbers, got 2");
}

TEST(Params, StringOutsideItsChoicesIsRefused)
{
  EXPECT_EQ(onlyProblem("mass: 1\nframe: hex"), "vehicle.yaml:frame: hex: not one of: x, plus");
}

TEST(Params, KeyWithoutValueIsRefused)
{
  EXPECT_EQ(onlyProblem("mass:"), "vehicle.yaml:mass: null: no value given");
}

TEST(Params, MalformedYamlIsRefusedWithItsLine)
{
  const std::string problem = onlyProblem("mass: 1\nrotor: [1, 2\n");
  EXPECT_EQ(problem.rfind("vehicle.yaml:(line ", 0), 0U) << problem;
}

TEST(Params, TopLevelThatIsNotAMapIsRefused)
{
  EXPECT_EQ(onlyProblem("- 1\n- 2"),
            "vehicle.yaml:(top level): [1, 2]: expected a map of keys to values");
}

TEST(Params, UnreadableFileIsAConfigErrorNamingIt)
{
  try {
    loadParams("/nonexistent/vehicle.yaml", vehicleSchema());
    FAIL() << "accepted a missing file";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/vehicle.yaml: cannot open", 0), 0U)
        << e.what();
  }
}

TEST(Params, EveryProblemIsReportedAtOnce)
{
  try {
    parseParams("mass: -1\ncolour: red\nframe: hex", "vehicle.yaml", vehicleSchema());
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().size(), 3U) << e.what();
  }
}

TEST(ParamSchema, DefaultOutsideItsOwnRangeIsAProgrammingError)
{
  ParamSchema schema;
  EXPECT_THROW(schema.addDouble("gain", 5.0, 0.0, 1.0, "", ""), std::logic_error);
  EXPECT_THROW(schema.addDouble("a", 0.5, 0.0, 1.0, "", "").addBool("a", true, ""),
               std::logic_error);
}

TEST(ParamSchema, DefaultsAloneNeedEveryKeyToHaveOne)
{
  EXPECT_THROW(defaultParams(vehicleSchema()), ConfigError);
  ParamSchema schema;
  schema.addDouble("gain", 0.5, 0.0, 1.0, "", "");
  EXPECT_DOUBLE_EQ(defaultParams(schema).getDouble("gain"), 0.5);
}

}  // namespace
}  // namespace quad::common

namespace quad::common {
namespace {

TEST(Params, ConfigPathsResolveAgainstTheirFileOrTheDefaults)
{
  ParamSchema schema;
  schema.addString("world", "worlds/demo.yaml", {}, "").addString("none", "", {}, "");
  const Params from_file = parseParams("world: ../worlds/open.yaml", "/etc/quad/plant.yaml", schema);
  EXPECT_EQ(configPath(from_file, "world", "/opt/quad/configs"), "/etc/quad/../worlds/open.yaml");
  const Params absolute = parseParams("world: /data/w.yaml", "/etc/quad/plant.yaml", schema);
  EXPECT_EQ(configPath(absolute, "world", "/opt/quad/configs"), "/data/w.yaml");
  const Params defaults = defaultParams(schema);
  EXPECT_EQ(configPath(defaults, "world", "/opt/quad/configs"), "/opt/quad/configs/worlds/demo.yaml");
  EXPECT_TRUE(configPath(defaults, "none", "/opt/quad/configs").empty());
}

}  // namespace
}  // namespace quad::common
