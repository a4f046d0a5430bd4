// The live page's client (docs/live.md): the Foxglove WebSocket protocol
// (foxglove.websocket.v1) from the browser, a decoder of the CDR of mechsim's structs read
// from the advertised OMG IDL schemas, and uPlot charts of the chosen fields. The decoder
// part runs under Node as well (module.exports at the end), for the tests.
"use strict";

// --- OMG IDL (the subset mechsim's idl/ uses) --------------------------------------------
// Structs of an IDL text by short name: [{name, type, seq}], type a primitive, "string" or
// another struct's name; seq true for sequence<T, N>.
function parseIdl(text) {
  const clean = text.replace(/\/\*[\s\S]*?\*\//g, "").replace(/\/\/.*$/gm, "").replace(/^\s*#.*$/gm, "");
  const structs = {};
  const re = /struct\s+(\w+)\s*\{([^}]*)\}/g;
  let m;
  while ((m = re.exec(clean))) {
    const members = [];
    for (let decl of m[2].split(";")) {
      decl = decl.replace(/@\w+(\([^)]*\))?/g, "").trim().replace(/\s+/g, " ");
      if (!decl) continue;
      let seq = false;
      const s = decl.match(/^sequence\s*<\s*([\w ]+?)\s*(,\s*\d+\s*)?>\s*(\w+)$/);
      let type, name;
      if (s) { seq = true; type = s[1]; name = s[3]; }
      else {
        const parts = decl.split(" ");
        name = parts.pop();
        type = parts.join(" ").replace(/<\s*\d+\s*>/, "");
      }
      members.push({ name, type: type.replace(/^.*::/, ""), seq });
    }
    structs[m[1]] = members;
  }
  return structs;
}

// --- CDR (plain XCDR1 / XCDR2, either byte order) -----------------------------------------
const SIZES = { "double": 8, "float": 4, "boolean": 1, "octet": 1, "char": 1, "short": 2, "unsigned short": 2,
                "long": 4, "unsigned long": 4, "long long": 8, "unsigned long long": 8 };

class CdrReader {
  constructor(buffer) {
    this.dv = new DataView(buffer.buffer || buffer, buffer.byteOffset || 0, buffer.byteLength);
    const rep = this.dv.getUint16(0, false);
    this.le = (rep & 1) === 1;
    this.maxAlign = rep >= 6 ? 4 : 8;  // XCDR2 aligns 8-byte members to 4
    this.off = 4;
  }
  align(n) {
    const a = Math.min(n, this.maxAlign), rel = this.off - 4;
    this.off += (a - (rel % a)) % a;
  }
  prim(type) {
    const n = SIZES[type];
    if (!n) throw new Error("unknown IDL type " + type);
    this.align(n);
    const dv = this.dv, o = this.off, le = this.le;
    this.off += n;
    switch (type) {
      case "double": return dv.getFloat64(o, le);
      case "float": return dv.getFloat32(o, le);
      case "boolean": case "octet": case "char": return dv.getUint8(o);
      case "short": return dv.getInt16(o, le);
      case "unsigned short": return dv.getUint16(o, le);
      case "long": return dv.getInt32(o, le);
      case "unsigned long": return dv.getUint32(o, le);
      case "long long": return Number(dv.getBigInt64(o, le));
      case "unsigned long long": return Number(dv.getBigUint64(o, le));
    }
  }
  string() {
    const n = this.prim("unsigned long");
    const bytes = new Uint8Array(this.dv.buffer, this.dv.byteOffset + this.off, Math.max(0, n - 1));
    this.off += n;
    return new TextDecoder().decode(bytes);
  }
}

// Decodes `bytes` as struct `name` of `structs` into a flat object: "header.t": 0.5, ...
// (sequence elements as "reals[0]", ...).
function decodeCdr(bytes, structs, name) {
  const r = new CdrReader(bytes);
  const out = {};
  const walk = (members, prefix) => {
    for (const m of members) {
      const key = prefix + m.name;
      const read = () => (m.type === "string" ? r.string() : structs[m.type] ? walk(structs[m.type], key + ".") : r.prim(m.type));
      if (m.seq) {
        const n = r.prim("unsigned long");
        for (let i = 0; i < n; ++i) {
          const v = read();
          if (v !== undefined) out[key + "[" + i + "]"] = v;
        }
      } else {
        const v = read();
        if (v !== undefined) out[key] = v;
      }
    }
  };
  walk(structs[name], "");
  return out;
}

// An FMU participant's channel: "y:f64,impacts:i32,faulted:boolean" (mechsim.fields) names
// the elements of its reals, integers and booleans.
function fmuNames(fieldsText) {
  const names = {};
  const count = { f64: 0, i32: 0, boolean: 0 };
  const seq = { f64: "reals", i32: "integers", boolean: "booleans" };
  for (const item of (fieldsText || "").split(",").filter(Boolean)) {
    const [name, kind] = item.split(":");
    if (seq[kind] === undefined) continue;
    names[seq[kind] + "[" + count[kind]++ + "]"] = name;
  }
  return names;
}

// One advertised channel, ready to decode: decode(bytes) -> {field: number|string}.
function channelDecoder(channel) {
  const structs = parseIdl(channel.schema);
  const short = channel.schemaName.replace(/^.*::/, "");
  if (!structs[short]) throw new Error("no struct " + short + " in the schema of " + channel.topic);
  const rename = fmuNames(channel["mechsim.fields"]);
  return (bytes) => {
    const flat = decodeCdr(bytes, structs, short);
    const named = {};
    for (const [k, v] of Object.entries(flat)) named[rename[k] || k] = v;
    return named;
  };
}

if (typeof module !== "undefined") module.exports = { parseIdl, decodeCdr, channelDecoder, fmuNames };

// --- The page ------------------------------------------------------------------------------
if (typeof window !== "undefined") {
  const WINDOW_S = 10, MAX_POINTS = 4000;
  const channels = new Map();  // id -> {info, decode, subscription, fields: Map(name -> checkbox), plot, data}
  const bySubscription = new Map();
  let nextSubscription = 1;
  const ws = new WebSocket("ws://" + location.host + "/", ["foxglove.websocket.v1"]);
  ws.binaryType = "arraybuffer";
  const $ = (id) => document.getElementById(id);
  $("window").textContent = WINDOW_S;
  window.mechsimLive = { channels, received: 0 };  // for a test to look at

  ws.onopen = () => ($("state").textContent = "connected");
  ws.onclose = () => ($("state").textContent = "disconnected (the run ended or the server stopped)");
  ws.onmessage = (ev) => {
    if (typeof ev.data === "string") return onJson(JSON.parse(ev.data));
    const dv = new DataView(ev.data);
    if (dv.getUint8(0) !== 1) return;
    const ch = bySubscription.get(dv.getUint32(1, true));
    if (!ch) return;
    const t_ns = Number(dv.getBigUint64(5, true));
    window.mechsimLive.received++;
    let values;
    try { values = ch.decode(new Uint8Array(ev.data, 13)); } catch (e) { ch.summaryEl.title = String(e); return; }
    ch.latest = values;
    for (const [name, el] of ch.valueEls) el.textContent = format(values[name]);
    if (ch.plotted.length) {
      ch.data[0].push(t_ns / 1e9);
      ch.plotted.forEach((name, i) => ch.data[i + 1].push(values[name]));
      const t0 = t_ns / 1e9 - WINDOW_S;
      while (ch.data[0].length > MAX_POINTS || (ch.data[0].length && ch.data[0][0] < t0)) ch.data.forEach((a) => a.shift());
      ch.dirty = true;
    }
  };

  function format(v) {
    return typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toPrecision(6)) : v === undefined ? "" : String(v);
  }

  function onJson(msg) {
    if (msg.op === "serverInfo") {
      $("server").textContent = msg.name;
      $("state").textContent = Object.entries(msg.metadata || {}).map(([k, v]) => k + ": " + v).join(", ");
    } else if (msg.op === "advertise") {
      for (const c of msg.channels) addChannel(c);
    }
  }

  function addChannel(info) {
    let decode;
    try { decode = channelDecoder(info); } catch (e) { return; }
    const ch = { info, decode, subscription: 0, valueEls: new Map(), plotted: [], data: [[]], plot: null, dirty: false };
    channels.set(info.id, ch);
    const details = document.createElement("details");
    const summary = document.createElement("summary");
    summary.innerHTML = "";
    summary.append(info.topic + " ");
    const type = document.createElement("span");
    type.className = "type";
    type.textContent = info.schemaName.replace(/^.*::/, "");
    summary.append(type);
    ch.summaryEl = summary;
    details.append(summary);
    details.addEventListener("toggle", () => {
      if (details.open) subscribe(ch);
    });
    ch.details = details;
    $("channels").append(details);
  }

  function subscribe(ch) {
    if (ch.subscription) return;
    ch.subscription = nextSubscription++;
    bySubscription.set(ch.subscription, ch);
    ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: ch.subscription, channelId: ch.info.id }] }));
    // The field list comes with the first sample (an FMU's sequences have its length).
    const wait = setInterval(() => {
      if (!ch.latest) return;
      clearInterval(wait);
      for (const name of Object.keys(ch.latest)) {
        const label = document.createElement("label");
        const box = document.createElement("input");
        box.type = "checkbox";
        box.dataset.topic = ch.info.topic;
        box.dataset.field = name;
        box.disabled = typeof ch.latest[name] !== "number";
        box.addEventListener("change", () => choose(ch, name, box.checked));
        const value = document.createElement("span");
        value.className = "value";
        ch.valueEls.set(name, value);
        label.append(box, " " + name, value);
        ch.details.append(label);
      }
    }, 50);
  }

  function choose(ch, name, on) {
    ch.plotted = on ? [...ch.plotted, name] : ch.plotted.filter((n) => n !== name);
    if (ch.plot) { ch.plot.destroy(); ch.plotDiv.remove(); ch.plot = null; }
    ch.data = [[], ...ch.plotted.map(() => [])];
    if (!ch.plotted.length) return;
    const div = document.createElement("div");
    div.className = "plot";
    div.dataset.topic = ch.info.topic;
    const title = document.createElement("h3");
    title.textContent = ch.info.topic;
    div.append(title);
    $("plots").append(div);
    ch.plotDiv = div;
    const colors = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"];
    ch.plot = new uPlot({
      width: Math.max(400, $("main").clientWidth - 30), height: 260,
      scales: { x: { time: false } },
      axes: [{ label: "t [s] (simulation)" }, {}],
      series: [{ label: "t" }, ...ch.plotted.map((n, i) => ({ label: n, stroke: colors[i % colors.length], width: 1.5 }))],
    }, ch.data, div);
  }

  // Redraws at the browser's frame rate, only the plots that received samples.
  (function frame() {
    for (const ch of channels.values())
      if (ch.plot && ch.dirty) { ch.plot.setData(ch.data); ch.dirty = false; }
    requestAnimationFrame(frame);
  })();
}
