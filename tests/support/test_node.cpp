// SPDX-License-Identifier: BSD-3-Clause
// A minimal node on the shared skeleton: counts the vehicle commands it receives. Tests use it
// to check the skeleton (heartbeats, wake-ups, clean shutdown on SIGINT/SIGTERM) and the tools.
#include <memory>

#include <spdlog/spdlog.h>

#include "quad/common/params.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"

namespace {

class TestNode : public quad::runtime::Node {
public:
  explicit TestNode(const quad::common::Params& params)
      : Node("test_node", quad::dds::optionsFromEnvironment("test_node")),
        commands_(participant(), quad::dds::topics::kVehicleCommand, waker())
  {
    spdlog::info("greeting: {}", params.getString("greeting"));
  }

protected:
  void onWake() override
  {
    while (auto command = commands_.take()) {
      ++received_;
      counters().samples_in++;
      spdlog::info("command {} received ({} so far)", static_cast<int>(command->kind()), received_);
    }
  }
  void onStop() override { spdlog::info("stopped cleanly; received {}", received_); }

private:
  quad::dds::Subscriber<quad::msg::VehicleCommand> commands_;
  int received_ = 0;
};

}  // namespace

int main(int argc, char** argv)
{
  quad::common::ParamSchema schema;
  schema.addString("greeting", "hello", {}, "logged at start")
      .addDouble("command_timeout", 1.0, 0.01, 60.0, "s", "unused; gives the tests a number");
  return quad::runtime::runNodeMain(argc, argv, "test_node", std::move(schema),
                                [](const quad::common::Params& params) {
                                  return std::make_unique<TestNode>(params);
                                });
}
