// SPDX-License-Identifier: BSD-3-Clause
#include "quad/security/documents.hpp"

#include <ctime>

#include <fmt/format.h>

#include "quad/common/xml_text.hpp"

namespace quad::security {

namespace {

constexpr const char* kDomains = "<domains><id_range><min>0</min><max>232</max></id_range></domains>";

std::string isoTime(Clock::time_point t)
{
  const std::time_t seconds = Clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

std::string topicList(const char* element, const std::vector<std::string>& topics)
{
  if (topics.empty()) {
    return "";
  }
  std::string out = fmt::format("        <{}>\n          <topics>\n", element);
  for (const auto& t : topics) {
    out += fmt::format("            <topic>{}</topic>\n", common::xmlEscaped(t));
  }
  // Any partition: a fleet's vehicles publish in partitions of their own, the plant and the
  // tools in the default one and "*" (dds::vehiclePartitions); the topics are what is granted.
  return out + fmt::format("          </topics>\n          <partitions>\n            <partition>*</partition>\n"
                           "          </partitions>\n        </{}>\n",
                           element);
}

}  // namespace

std::string governanceXml()
{
  return fmt::format(R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- quad: who may join a domain and how its traffic is protected. Signed by the permissions CA. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      {}
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
)",
                     kDomains);
}

std::string permissionsXml(const Grant& grant)
{
  return fmt::format(R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- quad: what the identity "{0}" may do; the rest is denied. Signed by the permissions CA. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="{0}">
      <subject_name>{1}</subject_name>
      <validity>
        <not_before>{2}</not_before>
        <not_after>{3}</not_after>
      </validity>
      <allow_rule>
        {4}
{5}{6}      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
)",
                     common::xmlEscaped(grant.identity), common::xmlEscaped(grant.subject), isoTime(grant.not_before),
                     isoTime(grant.not_after), kDomains, topicList("publish", grant.publish),
                     topicList("subscribe", grant.subscribe));
}

}  // namespace quad::security
