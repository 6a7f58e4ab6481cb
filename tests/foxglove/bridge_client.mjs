// SPDX-License-Identifier: BSD-3-Clause
// A Foxglove WebSocket client (@foxglove/ws-protocol's FoxgloveClient over the ws package)
// against quad bridge: it connects, lists the channels, subscribes to the state, the map and
// the goal answers, decodes what arrives with each channel's schema
// (@foxglove/omgidl-serialization), publishes a goal (clientPublish), tries a topic the
// stack does not take from outside, and waits for the planner's answer to its goal. Prints
// a JSON summary; exits 0 once the goal was answered, 1 on an error or after TIMEOUT s.
//   node bridge_client.mjs URL GOAL_ID X Y Z [TIMEOUT]
import wsProtocol from "@foxglove/ws-protocol";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader, MessageWriter } from "@foxglove/omgidl-serialization";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;

const [url, goalIdText, x, y, z, timeoutText] = process.argv.slice(2);
const goalId = Number(goalIdText);
const summary = {
  capabilities: [],
  channels: 0,
  topics: [],
  decoded: {},
  errors: [],
  statuses: [],
  goal_sent: false,
  goal_answer: null,
};
const finish = (code) => {
  process.stdout.write(JSON.stringify(summary, null, 1) + "\n");
  process.exit(code);
};
setTimeout(() => {
  summary.errors.push("timed out");
  finish(1);
}, Number(timeoutText ?? 60) * 1000);

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
const byTopic = new Map();
const readers = new Map();  // subscription id -> { topic, reader }

client.on("error", (e) => summary.errors.push(`socket: ${e.message ?? e}`));
client.on("serverInfo", (info) => {
  summary.capabilities = info.capabilities;
});
client.on("status", (s) => summary.statuses.push({ level: s.level, message: s.message }));
client.on("advertise", (channels) => {
  for (const c of channels) {
    byTopic.set(c.topic, c);
  }
  summary.channels = byTopic.size;
  summary.topics = [...byTopic.keys()].sort();
  for (const topic of ["quad/sim/state", "quad/display/map", "quad/planning/goal_ack"]) {
    const c = byTopic.get(topic);
    if (!c) {
      summary.errors.push(`${topic} was not advertised`);
      continue;
    }
    if (c.encoding !== "cdr" || c.schemaEncoding !== "omgidl") {
      summary.errors.push(`${topic}: encoding ${c.encoding}, schema encoding ${c.schemaEncoding}`);
    }
    const reader = new MessageReader(c.schemaName, parseIDL(c.schema));
    readers.set(client.subscribe(c.id), { topic, reader });
  }
});
client.on("message", ({ subscriptionId, data }) => {
  const r = readers.get(subscriptionId);
  if (!r) {
    summary.errors.push(`a message for subscription ${subscriptionId}, never asked`);
    return;
  }
  let m;
  try {
    m = r.reader.readMessage(data);
  } catch (e) {
    summary.errors.push(`${r.topic}: ${e.message}`);
    return;
  }
  summary.decoded[r.topic] = (summary.decoded[r.topic] ?? 0) + 1;
  if (r.topic === "quad/planning/goal_ack" && m.goal_id === goalId) {
    summary.goal_answer = { accepted: m.accepted, reason: m.reason };
    finish(0);
  }
  // Once the state and the map flow, publish the goal (and try a topic that is not the operator's).
  if (!summary.goal_sent && (summary.decoded["quad/sim/state"] ?? 0) >= 20 && summary.decoded["quad/display/map"]) {
    summary.goal_sent = true;
    // The refused topic first: its status is queued before anything the goal brings back.
    client.advertise({ topic: "quad/control/actuators", encoding: "cdr", schemaName: "quad::msg::ActuatorCommand" });
    const goalChannel = byTopic.get("quad/planning/goal");
    const writer = new MessageWriter(goalChannel.schemaName, parseIDL(goalChannel.schema));
    const channel = client.advertise({ topic: "quad/planning/goal", encoding: "cdr", schemaName: goalChannel.schemaName });
    const now = BigInt(Date.now()) * 1000000n;
    client.sendMessage(channel, writer.writeMessage({
      header: { vehicle_id: 0, stamp_ns: 0n, publish_ns: now, seq: 1n },
      goal_id: goalId,
      p_W: { x: Number(x), y: Number(y), z: Number(z) },
      yaw: 0,
      tolerance: 0.4,
    }));
  }
});
