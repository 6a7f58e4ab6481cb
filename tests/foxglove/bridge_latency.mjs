// SPDX-License-Identifier: BSD-3-Clause
// The WebSocket end of quad bridge's benchmark (tools/bridge/bench/bridge_bench.sh): a
// Foxglove client subscribed to quad/sim/state through the bridge; for each message, its
// receive time minus the publish time in its Header. Prints
// "count N median_us M p99_us P max_us X" after SECONDS.
//   node bridge_latency.mjs URL SECONDS
import wsProtocol from "@foxglove/ws-protocol";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const [url, seconds] = process.argv.slice(2);
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
const nowNs = () => BigInt(Math.round((performance.timeOrigin + performance.now()) * 1e6));
const latencyUs = [];
let reader;
let subscription;
client.on("error", (e) => {
  process.stderr.write(`bridge_latency: ${e.message ?? e}\n`);
  process.exit(1);
});
client.on("advertise", (channels) => {
  const c = channels.find((ch) => ch.topic === "quad/sim/state");
  reader = new MessageReader(c.schemaName, parseIDL(c.schema));
  subscription = client.subscribe(c.id);
});
client.on("message", ({ subscriptionId, data }) => {
  if (subscriptionId !== subscription) {
    return;
  }
  const received = nowNs();
  const m = reader.readMessage(data);
  latencyUs.push(Number(received - BigInt(m.header.publish_ns)) / 1000);
});
setTimeout(() => {
  latencyUs.sort((a, b) => a - b);
  const at = (q) => latencyUs[Math.floor(q * (latencyUs.length - 1))];
  process.stdout.write(latencyUs.length === 0 ? "count 0\n"
    : `count ${latencyUs.length} median_us ${at(0.5).toFixed(1)} p99_us ${at(0.99).toFixed(1)} max_us ${latencyUs.at(-1).toFixed(1)}\n`);
  process.exit(latencyUs.length === 0 ? 1 : 0);
}, Number(seconds) * 1000);
