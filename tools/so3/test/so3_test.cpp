// SPDX-License-Identifier: BSD-3-Clause
// quad so3 on the guide's worked examples, and its refusals.
#include "quad/so3/so3.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace quad::so3 {
namespace {

std::vector<std::string> words(const std::string& text)
{
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) {
    out.push_back(w);
  }
  return out;
}

std::string convert(const std::string& args, So3Options options = {})
{
  std::ostringstream out;
  so3Convert(words(args), options, out);
  return out.str();
}

std::string distance(const std::string& args)
{
  std::ostringstream out;
  so3Distance(words(args), {}, out);
  return out.str();
}

std::string refusal(const std::function<void()>& f)
{
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "accepted";
}

bool has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

TEST(So3Command, GuideEquation3IsAQuarterTurnAboutZ)
{
  const std::string out = convert("--matrix 0 -1 0 1 0 0 0 0 1");
  EXPECT_TRUE(has(out, "axis-angle: axis (0, 0, 1), angle 1.570796327 rad (90 deg)")) << out;
  EXPECT_TRUE(has(out, "quaternion (w, x, y, z): (0.7071067812, 0, 0, 0.7071067812)")) << out;
}

TEST(So3Command, GuideDistanceExampleIsSixtyDegreesInRhoAndOneTwentyApart)
{
  const std::string out = distance("--matrix 1 0 0 0 0 -1 0 1 0 --matrix 0 1 0 -1 0 0 0 0 1");
  EXPECT_TRUE(has(out, "rotation angle between them (geodesic): 2.094395102 rad (120 deg)")) << out;
  EXPECT_TRUE(has(out, "rho_s(h1, h2)   (eq. 5):  1.047197551 rad (60 deg)")) << out;
  EXPECT_TRUE(has(out, "rho_s(h1, -h2)  (eq. 5):  2.094395102 rad (120 deg)")) << out;
  EXPECT_TRUE(has(out, "rho(h1, h2)     (eq. 6):  1.047197551 rad (60 deg)")) << out;
  EXPECT_TRUE(has(out, "Frobenius in R9 (eq. 16): 2.449489743")) << out;
}

TEST(So3Command, GuideTable2QuaternionsAreTheirRotations)
{
  EXPECT_TRUE(has(convert("--quat 0 0 0 1"), "axis (0, 0, 1), angle 3.141592654 rad (180 deg)"));
  const std::string quarter = convert("--quat 1 1 0 0");
  EXPECT_TRUE(has(quarter, "note: normalized from norm 1.414213562")) << quarter;
  EXPECT_TRUE(has(quarter, "axis (1, 0, 0), angle 1.570796327 rad (90 deg)")) << quarter;
  EXPECT_TRUE(has(quarter, "  [0, 0, -1]\n  [0, 1, 0]")) << quarter;
}

TEST(So3Command, EveryInputFormGivesTheSameRotation)
{
  const std::string expected = convert("--matrix 0 -1 0 1 0 0 0 0 1");
  EXPECT_EQ(convert("--quat 0.7071067811865476 0 0 0.7071067811865476"), expected);
  EXPECT_EQ(convert("--axis-angle 0 0 1 1.5707963267948966"), expected);
  EXPECT_EQ(convert("--ypr 90 0 0", {.degrees = true}), expected);
}

TEST(So3Command, GimbalLockIsSaid)
{
  EXPECT_TRUE(has(convert("--ypr 0.3 1.5707963267948966 0.1"), "gimbal lock"));
}

TEST(So3Command, BadInputIsRefusedNamingTheOptionAndValue)
{
  EXPECT_EQ(refusal([] { convert("--matrix 1 0 0 0 1 0 0 0"); }),
            "--matrix: expected 9 numbers, got 8");
  EXPECT_EQ(refusal([] { convert("--quat 1 x 0 0"); }), "--quat: 'x' is not a finite number");
  EXPECT_EQ(refusal([] { convert("--quat 1 nan 0 0"); }), "--quat: 'nan' is not a finite number");
  EXPECT_TRUE(has(refusal([] { convert("--matrix 1 0 0 0 1 0 0 0 -1"); }),
                  "--matrix: not a rotation: max |AᵀA − I| = 0, det A = -1"));
  EXPECT_EQ(refusal([] { convert("--quat 0 0 0 0"); }), "--quat: the zero quaternion is no rotation");
  EXPECT_EQ(refusal([] { convert(""); }), "convert takes one rotation, got 0");
  EXPECT_EQ(refusal([] { distance("--ypr 1 2 3"); }), "distance takes two rotations, got 1");
  EXPECT_TRUE(has(refusal([] { convert("--euler 1 2 3"); }), "unexpected '--euler'"));
  std::ostringstream out;
  EXPECT_EQ(refusal([&] { so3Sample(3, 1, "euler", {}, out); }),
            "--as: 'euler': expected quat, matrix, axis-angle or ypr");
}

TEST(So3Command, SamplesAreReproducibleUnitQuaternions)
{
  std::ostringstream a;
  std::ostringstream b;
  so3Sample(5, 1, "quat", {}, a);
  so3Sample(5, 1, "quat", {}, b);
  EXPECT_EQ(a.str(), b.str());
  std::istringstream in(a.str());
  for (int i = 0; i < 5; ++i) {
    double w, x, y, z;
    in >> w >> x >> y >> z;
    EXPECT_NEAR(w * w + x * x + y * y + z * z, 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace quad::so3
