// SPDX-License-Identifier: BSD-3-Clause
#include "quad/introspection/idl.hpp"

#include <gtest/gtest.h>

namespace quad::introspection {
namespace {

TEST(Idl, EveryQuadMessageParsesAndLinks)
{
  const Schema& schema = quadSchema();
  const StructDef* state = schema.findStruct("quad::msg::VehicleState");
  ASSERT_NE(state, nullptr);
  ASSERT_GE(state->members.size(), 2U);
  EXPECT_EQ(state->members[0].name, "header");
  EXPECT_EQ(state->members[0].type.name, "quad::msg::Header");
  EXPECT_EQ(state->members[0].annotations, std::vector<std::string>{"key"});
  const EnumDef* mode = schema.findEnum("quad::msg::ControlMode");
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(mode->enumerators.front(), "CONTROL_DISARMED");
}

TEST(Idl, EnumeratorsAreNamedByValueAndUnknownValuesSaySo)
{
  const Schema& schema = quadSchema();
  EXPECT_EQ(schema.enumeratorName("quad::msg::FailsafeReason", 0), "FAILSAFE_NONE");
  EXPECT_EQ(schema.enumeratorName("foxglove::LogLevel", 4), "ERROR");
  EXPECT_EQ(schema.enumeratorName("quad::msg::FailsafeReason", 999), "quad::msg::FailsafeReason 999");
  EXPECT_EQ(schema.enumeratorName("quad::msg::Nope", 1), "quad::msg::Nope 1");
}

TEST(Idl, FoxglovesDisplaySchemasParseWithEveryPrimitive)
{
  const Schema& schema = quadSchema();
  const StructDef* entity = schema.findStruct("foxglove::SceneEntity");
  ASSERT_NE(entity, nullptr);
  EXPECT_EQ(entity->members.size(), 14U);  // Foxglove's members, none left out
  const std::string flat = schema.flattenedIdl("foxglove::SceneUpdate");
  for (const char* part : {"struct CubePrimitive", "struct ModelPrimitive", "enum LineType", "struct Time"}) {
    EXPECT_NE(flat.find(part), std::string::npos) << part;
  }
  EXPECT_EQ(flat.find("quad"), std::string::npos) << "a display schema stands alone";
}

TEST(Idl, EveryMessageStartsWithTheKeyedHeader)
{
  // The convention every tool relies on (loss audits, the vehicle key): Header first.
  // Foxglove's display schemas (foxglove::*) keep Foxglove's own layout.
  for (const auto& [name, def] : quadSchema().structs()) {
    if (name.starts_with("foxglove::")) {
      continue;
    }
    const bool is_part = name == "quad::msg::Header" || name == "quad::msg::Vector3" ||
                         name == "quad::msg::Quaternion" || name == "quad::msg::Point3f" ||
                         name == "quad::msg::VoxelChange" || name == "quad::msg::TrajectoryPiece";
    if (is_part) {
      continue;
    }
    ASSERT_FALSE(def.members.empty()) << name;
    EXPECT_EQ(def.members[0].type.name, "quad::msg::Header") << name;
    EXPECT_EQ(def.members[0].annotations, std::vector<std::string>{"key"}) << name;
  }
}

TEST(Idl, EverySequenceAndStringIsBounded)
{
  for (const auto& [name, def] : quadSchema().structs()) {
    for (const auto& m : def.members) {
      if (m.type.kind == TypeRef::Kind::kString || m.type.kind == TypeRef::Kind::kSequence) {
        EXPECT_GT(m.type.bound, 0U) << name << "." << m.name;
      }
    }
  }
}

TEST(Idl, FlattenedIdlIsSelfContainedAndReparsesToTheSameType)
{
  const std::string flat = quadSchema().flattenedIdl("quad::msg::VehicleState");
  EXPECT_EQ(flat.find("#include"), std::string::npos) << flat;
  // Dependencies come before their users.
  EXPECT_LT(flat.find("struct Header"), flat.find("struct VehicleState")) << flat;
  EXPECT_LT(flat.find("struct Quaternion"), flat.find("struct VehicleState")) << flat;

  Schema alone;
  alone.addFile("flat.idl", flat);
  alone.link();
  const StructDef* a = alone.findStruct("quad::msg::VehicleState");
  const StructDef* b = quadSchema().findStruct("quad::msg::VehicleState");
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->members.size(), b->members.size());
  for (std::size_t i = 0; i < a->members.size(); ++i) {
    EXPECT_EQ(a->members[i].name, b->members[i].name);
    EXPECT_EQ(a->members[i].type.name, b->members[i].type.name);
  }
}

TEST(Idl, UnknownTypeNamesFileStructAndMember)
{
  Schema s;
  s.addFile("bad.idl", "module m { struct S { Missing x; }; };");
  try {
    s.link();
    FAIL();
  } catch (const IdlError& e) {
    EXPECT_STREQ(e.what(), "bad.idl: m::S.x: unknown type 'Missing'");
  }
}

TEST(Idl, SyntaxErrorNamesFileLineAndToken)
{
  Schema s;
  try {
    s.addFile("bad.idl", "module m {\n struct S {\n long x\n };\n};");
    FAIL();
  } catch (const IdlError& e) {
    EXPECT_STREQ(e.what(), "bad.idl:4: expected ';' (at '}')");
  }
}

TEST(Idl, NamesResolveFromTheInnermostScope)
{
  Schema s;
  s.addFile("a.idl", "module a { struct T { long v; }; module b { struct T { short w; };"
                     " struct U { T t; ::a::T outer; }; }; };");
  s.link();
  const StructDef* u = s.findStruct("a::b::U");
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(u->members[0].type.name, "a::b::T");
  EXPECT_EQ(u->members[1].type.name, "a::T");
}

}  // namespace
}  // namespace quad::introspection
