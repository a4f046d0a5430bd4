// Reads an MCAP file with the third-party @mcap/core readers and prints what they saw as
// JSON: header, schemas, channels, statistics, message counts and bytes per topic, and
// whether the file was complete. mechsim's tests use it to check that its recordings are
// readable by MCAP tooling nobody here wrote.
//
//   node read_mcap.mjs FILE
//
// Two passes: McapIndexedReader (footer -> summary -> chunk indexes; fails on a truncated
// file) and McapStreamReader (every record from the start, CRCs validated; on a truncated
// file it reads what is complete and reports done() = false).
import { open, readFile } from "node:fs/promises";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";

const path = process.argv[2];
if (!path) {
  console.error("usage: node read_mcap.mjs FILE");
  process.exit(2);
}

const decompressHandlers = await loadDecompressHandlers();

function countMessage(counts, bytes, topic, message) {
  counts[topic] = (counts[topic] ?? 0) + 1;
  bytes[topic] = (bytes[topic] ?? 0) + message.data.byteLength;
}

function describeChannel(channel) {
  return {
    id: channel.id,
    schema_id: channel.schemaId,
    topic: channel.topic,
    message_encoding: channel.messageEncoding,
    metadata: Object.fromEntries(channel.metadata),
  };
}

function describeSchema(schema) {
  return {
    id: schema.id,
    name: schema.name,
    encoding: schema.encoding,
    data: new TextDecoder().decode(schema.data),
  };
}

async function readIndexed() {
  const handle = await open(path, "r");
  try {
    const readable = {
      size: async () => BigInt((await handle.stat()).size),
      read: async (offset, size) => {
        const buffer = new Uint8Array(Number(size));
        const { bytesRead } = await handle.read(buffer, 0, buffer.length, Number(offset));
        if (bytesRead !== buffer.length) throw new Error(`short read at ${offset}`);
        return buffer;
      },
    };
    const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
    const counts = {};
    const bytes = {};
    let previousLogTime = -1n;
    let inOrder = true;
    for await (const message of reader.readMessages({ validateCrcs: true })) {
      countMessage(counts, bytes, reader.channelsById.get(message.channelId).topic, message);
      if (message.logTime < previousLogTime) inOrder = false;
      previousLogTime = message.logTime;
    }
    const stats = reader.statistics;
    return {
      ok: true,
      header: { profile: reader.header.profile, library: reader.header.library },
      schemas: [...reader.schemasById.values()].map(describeSchema),
      channels: [...reader.channelsById.values()].map(describeChannel),
      statistics: stats && {
        message_count: Number(stats.messageCount),
        schema_count: stats.schemaCount,
        channel_count: stats.channelCount,
        chunk_count: stats.chunkCount,
        message_start_time: stats.messageStartTime.toString(),
        message_end_time: stats.messageEndTime.toString(),
        channel_message_counts: Object.fromEntries(
          [...stats.channelMessageCounts].map(([id, n]) => [id, Number(n)]),
        ),
      },
      chunk_indexes: reader.chunkIndexes.length,
      message_counts: counts,
      message_bytes: bytes,
      log_time_ordered: inOrder,
    };
  } catch (error) {
    return { ok: false, error: String(error?.message ?? error) };
  } finally {
    await handle.close();
  }
}

async function readStream() {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  const channels = new Map();
  const schemas = new Map();
  const counts = {};
  const bytes = {};
  const recordCounts = {};
  let error = null;
  reader.append(await readFile(path));
  try {
    for (let record; (record = reader.nextRecord()); ) {
      recordCounts[record.type] = (recordCounts[record.type] ?? 0) + 1;
      if (record.type === "Schema") schemas.set(record.id, record);
      else if (record.type === "Channel") channels.set(record.id, record);
      else if (record.type === "Message")
        countMessage(counts, bytes, channels.get(record.channelId)?.topic ?? `#${record.channelId}`, record);
    }
  } catch (e) {
    error = String(e?.message ?? e);
  }
  return {
    done: reader.done(),
    bytes_remaining: reader.bytesRemaining(),
    error,
    record_counts: recordCounts,
    schemas: [...schemas.values()].map(describeSchema),
    channels: [...channels.values()].map(describeChannel),
    message_counts: counts,
    message_bytes: bytes,
  };
}

const indexed = await readIndexed();
const stream = await readStream();
const complete = indexed.ok && stream.done && stream.error === null;
console.log(JSON.stringify({ file: path, complete, indexed, stream }, null, 2));
