// SPDX-License-Identifier: BSD-3-Clause
// Reads a quad recording with the MCAP reader and OMG IDL decoder Foxglove uses, decodes
// every message, and compares the samples of one topic with what `quad topic echo --json`
// printed for the same samples (matched by Header.seq).
//   node check.mjs FILE.mcap ECHO.jsonl TOPIC
import { readFileSync } from "node:fs";
import { McapStreamReader } from "@mcap/core";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import { decompress } from "fzstd";

const [file, echoFile, topic] = process.argv.slice(2);
const fail = (why) => {
  console.error(`check: ${why}`);
  process.exit(1);
};

// Echoed samples by seq. 64-bit integers are quoted first: JSON numbers lose them.
const echoed = new Map();
for (const line of readFileSync(echoFile, "utf8").split("\n")) {
  if (!line.startsWith("{")) continue;
  const sample = JSON.parse(line.replace(/([:\[,])(-?\d{16,})(?=[,\]}])/g, '$1"$2"'));
  echoed.set(String(sample.header.seq), sample);
}

const reader = new McapStreamReader({
  decompressHandlers: { zstd: (buffer, size) => decompress(buffer, new Uint8Array(Number(size))) },
});
reader.append(readFileSync(file));
const schemas = new Map();
const channels = new Map();
const decoders = new Map();
const enumValues = new Map(); // enumerator name -> value, from every schema
let decoded = 0;
let compared = 0;

function same(a, e, path) {
  if (e === null && typeof a === "number" && Number.isNaN(a)) return;
  if (typeof a === "bigint") {
    if (String(a) !== String(e)) fail(`${path}: decoded ${a}, echoed ${e}`);
  } else if (typeof a === "number" && typeof e === "string") {
    if (enumValues.get(e) !== a) fail(`${path}: decoded ${a}, echoed ${e}`);
  } else if (typeof a === "number") {
    if (Math.abs(a - Number(e)) > 1e-12 * Math.max(1, Math.abs(a))) fail(`${path}: decoded ${a}, echoed ${e}`);
  } else if (Array.isArray(a) || ArrayBuffer.isView(a)) {
    if (a.length !== e.length) fail(`${path}: ${a.length} elements decoded, ${e.length} echoed`);
    for (let i = 0; i < a.length; i++) same(a[i], e[i], `${path}[${i}]`);
  } else if (typeof a === "object") {
    for (const k of Object.keys(e)) {
      if (!(k in a)) fail(`${path}.${k}: echoed, not decoded`);
      same(a[k], e[k], `${path}.${k}`);
    }
  } else if (a !== e) {
    fail(`${path}: decoded ${a}, echoed ${e}`);
  }
}

for (let record; (record = reader.nextRecord()); ) {
  if (record.type === "Schema") {
    if (record.encoding !== "omgidl") fail(`schema ${record.name}: encoding ${record.encoding}`);
    schemas.set(record.id, record);
  } else if (record.type === "Channel") {
    if (record.messageEncoding !== "cdr") fail(`channel ${record.topic}: encoding ${record.messageEncoding}`);
    channels.set(record.id, record);
  } else if (record.type === "Message") {
    const channel = channels.get(record.channelId);
    if (!decoders.has(channel.schemaId)) {
      const schema = schemas.get(channel.schemaId);
      const definitions = parseIDL(new TextDecoder().decode(schema.data));
      for (const d of definitions) {
        for (const member of d.definitions) {
          if (member.isConstant) enumValues.set(member.name, member.value);
        }
      }
      decoders.set(channel.schemaId, new MessageReader(schema.name, definitions));
    }
    const message = decoders.get(channel.schemaId).readMessage(record.data);
    decoded++;
    if (channel.topic === topic && echoed.has(String(message.header.seq))) {
      same(message, echoed.get(String(message.header.seq)), topic);
      compared++;
    }
  }
}
if (!reader.done()) fail("the reader did not reach the end of the file");
if (compared === 0) fail(`no ${topic} sample of the recording was echoed`);
console.log(`check: decoded ${decoded} messages on ${channels.size} channels; ${compared} ${topic} samples equal to the echo`);
