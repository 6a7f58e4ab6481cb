// SPDX-License-Identifier: BSD-3-Clause
// A client of quad bridge that subscribes to every channel and then stops reading its socket:
// the slowest client there is. It prints "stalled" once it stopped reading and stays
// connected until it is killed.
//   node slow_client.mjs URL
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const socket = new WebSocket(process.argv[2], [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws: socket });
client.on("error", (e) => {
  process.stderr.write(`slow_client: ${e.message ?? e}\n`);
  process.exit(1);
});
client.on("advertise", (channels) => {
  for (const c of channels) {
    client.subscribe(c.id);
  }
  // The subscriptions are out; from now on nothing is read.
  setTimeout(() => {
    socket._socket.pause();
    process.stdout.write("stalled\n");
  }, 200);
});
setInterval(() => {}, 1000);
