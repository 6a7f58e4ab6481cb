// SPDX-License-Identifier: BSD-3-Clause
// A ParamTable declares each parameter once: its schema takes the defaults from the config
// struct, and reading fills the struct's fields from a validated file.
#include "quad/common/param_table.hpp"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>
#include <vector>

namespace quad::common {
namespace {

enum class Shape { kX, kPlus };

struct Rotor {
  double k_f = 8.0e-6;  // [N s^2/rad^2]
  int count = 4;
};

struct Vehicle {
  double mass = 1.0;  // required: no default in the schema
  Rotor rotor;
  std::array<double, 3> inertia{0.01, 0.01, 0.02};
  Shape shape = Shape::kX;
  bool armed_at_start = false;
  std::string name = "x500";
  std::int64_t step_ns = 4'000'000;
  std::vector<std::string> participants{"plant", "control"};
  std::filesystem::path world = "worlds/demo.yaml";
};

const ParamTable<Rotor>& rotorTable()
{
  static const ParamTable<Rotor> table = [] {
    ParamTable<Rotor> t;
    t.number("rotor.k_f", [](Rotor& r) -> double& { return r.k_f; }, {0.0, 1.0}, "N s^2/rad^2", "thrust coefficient")
        .number("rotor.count", [](Rotor& r) -> int& { return r.count; }, {3, 8}, "", "number of rotors");
    return t;
  }();
  return table;
}

const ParamTable<Vehicle>& vehicleTable()
{
  static const ParamTable<Vehicle> table = [] {
    ParamTable<Vehicle> t;
    t.number("mass", [](Vehicle& v) -> double& { return v.mass; }, {0.01, 100.0}, "kg", "vehicle mass",
             Need::kRequired)
        .include(rotorTable(), [](Vehicle& v) -> Rotor& { return v.rotor; })
        .vector("inertia", [](Vehicle& v) -> std::array<double, 3>& { return v.inertia; }, {0.0, 10.0}, "kg m^2",
                "principal moments")
        .choice("frame", [](Vehicle& v) -> Shape& { return v.shape; }, {{"x", Shape::kX}, {"plus", Shape::kPlus}},
                "rotor layout")
        .flag("armed_at_start", [](Vehicle& v) -> bool& { return v.armed_at_start; }, "arm without a command")
        .text("name", [](Vehicle& v) -> std::string& { return v.name; }, {}, "what the logs call it")
        .seconds("step", [](Vehicle& v) -> std::int64_t& { return v.step_ns; }, {1e-5, 1.0}, "integration step")
        .list("participants", [](Vehicle& v) -> std::vector<std::string>& { return v.participants; },
              "who takes part")
        .path("world", [](Vehicle& v) -> std::filesystem::path& { return v.world; }, "world file");
    return t;
  }();
  return table;
}

TEST(ParamTable, TheSchemaTakesEachDefaultFromTheStructAndLeavesRequiredKeysWithout)
{
  // GIVEN the table's schema
  const ParamSchema& schema = vehicleTable().schema();
  const auto defaultOf = [&](const char* key) { return schema.find(key)->default_value; };
  // THEN the defaults are the struct's initialisers, in the file's units and forms
  EXPECT_FALSE(defaultOf("mass").has_value());
  EXPECT_EQ(std::get<double>(*defaultOf("rotor.k_f")), 8.0e-6);
  EXPECT_EQ(std::get<std::int64_t>(*defaultOf("rotor.count")), 4);
  EXPECT_EQ(std::get<std::vector<double>>(*defaultOf("inertia")), (std::vector<double>{0.01, 0.01, 0.02}));
  EXPECT_EQ(schema.find("inertia")->size, 3U);
  EXPECT_EQ(std::get<std::string>(*defaultOf("frame")), "x");
  EXPECT_EQ(schema.find("frame")->choices, (std::vector<std::string>{"x", "plus"}));
  EXPECT_EQ(std::get<double>(*defaultOf("step")), 0.004);
  EXPECT_EQ(schema.find("step")->unit, "s");
  EXPECT_EQ(std::get<std::string>(*defaultOf("participants")), "plant,control");
  EXPECT_EQ(std::get<std::string>(*defaultOf("world")), "worlds/demo.yaml");
  EXPECT_EQ(schema.find("rotor.count")->type, ParamType::kInt);
  EXPECT_EQ(*schema.find("rotor.count")->max, 8.0);
}

TEST(ParamTable, ReadingFillsEveryFieldFromTheFile)
{
  // GIVEN a file that sets every key
  const Params p = parseParams(
      "mass: 2.5\nrotor: {k_f: 2.0e-6, count: 6}\ninertia: [1, 2, 3]\nframe: plus\narmed_at_start: true\n"
      "name: heavy\nstep: 0.002\nparticipants: ' plant , mapping,'\nworld: /abs/w.yaml\n",
      "/configs/v.yaml", vehicleTable().schema());
  // WHEN the table reads it
  const Vehicle v = vehicleTable().read(p, "/defaults");
  // THEN each field holds the file's value, converted to the field's form
  EXPECT_EQ(v.mass, 2.5);
  EXPECT_EQ(v.rotor.k_f, 2.0e-6);
  EXPECT_EQ(v.rotor.count, 6);
  EXPECT_EQ(v.inertia, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(v.shape, Shape::kPlus);
  EXPECT_TRUE(v.armed_at_start);
  EXPECT_EQ(v.name, "heavy");
  EXPECT_EQ(v.step_ns, 2'000'000);
  EXPECT_EQ(v.participants, (std::vector<std::string>{"plant", "mapping"}));
  EXPECT_EQ(v.world, "/abs/w.yaml");
}

TEST(ParamTable, KeysLeftOutReadAsTheStructsDefaultsAndPathsResolveLikeConfigPath)
{
  // GIVEN a file that sets only the required key and a relative path
  const Params p = parseParams("mass: 3\nworld: w.yaml\n", "/configs/v.yaml", vehicleTable().schema());
  const Vehicle v = vehicleTable().read(p, "/defaults");
  const Vehicle defaults;
  // THEN the rest equals a default-constructed struct, and the path is the file's folder's
  EXPECT_EQ(v.rotor.k_f, defaults.rotor.k_f);
  EXPECT_EQ(v.inertia, defaults.inertia);
  EXPECT_EQ(v.step_ns, defaults.step_ns);
  EXPECT_EQ(v.participants, defaults.participants);
  EXPECT_EQ(v.world, configPath(p, "world", "/defaults"));
  EXPECT_EQ(v.world, std::filesystem::path("/configs/w.yaml"));
}

TEST(ParamTable, TheFileIsValidatedByTheSchemaTheTableMade)
{
  // GIVEN values out of range, of a choice not offered, and a required key missing
  const auto problems = [](const std::string& yaml) {
    try {
      parseParams(yaml, "v.yaml", vehicleTable().schema());
    } catch (const ConfigError& e) {
      return e.problems().size();
    }
    return std::size_t{0};
  };
  // THEN each is refused
  EXPECT_EQ(problems("mass: 2\nrotor: {count: 9}\n"), 1U);
  EXPECT_EQ(problems("mass: 2\nframe: hex\n"), 1U);
  EXPECT_EQ(problems("rotor: {count: 4}\n"), 1U);
  EXPECT_EQ(problems("mass: 2\n"), 0U);
}

TEST(ParamTable, AChoiceWhoseDefaultHasNoNameIsAProgrammingError)
{
  ParamTable<Vehicle> t;
  EXPECT_THROW(t.choice("frame", [](Vehicle& v) -> Shape& { return v.shape; }, {{"plus", Shape::kPlus}}, "layout"),
               std::logic_error);
}

}  // namespace
}  // namespace quad::common
