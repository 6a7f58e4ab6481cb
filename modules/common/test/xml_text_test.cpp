// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/xml_text.hpp"

#include <gtest/gtest.h>

namespace quad::common {
namespace {

TEST(XmlEscaped, TheMarkupCharactersBecomeEntitiesAndTheRestStays)
{
  EXPECT_EQ(xmlEscaped("a <b> & \"c\" 'd' µT"), "a &lt;b&gt; &amp; &quot;c&quot; 'd' µT");
  EXPECT_EQ(xmlEscaped(""), "");
}

}  // namespace
}  // namespace quad::common
