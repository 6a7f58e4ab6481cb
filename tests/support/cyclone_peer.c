// SPDX-License-Identifier: BSD-3-Clause
// A participant of another DDS implementation (Eclipse Cyclone DDS), built from quad's own IDL
// with Cyclone's idlc, at Cyclone's default QoS except where docs/dds.md says a foreign
// participant must follow quad's contract. It joins a quad domain, prints every vehicle state
// it decodes as one JSON line, publishes a goal, and ends when the vehicle is within the
// goal's tolerance (exit 0) or after its timeout (exit 1).
//   quad_cyclone_peer DOMAIN X Y Z TIMEOUT_S
#include <dds/dds.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "Goal.h"
#include "VehicleState.h"

static int64_t wallNs(void)
{
  struct timespec t;
  clock_gettime(CLOCK_REALTIME, &t);
  return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

static void printState(const quad_msg_VehicleState* s)
{
  printf("{\"header\":{\"vehicle_id\":%u,\"stamp_ns\":%lld,\"seq\":%llu},"
         "\"p_W\":{\"x\":%.17g,\"y\":%.17g,\"z\":%.17g},\"v_W\":{\"x\":%.17g,\"y\":%.17g,\"z\":%.17g},"
         "\"q_WB\":{\"w\":%.17g,\"x\":%.17g,\"y\":%.17g,\"z\":%.17g},\"landed\":%s}\n",
         s->header.vehicle_id, (long long)s->header.stamp_ns, (unsigned long long)s->header.seq, s->p_W.x, s->p_W.y,
         s->p_W.z, s->v_W.x, s->v_W.y, s->v_W.z, s->q_WB.w, s->q_WB.x, s->q_WB.y, s->q_WB.z,
         s->landed ? "true" : "false");
}

int main(int argc, char** argv)
{
  if (argc != 6) {
    fprintf(stderr, "usage: quad_cyclone_peer DOMAIN X Y Z TIMEOUT_S\n");
    return 2;
  }
  const dds_domainid_t domain = (dds_domainid_t)atoi(argv[1]);
  const double goal[3] = {atof(argv[2]), atof(argv[3]), atof(argv[4])};
  const double timeout_s = atof(argv[5]);
  const double tolerance = 0.4;

  const dds_entity_t participant = dds_create_participant(domain, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "cyclone peer: participant: %s\n", dds_strretcode(-participant));
    return 1;
  }
  const dds_entity_t state_topic = dds_create_topic(participant, &quad_msg_VehicleState_desc, "quad/sim/state", NULL, NULL);
  const dds_entity_t goal_topic = dds_create_topic(participant, &quad_msg_Goal_desc, "quad/planning/goal", NULL, NULL);
  // The state reader at Cyclone's defaults but for a deeper history: states come at 250 Hz of
  // sim time, several per take.
  dds_qos_t* rqos = dds_create_qos();
  dds_qset_history(rqos, DDS_HISTORY_KEEP_LAST, 256);
  const dds_entity_t reader = dds_create_reader(participant, state_topic, rqos, NULL);
  dds_delete_qos(rqos);
  // The goal writer at Cyclone's defaults but for durability: the goal is latched
  // (TRANSIENT_LOCAL), so that a planner that starts later still gets it.
  dds_qos_t* qos = dds_create_qos();
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  const dds_entity_t writer = dds_create_writer(participant, goal_topic, qos, NULL);
  dds_delete_qos(qos);
  if (state_topic < 0 || goal_topic < 0 || reader < 0 || writer < 0) {
    fprintf(stderr, "cyclone peer: cannot create the topics, reader or writer\n");
    dds_delete(participant);
    return 1;
  }

  quad_msg_Goal g;
  g.header.vehicle_id = 0;
  g.header.stamp_ns = wallNs();
  g.header.publish_ns = g.header.stamp_ns;
  g.header.seq = 1;
  g.goal_id = 1;
  g.p_W.x = goal[0];
  g.p_W.y = goal[1];
  g.p_W.z = goal[2];
  g.yaw = NAN;
  g.tolerance = tolerance;
  if (dds_write(writer, &g) < 0) {
    fprintf(stderr, "cyclone peer: cannot write the goal\n");
    dds_delete(participant);
    return 1;
  }
  fflush(stdout);

  enum { kBatch = 32 };
  quad_msg_VehicleState states[kBatch];
  void* samples[kBatch];
  dds_sample_info_t infos[kBatch];
  for (int i = 0; i < kBatch; ++i) {
    samples[i] = &states[i];
  }
  const int64_t end = wallNs() + (int64_t)(timeout_s * 1e9);
  int reached = 0;
  unsigned long long received = 0;
  while (!reached && wallNs() < end) {
    const int n = dds_take(reader, samples, infos, kBatch, kBatch);
    for (int i = 0; i < n; ++i) {
      if (!infos[i].valid_data) {
        continue;
      }
      ++received;
      printState(&states[i]);
      const double dx = states[i].p_W.x - goal[0], dy = states[i].p_W.y - goal[1], dz = states[i].p_W.z - goal[2];
      reached = reached || sqrt(dx * dx + dy * dy + dz * dz) <= tolerance;
    }
    fflush(stdout);
    if (n <= 0) {
      dds_sleepfor(DDS_MSECS(5));
    }
  }
  fprintf(stderr, "cyclone peer: %llu states, goal (%g, %g, %g) %s\n", received, goal[0], goal[1], goal[2],
          reached ? "reached" : "not reached before the timeout");
  dds_delete(participant);
  return reached ? 0 : 1;
}
