// SPDX-License-Identifier: BSD-3-Clause
// Reads a quad recording as Foxglove and Lichtblick do: the MCAP through @mcap/core, each
// display topic's schema through
// @foxglove/omgidl-parser and its messages through @foxglove/omgidl-serialization. Prints a
// JSON summary of what a viewer would draw; exits 1 when a message does not decode.
//   node display_topics.mjs RECORDING.mcap
import { readFileSync } from "node:fs";
import { McapStreamReader } from "@mcap/core";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import { decompress } from "fzstd";

const FLOAT32 = 7;

function cloudPoints(cloud) {
  const field = (name) => cloud.fields.find((f) => f.name === name);
  const [x, y, z] = ["x", "y", "z"].map(field);
  if (!x || !y || !z || [x, y, z].some((f) => f.type !== FLOAT32)) {
    throw new Error(`point cloud without float32 x, y, z fields: ${JSON.stringify(cloud.fields)}`);
  }
  const view = new DataView(cloud.data.buffer, cloud.data.byteOffset, cloud.data.byteLength);
  const points = [];
  for (let at = 0; at + cloud.point_stride <= cloud.data.byteLength; at += cloud.point_stride) {
    points.push([x, y, z].map((f) => view.getFloat32(at + f.offset, true)));
  }
  return points;
}

const quatNormError = (q) => Math.abs(Math.hypot(q.x, q.y, q.z, q.w) - 1);
const dist = (a, b) => Math.hypot(a.x - b.x, a.y - b.y, a.z - b.z);

async function main() {
  const file = process.argv[2];
  const reader = new McapStreamReader({
    decompressHandlers: { zstd: (buffer, size) => decompress(buffer, new Uint8Array(Number(size))) },
    validateCrcs: true,
  });
  reader.append(readFileSync(file));

  const schemas = new Map();
  const channels = new Map();
  const summary = { channels: {}, errors: [] };
  const last = {};
  const frames = new Set();
  let quatError = 0;
  let bodyGap = 0;
  let depthRange = 0;
  const depthFrames = new Set();
  const levels = {};
  const names = new Set();
  const lines = [];
  for (let record; (record = reader.nextRecord()); ) {
    if (record.type === "Schema") {
      schemas.set(record.id, record);
    } else if (record.type === "Channel") {
      if (!record.topic.startsWith("quad/display/")) {
        continue;
      }
      if (channels.has(record.id)) {
        continue;  // a channel is written again in the summary section
      }
      const schema = schemas.get(record.schemaId);
      const entry = { schema: schema.name, schema_encoding: schema.encoding, message_encoding: record.messageEncoding,
                      messages: 0, decoded: 0 };
      summary.channels[record.topic] = entry;
      try {
        const text = new TextDecoder().decode(schema.data);
        channels.set(record.id, { topic: record.topic, entry, reader: new MessageReader(schema.name, parseIDL(text)) });
      } catch (e) {
        summary.errors.push(`${record.topic}: schema ${schema.name} does not parse: ${e.message}`);
      }
    } else if (record.type === "Message") {
      const ch = channels.get(record.channelId);
      if (!ch) {
        continue;
      }
      ch.entry.messages++;
      let m;
      try {
        m = ch.reader.readMessage(record.data);
      } catch (e) {
        summary.errors.push(`${ch.topic}: message ${ch.entry.messages} does not decode: ${e.message}`);
        continue;
      }
      ch.entry.decoded++;
      last[ch.topic] = m;
      if (ch.topic === "quad/display/transforms") {
        const byChild = {};
        for (const t of m.transforms) {
          frames.add(`${t.parent_frame_id}>${t.child_frame_id}`);
          quatError = Math.max(quatError, quatNormError(t.rotation));
          byChild[t.child_frame_id] = t.translation;
        }
        if (byChild.body && byChild.body_true) {
          bodyGap = Math.max(bodyGap, dist(byChild.body, byChild.body_true));
        }
      } else if (ch.topic === "quad/display/depth") {
        depthFrames.add(m.frame_id);
        for (const p of cloudPoints(m)) {
          depthRange = Math.max(depthRange, Math.hypot(...p));
        }
      } else if (ch.topic === "quad/display/log") {
        levels[m.level] = (levels[m.level] ?? 0) + 1;
        names.add(m.name);
        lines.push(m.message);
      }
    }
  }
  const poses = (topic) => last[topic]?.poses.length ?? 0;
  summary.transforms = { frames: [...frames].sort(), max_quaternion_norm_error: quatError, max_body_truth_gap_m: bodyGap };
  summary.trajectory = { frame: last["quad/display/trajectory"]?.frame_id ?? "", poses: poses("quad/display/trajectory") };
  summary.true_trajectory = { poses: poses("quad/display/true_trajectory") };
  summary.path = { poses: poses("quad/display/path") };
  const map = last["quad/display/map"];
  if (map) {
    const points = cloudPoints(map);
    const lo = [0, 1, 2].map((i) => Math.min(...points.map((p) => p[i])));
    const hi = [0, 1, 2].map((i) => Math.max(...points.map((p) => p[i])));
    summary.map = { frame: map.frame_id, stride: map.point_stride, fields: map.fields.map((f) => f.name), points: points.length, min: lo, max: hi };
  }
  summary.depth = { frames: [...depthFrames], max_range_m: depthRange };
  const scene = last["quad/display/scene"];
  if (scene) {
    const count = (kind) => scene.entities.reduce((n, e) => n + e[kind].length, 0);
    const goal = scene.entities.find((e) => e.id === "goal");
    summary.scene = { entities: scene.entities.map((e) => e.id), cubes: count("cubes"), cylinders: count("cylinders"),
                      spheres: count("spheres"), goal: goal ? goal.spheres[0].pose.position : null };
  }
  summary.log = { lines: lines.length, levels, names: [...names].sort(), first: lines.slice(0, 5) };
  process.stdout.write(JSON.stringify(summary, null, 1) + "\n");
  process.exit(summary.errors.length === 0 ? 0 : 1);
}

main().catch((e) => {
  process.stderr.write(`display_topics: ${e.stack}\n`);
  process.exit(1);
});
