// SPDX-License-Identifier: BSD-3-Clause
// A minimal stand-in controller for plant tests: answers every vehicle state with rotor
// commands stamped with that state's time, holding an altitude with a PD law on collective
// thrust. Its output depends on the state it answers, so a run is reproducible only if the
// plant's lockstep pairs each command with the right state.
//   altitude_controller HOVER_RAD_PER_S TARGET_Z_M
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"

int main(int argc, char** argv)
{
  if (argc != 3) {
    std::cerr << "usage: altitude_controller HOVER_RAD_PER_S TARGET_Z_M\n";
    return 2;
  }
  const double hover = std::atof(argv[1]);
  const double target = std::atof(argv[2]);
  quad::dds::Participant participant(quad::dds::optionsFromEnvironment("altitude_controller"));
  quad::dds::Waker waker;
  quad::dds::Subscriber<quad::msg::VehicleState> state(participant, quad::dds::topics::kSimState, &waker);
  quad::dds::Publisher<quad::msg::ActuatorCommand> actuators(participant, quad::dds::topics::kActuators);
  std::cout << "ready" << std::endl;
  while (true) {
    waker.waitUntil(quad::common::steadyTimeNs() + 100'000'000);
    for (const auto& s : state.takeAll()) {
      const double error = target - s.p_W().z();
      const double thrust_ratio = std::clamp(1.0 + 0.4 * error - 0.6 * s.v_W().z(), 0.5, 1.6);
      const double w = hover * std::sqrt(thrust_ratio);
      quad::msg::ActuatorCommand cmd;
      cmd.header().stamp_ns(s.header().stamp_ns());
      cmd.rotor_speed({w, w, w, w});
      cmd.armed(true);
      actuators.write(cmd);
    }
  }
}
