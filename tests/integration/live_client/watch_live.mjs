// Watches a mechsim live server with the Foxglove WebSocket protocol's own client
// (@foxglove/ws-protocol) and decodes every message twice: with Foxglove's OMG IDL
// deserializer (@foxglove/omgidl-serialization, from the advertised schema) and with the
// browser page's decoder (tools/live/page/live.js). Test helper, not shipped.
//   node watch_live.mjs URL PAGE_JS OUT_JSON [SECONDS]
// Reads until the server closes (or SECONDS pass), then writes {serverInfo, channels,
// messages: [{topic, timestamp_ns, foxglove: {...}, page: {...}}]} with the headers and
// numeric fields of each message.
import wsProtocol from "@foxglove/ws-protocol";
import omgidlParser from "@foxglove/omgidl-parser";
import omgidlSerialization from "@foxglove/omgidl-serialization";
import WebSocket from "ws";
import { createRequire } from "module";
import { writeFileSync } from "fs";

// CommonJS packages: their default export holds the names.
const { FoxgloveClient } = wsProtocol;
const { parseIDL } = omgidlParser;
const { MessageReader } = omgidlSerialization;

const [url, pageJs, out, seconds] = process.argv.slice(2);
const page = createRequire(import.meta.url)(pageJs);
const result = { serverInfo: null, channels: [], messages: [], errors: [] };
const byChannel = new Map();
const bySubscription = new Map();

// The header and scalar fields of a decoded struct, flat ("header.t", "angle", ...).
function flat(value, prefix = "", into = {}) {
  for (const [k, v] of Object.entries(value)) {
    if (typeof v === "bigint") into[prefix + k] = Number(v);
    else if (typeof v === "number" || typeof v === "boolean" || typeof v === "string") into[prefix + k] = v;
    else if (ArrayBuffer.isView(v) || Array.isArray(v)) Array.from(v).forEach((e, i) => (into[`${prefix}${k}[${i}]`] = typeof e === "bigint" ? Number(e) : e));
    else if (v && typeof v === "object") flat(v, prefix + k + ".", into);
  }
  return into;
}

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("serverInfo", (info) => (result.serverInfo = info));
client.on("advertise", (channels) => {
  for (const c of channels) {
    result.channels.push(c);
    try {
      const reader = new MessageReader(c.schemaName, parseIDL(c.schema));
      const decode = page.channelDecoder(c);
      byChannel.set(c.id, { c, reader, decode });
      bySubscription.set(client.subscribe(c.id), c.id);
    } catch (e) {
      result.errors.push(`${c.topic}: ${e}`);
    }
  }
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const ch = byChannel.get(bySubscription.get(subscriptionId));
  if (!ch) return;
  try {
    result.messages.push({ topic: ch.c.topic, timestamp_ns: Number(timestamp), foxglove: flat(ch.reader.readMessage(data)),
                           page: ch.decode(new Uint8Array(data.buffer, data.byteOffset, data.byteLength)) });
  } catch (e) {
    result.errors.push(`${ch.c.topic}: ${e}`);
  }
});
const finish = () => {
  writeFileSync(out, JSON.stringify(result));
  process.exit(0);
};
client.on("close", finish);
client.on("error", (e) => result.errors.push(String(e && e.message ? e.message : e)));
if (seconds) setTimeout(finish, Number(seconds) * 1000);
