// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/world.hpp"

#include <gtest/gtest.h>

#include <random>

#include "quad/common/params.hpp"
#include "quad/world/world_file.hpp"

namespace quad::world {
namespace {

World single(const Obstacle& o)
{
  return World(Bounds{Vector3(-50, -50, 0), Vector3(50, 50, 20)}, Vector3::Zero(), Vector3(1, 1, 1), {o});
}

TEST(World, RayHitsABoxAtTheExactDistance)
{
  const World w = single(Obstacle::makeBox({Vector3(10, 0, 2), Vector3(2, 2, 4), 0.0}));
  const auto hit = w.raycast(Vector3(0, 0, 2), Vector3::UnitX(), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->distance, 9.0);
  EXPECT_EQ(hit->obstacle, 0);
  // Turned 45°: the ray meets the vertical edge at x = 10 − √2.
  const World turned = single(Obstacle::makeBox({Vector3(10, 0, 2), Vector3(2, 2, 4), geometry::kPi / 4}));
  EXPECT_NEAR(turned.raycast(Vector3(0, 0, 2), Vector3::UnitX(), 100.0)->distance, 10.0 - std::sqrt(2.0), 1e-12);
  // Above the box, the ray passes.
  EXPECT_FALSE(w.raycast(Vector3(0, 0, 4.5), Vector3::UnitX(), 100.0).has_value());
  // Beyond max range: no hit.
  EXPECT_FALSE(w.raycast(Vector3(0, 0, 2), Vector3::UnitX(), 8.9).has_value());
}

TEST(World, RayHitsCylindersSpheresAndTheGround)
{
  const World cyl = single(Obstacle::makeCylinder({5, 0, 0.5, 3}));
  EXPECT_DOUBLE_EQ(cyl.raycast(Vector3(0, 0, 1), Vector3::UnitX(), 100)->distance, 4.5);
  EXPECT_DOUBLE_EQ(cyl.raycast(Vector3(5, 0, 10), -Vector3::UnitZ(), 100)->distance, 7.0);  // top cap
  const World sph = single(Obstacle::makeSphere({Vector3(0, 0, 10), 1.0}));
  EXPECT_DOUBLE_EQ(sph.raycast(Vector3(0, 0, 5), Vector3::UnitZ(), 100)->distance, 4.0);
  const auto ground = sph.raycast(Vector3(0, 0, 2), Vector3(1, 0, -1).normalized(), 100);
  ASSERT_TRUE(ground.has_value());
  EXPECT_EQ(ground->obstacle, World::kGround);
  EXPECT_NEAR(ground->distance, 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(World, SignedDistanceIsNegativeInsideAndExactOutside)
{
  const Obstacle box = Obstacle::makeBox({Vector3(0, 0, 1), Vector3(2, 2, 2), 0.0});
  EXPECT_DOUBLE_EQ(box.signedDistance(Vector3(3, 0, 1)), 2.0);
  EXPECT_DOUBLE_EQ(box.signedDistance(Vector3(2, 2, 1)), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(box.signedDistance(Vector3(0, 0, 1)), -1.0);
  const Obstacle cyl = Obstacle::makeCylinder({0, 0, 1, 5});
  EXPECT_DOUBLE_EQ(cyl.signedDistance(Vector3(3, 0, 2)), 2.0);
  EXPECT_DOUBLE_EQ(cyl.signedDistance(Vector3(0, 0, 7)), 2.0);
  EXPECT_DOUBLE_EQ(cyl.signedDistance(Vector3(4, 0, 9)), 5.0);  // past the rim: 3-4-5
}

TEST(World, IndexedRaycastEqualsBruteForceInAForest)
{
  const World w = parseWorld(R"(
bounds: {min: [-5, -30, 0], max: [105, 30, 20]}
start: [0, 0, 1]
goal: [100, 0, 2]
obstacles:
  - {type: sphere, center: [50, 0, 12], radius: 3}
  - {type: box, center: [30, 5, 2], size: [4, 1, 4], yaw: 0.7}
generators:
  - {type: forest, seed: 11, min: [0, -28], max: [100, 28], density: 0.18, radius: [0.2, 0.8], height: [4, 15]}
)",
                             "forest.yaml");
  ASSERT_GT(w.obstacles().size(), 1000U);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> x(-4.0, 104.0);
  std::uniform_real_distribution<double> y(-29.0, 29.0);
  std::uniform_real_distribution<double> z(0.1, 19.0);
  int hits = 0;
  for (int k = 0; k < 5000; ++k) {
    const Vector3 o(x(rng), y(rng), z(rng));
    const Vector3 d = Vector3(u(rng), u(rng), 0.3 * u(rng)).normalized();
    const auto fast = w.raycast(o, d, 40.0);
    const auto slow = w.raycastBruteForce(o, d, 40.0);
    ASSERT_EQ(fast.has_value(), slow.has_value()) << o.transpose() << " / " << d.transpose();
    if (fast) {
      ++hits;
      EXPECT_EQ(fast->obstacle, slow->obstacle);
      EXPECT_DOUBLE_EQ(fast->distance, slow->distance);
    }
  }
  EXPECT_GT(hits, 1000);
}

TEST(World, ContactsFindObstaclesTouchingTheSphereAndTheBounds)
{
  const World w(Bounds{Vector3(0, 0, 0), Vector3(20, 20, 10)}, Vector3(1, 1, 0), Vector3(19, 19, 2),
                {Obstacle::makeBox({Vector3(10, 10, 2), Vector3(2, 2, 4), 0.0}),
                 Obstacle::makeCylinder({15, 5, 0.5, 6})});
  EXPECT_TRUE(w.contacts(Vector3(5, 5, 2), 0.3).empty());
  EXPECT_EQ(w.contacts(Vector3(11.2, 10, 2), 0.3), std::vector<int>{0});
  EXPECT_TRUE(w.contacts(Vector3(11.4, 10, 2), 0.3).empty());
  EXPECT_EQ(w.contacts(Vector3(15.7, 5, 3), 0.3), std::vector<int>{1});
  EXPECT_EQ(w.contacts(Vector3(0.2, 5, 3), 0.3), std::vector<int>{World::kBounds});
  EXPECT_EQ(w.contacts(Vector3(5, 5, 9.8), 0.3), std::vector<int>{World::kBounds});
  EXPECT_TRUE(w.contacts(Vector3(5, 5, 0.0), 0.3).empty());  // the ground is contact, not collision
}

TEST(WorldFile, TheDesignExampleLoads)
{
  const World w = loadWorld(std::string(QUAD_CONFIG_DIR) + "/worlds/demo.yaml");
  EXPECT_EQ(w.start(), Vector3(0, 0, 0));
  EXPECT_EQ(w.goal(), Vector3(50, 0, 2));
  ASSERT_GT(w.obstacles().size(), 3U);
  EXPECT_EQ(w.obstacles()[0].kind, Obstacle::Kind::kBox);
  EXPECT_EQ(w.obstacles()[1].kind, Obstacle::Kind::kCylinder);
  EXPECT_EQ(w.obstacles()[2].kind, Obstacle::Kind::kSphere);
  const World walls = loadWorld(std::string(QUAD_CONFIG_DIR) + "/worlds/walls.yaml");
  EXPECT_EQ(walls.obstacles().size(), 6U);  // three walls, each in two parts
}

TEST(WorldFile, GeneratorsAreDeterministicAndKeepStartAndGoalClear)
{
  const std::string text = R"(
bounds: {min: [-5, -10, 0], max: [60, 10, 10]}
start: [10, 0, 0]
goal: [40, 0, 2]
generators:
  - {type: forest, seed: 7, min: [0, -10], max: [60, 10], density: 0.3, radius: [0.2, 0.6], height: [5, 9], clearance: 3}
  - {type: walls, seed: 2, min: [20, -10], max: [30, 10], count: 2, gap: 2, thickness: 0.3, height: 5}
)";
  const World a = parseWorld(text, "a.yaml");
  const World b = parseWorld(text, "b.yaml");
  ASSERT_EQ(a.obstacles().size(), b.obstacles().size());
  for (std::size_t i = 0; i < a.obstacles().size(); ++i) {
    Vector3 alo, ahi, blo, bhi;
    a.obstacles()[i].bounds(alo, ahi);
    b.obstacles()[i].bounds(blo, bhi);
    EXPECT_EQ(alo, blo);
    EXPECT_EQ(ahi, bhi);
  }
  for (const auto& o : a.obstacles()) {
    if (o.kind == Obstacle::Kind::kCylinder) {
      EXPECT_GT(std::hypot(o.cylinder.x - 10, o.cylinder.y) - o.cylinder.radius, 3.0);
      EXPECT_GT(std::hypot(o.cylinder.x - 40, o.cylinder.y) - o.cylinder.radius, 3.0);
    }
  }
}

TEST(WorldFile, AForestWithAGapKeepsItsTreesApartAndItsCount)
{
  // GIVEN the benchmark's forest: trees 0.5-0.7 m thick, one per 25 m², kept 0.5 m apart
  const std::string text = R"(
bounds: {min: [0, -15, 0], max: [60, 15, 6]}
start: [10, 0, 0]
goal: [50, 0, 2]
generators:
  - {type: forest, seed: 3, min: [0, -15], max: [60, 15], density: 0.04, radius: [0.25, 0.35], height: [8, 10], clearance: 0, gap: 0.5}
)";
  const World w = parseWorld(text, "forest.yaml");
  // THEN it has its 72 trees, none nearer another than the gap
  ASSERT_EQ(w.obstacles().size(), 72U);
  for (std::size_t i = 0; i < w.obstacles().size(); ++i) {
    for (std::size_t j = i + 1; j < w.obstacles().size(); ++j) {
      const Cylinder& a = w.obstacles()[i].cylinder;
      const Cylinder& b = w.obstacles()[j].cylinder;
      EXPECT_GE(std::hypot(a.x - b.x, a.y - b.y) - a.radius - b.radius, 0.5);
    }
  }
  // ... and a gap no forest of that density has room for is refused, naming the key
  try {
    parseWorld(std::string(text).replace(text.find("gap: 0.5"), 8, "gap: 9.0"), "forest.yaml");
    FAIL() << "an impossible gap was taken";
  } catch (const common::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1U);
    EXPECT_EQ(e.problems().front().rfind("forest.yaml:generators[0].gap: 9", 0), 0U) << e.problems().front();
  }
}

TEST(WorldFile, BadInputNamesFileKeyAndValue)
{
  const auto problems = [](const std::string& text) {
    try {
      parseWorld(text, "w.yaml");
    } catch (const common::ConfigError& e) {
      return e.problems();
    }
    return std::vector<std::string>{"accepted"};
  };
  const std::string head = "bounds: {min: [0, 0, 0], max: [10, 10, 10]}\nstart: [1, 1, 0]\ngoal: [9, 9, 2]\n";
  EXPECT_EQ(problems(head + "obstacles:\n  - {type: sphere, center: [5, 5, 5], radius: -1}"),
            std::vector<std::string>{"w.yaml:obstacles[0].radius: -1: out of range [1e-06, 100000]"});
  EXPECT_EQ(problems(head + "obstacles:\n  - {center: [5, 5, 5], radius: 1}\n  - {type: sphere, center: [1, 1, 1]}"),
            (std::vector<std::string>{"w.yaml:obstacles[0].type: (missing): expected box, cylinder or sphere",
                                      "w.yaml:obstacles[1].radius: (missing): required"}));
  EXPECT_EQ(problems(head + "obstacles:\n  - {type: cone, center: [5, 5, 5]}"),
            std::vector<std::string>{"w.yaml:obstacles[0].type: cone: expected box, cylinder or sphere"});
  EXPECT_EQ(problems(head + "obstacles:\n  - {type: box, center: [5, 5], size: [1, 1, 1]}"),
            std::vector<std::string>{"w.yaml:obstacles[0].center: [5, 5]: expected a list of 3 numbers"});
  EXPECT_EQ(problems(head + "obstacles:\n  - {type: sphere, center: [5, 5, .nan], radius: 1}"),
            std::vector<std::string>{"w.yaml:obstacles[0].center[2]: .nan: not a finite number"});
  EXPECT_EQ(problems(head + "colour: red"),
            std::vector<std::string>{"w.yaml:colour: red: unknown key (expected one of: bounds, "
                                     "generators, goal, index_cell_size, maps, obstacles, start)"});
  EXPECT_EQ(problems("bounds: {min: [0, 0, 0], max: [10, 10, 10]}\nstart: [11, 1, 0]\ngoal: [9, 9, 2]"),
            std::vector<std::string>{"w.yaml:start: [11, 1, 0]: outside the bounds"});
  EXPECT_EQ(problems(head + "generators:\n  - {type: forest, seed: 1, min: [0, 0], max: [10, 10], "
                            "density: 0.1, radius: [0.5, 0.2], height: [1, 2]}"),
            std::vector<std::string>{"w.yaml:generators[0].radius: [0.5, 0.2]: expected [low, high] with low <= high"});
}

}  // namespace
}  // namespace quad::world
