// botsim live: the page. It draws a Nexys4-like board (our own drawing), the VGA monitor and
// the world, and speaks botsim's protocol (docs/LIVE.md) over one WebSocket to the server
// that serves it. Everything it shows comes from the server; what the user does becomes a
// command, and the server's next state shows its effect.
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const $ = (id) => document.getElementById(id);
const board = $("board");
let ws = null;
let state = null;           // the last state message
let world = null;           // {width, height, cells}
const path = [];            // the bot's samples: [x, y]
let pendingFrame = null;    // the frame message whose PNG comes next
let latched = new Set();    // buttons held down by shift-click
let mode = "board";         // "board" (botsim board --live) or "bot" (botsim run --live)
const mouseHeld = new Set(); // buttons held down by the mouse

function el(name, attrs, parent) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  (parent || board).appendChild(e);
  return e;
}

function send(msg) {
  if (ws && ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(msg));
}

// ---- The board drawing ----------------------------------------------------------------
const leds = [], knobs = [], digits = [], buttons = {};

// The board the design is made for (the server's hello says which: board.md's Nexys4, Nexys4
// DDR or Nexys3): its digits, LEDs and switches, and its buttons as [botsim's name, label],
// the reset first. Until the hello, a Nexys4.
const NEXYS4 = {
  name: "NEXYS4", digits: 8, leds: 16, switches: 16,
  buttons: [["btnCpuReset", "CPU RESET"], ["btnU", "BTNU"], ["btnL", "BTNL"], ["btnC", "BTNC"], ["btnR", "BTNR"], ["btnD", "BTND"]],
};
let face = NEXYS4;

function drawBoard(f) {
  face = f;
  board.replaceChildren();
  board.setAttribute("aria-label", "The " + f.name + " board");
  leds.length = knobs.length = digits.length = 0;
  for (const k of Object.keys(buttons)) delete buttons[k];
  const defs = el("defs");
  const glow = el("filter", { id: "glow", x: "-50%", y: "-50%", width: "200%", height: "200%" }, defs);
  el("feGaussianBlur", { stdDeviation: "2.2", result: "b" }, glow);
  const merge = el("feMerge", {}, glow);
  el("feMergeNode", { in: "b" }, merge);
  el("feMergeNode", { in: "SourceGraphic" }, merge);

  el("rect", { class: "pcb", x: 6, y: 6, width: 648, height: 428, rx: 14 });
  for (const [x, y] of [[24, 24], [636, 24], [24, 416], [636, 416]]) el("circle", { cx: x, cy: y, r: 7, fill: "#c9b98f" });
  const t = el("text", { class: "silk big", x: 40, y: 44 });
  t.textContent = f.name;
  const s = el("text", { class: "silk", x: 60 + 12 * f.name.length, y: 44 });
  s.textContent = "botsim live board";

  // The digits, the highest on the left, centred over x = 310.
  const box = f.digits * 48 + 20;
  el("rect", { x: 310 - box / 2, y: 66, width: box, height: 92, rx: 6, fill: "#0b0b0b" });
  for (let i = 0; i < f.digits; i++) digits[f.digits - 1 - i] = drawDigit(310 - box / 2 + 16 + i * 48, 78);

  // The buttons: a separate reset button (labelled CPU RESET), or the reset in the middle of
  // the cross (a Nexys3's BTNS), and the others around it.
  const cx = 560, cy = 218, d = 44;
  const at = { btnU: [cx, cy - d], btnL: [cx - d, cy], btnC: [cx, cy], btnR: [cx + d, cy], btnD: [cx, cy + d] };
  for (const [name, label] of f.buttons) {
    if (name === "btnCpuReset" && label === "CPU RESET") drawButton(name, 590, 62, label, true);
    else if (name === "btnCpuReset") drawButton(name, cx, cy, label, false);
    else drawButton(name, at[name][0], at[name][1], label);
  }

  // The LEDs over the switches, the highest on the left, centred over x = 310.
  for (let i = 0; i < Math.max(f.leds, f.switches); i++) {
    const x = 310 + ((Math.max(f.leds, f.switches) - 1) / 2 - i) * 36;
    if (i < f.leds) {
      leds[i] = el("rect", { class: "led", id: "ld" + i, x: x - 6, y: 318, width: 12, height: 8, rx: 2 });
      const l = el("text", { class: "silk", x: x, y: 312, "text-anchor": "middle" });
      l.textContent = "LD" + i;
    }
    if (i < f.switches) {
      el("rect", { class: "sw-slot", x: x - 7, y: 344, width: 14, height: 44, rx: 3 });
      const knob = el("rect", { class: "sw-knob", id: "sw" + i, x: x - 6, y: 368, width: 12, height: 18, rx: 2 });
      knob.addEventListener("click", () => toggleSwitch(i));
      knobs[i] = knob;
      const sl = el("text", { class: "silk", x: x, y: 404, "text-anchor": "middle" });
      sl.textContent = "SW" + i;
    }
  }
}

// One digit: segments a-g and the point, each an element whose class says if it is lit.
function drawDigit(x, y) {
  const w = 30, h = 64, t = 6;
  const H = (x0, y0) => `${x0 + t / 2},${y0} ${x0 + w - t / 2},${y0} ${x0 + w},${y0 + t / 2} ${x0 + w - t / 2},${y0 + t} ${x0 + t / 2},${y0 + t} ${x0},${y0 + t / 2}`;
  const V = (x0, y0) => `${x0 + t / 2},${y0} ${x0 + t},${y0 + t / 2} ${x0 + t},${y0 + h / 2 - t / 2} ${x0 + t / 2},${y0 + h / 2} ${x0},${y0 + h / 2 - t / 2} ${x0},${y0 + t / 2}`;
  const sk = `skewX(-6) translate(${x + 8},${y})`;
  const g = el("g", { transform: sk });
  const segs = [
    el("polygon", { class: "seg", points: H(0, 0) }, g),                 // a
    el("polygon", { class: "seg", points: V(w - t, 0) }, g),             // b
    el("polygon", { class: "seg", points: V(w - t, h / 2) }, g),         // c
    el("polygon", { class: "seg", points: H(0, h - t) }, g),             // d
    el("polygon", { class: "seg", points: V(0, h / 2) }, g),             // e
    el("polygon", { class: "seg", points: V(0, 0) }, g),                 // f
    el("polygon", { class: "seg", points: H(0, h / 2 - t / 2) }, g),     // g
  ];
  segs.push(el("circle", { class: "seg", cx: w + 5, cy: h - 3, r: 3.2 }, g)); // the point
  return segs;
}

function drawButton(name, x, y, label, reset) {
  const b = el("circle", { class: "btn" + (reset ? " reset" : ""), id: "btn-" + name, cx: x, cy: y, r: 15 });
  const l = el("text", { class: "silk", x: x, y: y + 29, "text-anchor": "middle" });
  l.textContent = label;
  b.addEventListener("mousedown", (e) => {
    e.preventDefault();
    if (e.shiftKey) {
      // Shift-click holds it down until the next click.
      if (latched.has(name)) { latched.delete(name); press(name, false); }
      else { latched.add(name); press(name, true); }
      return;
    }
    if (latched.has(name)) { latched.delete(name); press(name, false); return; }
    mouseHeld.add(name);
    press(name, true);
  });
  buttons[name] = b;
}

window.addEventListener("mouseup", () => {
  for (const name of mouseHeld) press(name, false);
  mouseHeld.clear();
});

function press(name, down) {
  if (!buttons[name]) return; // not on this board
  buttons[name].classList.toggle("down", down);
  send({ type: "button", name: name, down: down });
}

function toggleSwitch(i) {
  const on = state ? (state.switches >> i & 1) === 0 : true;
  send({ type: "switch", index: i, on: on });
}

// ---- The bot alone: its motors (MotCtl_in: bit 5 left on, 4 left forward, 1 right on,
// 0 right forward; botsim.md 3.1) ---------------------------------------------------------
const WHEEL = { l: { fwd: 0x30, rev: 0x20, off: 0x00, mask: 0xF0 }, r: { fwd: 0x03, rev: 0x02, off: 0x00, mask: 0x0F } };
function motors() { return state && state.motors != null ? state.motors : 0; }
function setMotors(v) { send({ type: "motors", value: v }); }
for (const b of document.querySelectorAll(".wheel button")) {
  b.addEventListener("click", () => {
    const w = WHEEL[b.dataset.wheel];
    setMotors((motors() & ~w.mask & 0xFF) | w[b.dataset.dir]);
  });
}
function wheelOf(v, w) {
  const on = (v >> (w === "l" ? 5 : 1)) & 1, fwd = (v >> (w === "l" ? 4 : 0)) & 1;
  return on ? (fwd ? "fwd" : "rev") : "off";
}
const keyDrive = { ArrowUp: 0x33, ArrowDown: 0x22, ArrowLeft: 0x23, ArrowRight: 0x32 };
let driveKey = null;

const keyButtons = { ArrowUp: "btnU", ArrowDown: "btnD", ArrowLeft: "btnL", ArrowRight: "btnR", Enter: "btnC", r: "btnCpuReset", R: "btnCpuReset" };
// A design with a keyboard: keys typed on the board (it has the focus) are its keyboard's
// (scan codes by the key's place, KeyboardEvent.code); the buttons are clicked.
let peripherals = {};
const keysDown = new Set();
function typing(e) { return peripherals.keyboard && document.activeElement === board; }
window.addEventListener("keydown", (e) => {
  if (e.target.tagName === "SELECT" || e.target.tagName === "INPUT") return;
  if (typing(e)) {
    e.preventDefault();
    if (!e.repeat && e.code && !keysDown.has(e.code)) {
      keysDown.add(e.code);
      send({ type: "key", code: e.code, down: true });
    }
    return;
  }
  if (mode === "bot") {
    if (e.key in keyDrive) {
      e.preventDefault();
      if (!e.repeat) { driveKey = e.key; setMotors(keyDrive[e.key]); }
    }
  } else {
    const b = keyButtons[e.key];
    if (b && !e.repeat) { e.preventDefault(); press(b, true); }
  }
  if (e.key === "p" || e.key === "P") toggleRun();
  if (e.key === "n" || e.key === "N") send({ type: "step" });
});
window.addEventListener("keyup", (e) => {
  if (keysDown.has(e.code)) {
    e.preventDefault();
    keysDown.delete(e.code);
    send({ type: "key", code: e.code, down: false });
    return;
  }
  if (e.target.tagName === "INPUT") return;
  if (mode === "bot") {
    if (e.key === driveKey) { e.preventDefault(); driveKey = null; setMotors(0); }
    return;
  }
  const b = keyButtons[e.key];
  if (b) { e.preventDefault(); press(b, false); }
});

// Keys held when the board loses the focus are released.
board.addEventListener("blur", () => {
  for (const code of keysDown) send({ type: "key", code: code, down: false });
  keysDown.clear();
});
board.addEventListener("mousedown", () => board.focus());

// ---- The console (USB-UART) -------------------------------------------------------------
$("console-form").addEventListener("submit", (e) => {
  e.preventDefault();
  const text = $("console-in").value + "\r";
  $("console-in").value = "";
  send({ type: "uart", text: text });
});
function consoleText(text, baud) {
  const out = $("console-out");
  // A terminal: CR LF and lone CR end a line.
  out.textContent += text.replace(/\r\n?/g, "\n");
  out.scrollTop = out.scrollHeight;
  if (baud) $("baud").textContent = "USB-UART, " + baud + " baud";
}

// ---- The tilt (the accelerometer): sliders, or drag on the pad (x right, y up; z from
// them, as gravity is 1 g) ------------------------------------------------------------------
const tilt = { x: 0, y: 0, z: 1 };
let tiltSent = 0, tiltTimer = null;
function sendTilt() {
  const now = performance.now();
  clearTimeout(tiltTimer);
  if (now - tiltSent < 50) { tiltTimer = setTimeout(sendTilt, 50); return; }
  tiltSent = now;
  send({ type: "tilt", x: tilt.x, y: tilt.y, z: tilt.z });
}
function showTilt() {
  for (const a of ["x", "y", "z"]) $("tilt-" + a).value = tilt[a];
  $("tilt-now").textContent = `x ${tilt.x.toFixed(2)} g, y ${tilt.y.toFixed(2)} g, z ${tilt.z.toFixed(2)} g`;
  const c = $("tilt-pad"), g = c.getContext("2d"), r = c.width / 2;
  g.clearRect(0, 0, c.width, c.height);
  g.strokeStyle = "#3a434e";
  g.beginPath(); g.arc(r, r, r - 2, 0, 2 * Math.PI); g.moveTo(r, 4); g.lineTo(r, c.height - 4); g.moveTo(4, r); g.lineTo(c.width - 4, r); g.stroke();
  g.fillStyle = "#4fb3ff";
  g.beginPath(); g.arc(r + tilt.x * (r - 10), r - tilt.y * (r - 10), 7, 0, 2 * Math.PI); g.fill();
}
for (const a of ["x", "y", "z"]) {
  $("tilt-" + a).addEventListener("input", (e) => { tilt[a] = Number(e.target.value); showTilt(); sendTilt(); });
}
$("tilt-flat").addEventListener("click", () => { Object.assign(tilt, { x: 0, y: 0, z: 1 }); showTilt(); sendTilt(); });
function padTilt(e) {
  const c = $("tilt-pad"), rect = c.getBoundingClientRect(), r = rect.width / 2;
  let x = (e.clientX - rect.left - r) / (r - 10), y = -(e.clientY - rect.top - r) / (r - 10);
  const len = Math.hypot(x, y);
  if (len > 1) { x /= len; y /= len; }
  tilt.x = Math.round(x * 100) / 100;
  tilt.y = Math.round(y * 100) / 100;
  tilt.z = Math.round(Math.sqrt(Math.max(0, 1 - tilt.x * tilt.x - tilt.y * tilt.y)) * 100) / 100;
  showTilt();
  sendTilt();
}
$("tilt-pad").addEventListener("pointerdown", (e) => { e.target.setPointerCapture(e.pointerId); padTilt(e); });
$("tilt-pad").addEventListener("pointermove", (e) => { if (e.buttons) padTilt(e); });

// ---- The sound: the board's ampPWM averaged into 48 kHz samples by the server, AC-coupled
// here (as the board's output is) and played through Web Audio ---------------------------
const sound = { ctx: null, on: false, next: 0, lastIn: null, lastOut: 0, samples: 0, peak: 0 };
window.botsimSound = sound; // what the page computed, for tests
$("mute").addEventListener("click", () => {
  sound.on = !sound.on;
  if (sound.on && !sound.ctx) sound.ctx = new AudioContext();
  if (sound.ctx) (sound.on ? sound.ctx.resume() : sound.ctx.suspend());
  $("mute").textContent = sound.on ? "Mute" : "Sound on";
  $("sound-now").textContent = sound.on ? "playing" : "muted";
});
function playSamples(rate, bytes) {
  const x = new Float32Array(bytes.length);
  for (let i = 0; i < bytes.length; i++) {
    const v = bytes[i] / 255;
    if (sound.lastIn === null) sound.lastIn = v;
    sound.lastOut = v - sound.lastIn + 0.9974 * sound.lastOut;
    sound.lastIn = v;
    x[i] = sound.lastOut;
    sound.peak = Math.max(sound.peak, Math.abs(x[i]));
  }
  sound.samples += x.length;
  if (!sound.on || !sound.ctx) return;
  const buf = sound.ctx.createBuffer(1, x.length, rate);
  buf.copyToChannel(x, 0);
  const src = sound.ctx.createBufferSource();
  src.buffer = buf;
  src.connect(sound.ctx.destination);
  const t = Math.max(sound.next, sound.ctx.currentTime + 0.05);
  src.start(t);
  sound.next = t + buf.duration;
}

// ---- Controls --------------------------------------------------------------------------
function toggleRun() { send({ type: state && state.running ? "pause" : "run" }); }
$("run").addEventListener("click", toggleRun);
$("step").addEventListener("click", () => send({ type: "step" }));
$("speed").addEventListener("change", (e) => {
  const v = e.target.value;
  send({ type: "speed", factor: v === "max" ? null : Number(v) });
});
$("save").addEventListener("click", () => send({ type: "save" }));
$("stop").addEventListener("click", () => send({ type: "stop" }));

// ---- What the server says --------------------------------------------------------------
// The speed the run has (set by --speed, or by any page), unless this page's list is open.
function showSpeed(factor) {
  const sel = $("speed");
  if (document.activeElement === sel) return;
  const v = factor === null || factor === undefined ? "max" : String(factor);
  if (![...sel.options].some((o) => o.value === v)) {
    const o = document.createElement("option");
    o.value = v;
    o.textContent = v + " x";
    sel.add(o, sel.options[sel.options.length - 1]);
  }
  sel.value = v;
}

function showState(s) {
  state = s;
  leds.forEach((led, i) => led.classList.toggle("on", (s.leds >> i & 1) === 1));
  knobs.forEach((knob, i) => knob.setAttribute("transform", (s.switches >> i & 1) ? "translate(0,-22)" : ""));
  for (let d = 0; d < digits.length; d++) {
    const lit = s.digits[d];
    digits[d].forEach((seg, k) => seg.classList.toggle("on", (lit >> k & 1) === 1));
  }
  for (const [name, b] of Object.entries(buttons)) {
    if (!mouseHeld.has(name) && !latched.has(name)) b.classList.toggle("down", s.buttons.includes(name));
  }
  $("time").textContent = (s.time_ps / 1e12).toFixed(3) + " s";
  $("rate").textContent = s.running ? s.rate.toFixed(2) + " x real time" : "paused";
  $("behind").textContent = s.behind || "";
  $("behind").hidden = !s.behind;
  $("samples").textContent = world || mode === "bot" ? s.samples + " samples" : "";
  $("run").textContent = s.running ? "Pause" : "Run";
  if (s.motors != null) {
    $("motctl-now").textContent = "MotCtl " + hex(s.motors);
    for (const w of ["l", "r"]) {
      const on = wheelOf(s.motors, w);
      for (const d of ["fwd", "off", "rev"]) $(w + "m-" + d).classList.toggle("on", d === on);
    }
  }
  showSpeed(s.speed);
  $("fps").textContent = s.frame_rate > 0 ? s.frame_rate.toFixed(1) + " frames/s" : "";
  const b = s.bot;
  if (b) {
    $("r-x").textContent = b.x;
    $("r-y").textContent = b.y;
    $("r-heading").textContent = b.heading;
    $("r-movement").textContent = b.movement;
    $("r-sensors").textContent = b.sensors.toString(2).padStart(8, "0");
    $("r-info").textContent = hex(b.info);
    $("r-motctl").textContent = hex(b.motctl);
    $("r-lmdist").textContent = b.lmdist;
    $("r-rmdist").textContent = b.rmdist;
  }
  // Where the other bots are, in their colours, under the world.
  const legend = $("others");
  legend.textContent = "";
  (s.others || []).forEach((o, i) => {
    const e = document.createElement("span");
    e.className = "other-bot";
    e.style.color = OTHER_COLOURS[i % OTHER_COLOURS.length];
    e.textContent = " \u25B6 " + o.path + (o.bot ? " (" + o.bot.x + ", " + o.bot.y + ") " + o.bot.heading : ": no sample yet");
    legend.appendChild(e);
  });
  drawWorld();
}

function hex(v) { return v.toString(16).toUpperCase().padStart(2, "0"); }

const CELL = ["#f4f1ea", "#111111", "#b3412e", "#9aa3ad"]; // floor, line, obstruction, reserved
const HEADING = { N: -90, NE: -45, E: 0, SE: 45, S: 90, SW: 135, W: 180, NW: -135 };
let worldImage = null;

function drawWorld() {
  const c = $("world");
  const g = c.getContext("2d");
  if (!world) return;
  const k = c.width / world.width;
  if (!worldImage) {
    worldImage = document.createElement("canvas");
    worldImage.width = c.width;
    worldImage.height = c.height;
    const w = worldImage.getContext("2d");
    for (let y = 0; y < world.height; y++) {
      for (let x = 0; x < world.width; x++) {
        w.fillStyle = CELL[Number(world.cells[y * world.width + x])];
        w.fillRect(x * k, y * k, k, k);
      }
    }
  }
  g.drawImage(worldImage, 0, 0);
  if (path.length > 1) {
    g.strokeStyle = "rgba(47, 128, 237, 0.85)";
    g.lineWidth = 2;
    g.beginPath();
    path.forEach(([x, y], i) => (i ? g.lineTo : g.moveTo).call(g, (x + 0.5) * k, (y + 0.5) * k));
    g.stroke();
  }
  const b = state && state.bot;
  if (b) drawBot(g, k, b, "#2f80ed", 1);
  // The design's other bots (a game's monster), each in its own colour, smaller and over the
  // first: bots on one cell stay visible.
  const others = (state && state.others) || [];
  others.forEach((o, i) => o.bot && drawBot(g, k, o.bot, OTHER_COLOURS[i % OTHER_COLOURS.length], 0.6));
}

// The other bots' colours (the second, third and fourth bot: botsim's pictures' too).
const OTHER_COLOURS = ["#00c8c8", "#e6c800", "#dc2828"];

// A bot as an arrow on its cell, pointing where it heads (`size` 1: the first bot's).
function drawBot(g, k, b, colour, size) {
  g.save();
  g.translate((b.x + 0.5) * k, (b.y + 0.5) * k);
  g.rotate(((HEADING[b.heading] || 0) * Math.PI) / 180);
  g.scale(size, size);
  g.fillStyle = colour;
  g.strokeStyle = "#fff";
  g.lineWidth = 1.5;
  g.beginPath();
  g.moveTo(9, 0);
  g.lineTo(-7, -7);
  g.lineTo(-4, 0);
  g.lineTo(-7, 7);
  g.closePath();
  g.fill();
  g.stroke();
  g.restore();
}

function showError(text) {
  const e = $("error");
  e.textContent = text;
  e.hidden = false;
  clearTimeout(showError.t);
  showError.t = setTimeout(() => (e.hidden = true), 4000);
}

function download(name, text) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type: "text/plain" }));
  a.download = name;
  a.click();
  URL.revokeObjectURL(a.href);
}

function onMessage(ev) {
  if (typeof ev.data !== "string") {
    // The PNG of the frame message before it.
    if (!pendingFrame) return;
    const img = $("vga");
    const old = img.src;
    img.src = URL.createObjectURL(new Blob([ev.data], { type: "image/png" }));
    img.dataset.sample = pendingFrame.sample;
    img.dataset.sampleFrom = pendingFrame.sample_from;
    img.dataset.timePs = pendingFrame.time_ps;
    if (old) URL.revokeObjectURL(old);
    $("novga").hidden = true;
    pendingFrame = null;
    return;
  }
  const m = JSON.parse(ev.data);
  if (m.gpio) return; // ViDBo's shape, for ViDBo front ends
  switch (m.type) {
    case "hello":
      if (m.board) drawBoard(m.board);
      world = m.world;
      worldImage = null;
      path.length = 0;
      $("design").textContent = m.design ? m.design.top + " — " + m.design.sources : "";
      mode = m.mode || "board";
      document.body.classList.toggle("bot", mode === "bot");
      $("board").style.display = mode === "bot" ? "none" : "";
      $("board-hint").hidden = mode === "bot";
      $("drive").hidden = mode !== "bot";
      $("monitor").hidden = mode === "bot";
      if (m.vga === false) $("novga").textContent = "this design has no VGA pins";
      // A design with no VGA and no bot: nothing on the right but its peripherals' panels.
      if (m.vga === false && !m.world && mode === "board") $("monitor").hidden = true;
      // A board without a bot (a final project): no world, no registers; Step runs 50 ms.
      const alone = mode === "board" && !m.world;
      $("worldbox").hidden = alone;
      $("regs").hidden = alone;
      if (alone) $("step").title = "Run 50 ms of board time (and draw the frame after it), then pause (N)";
      // The peripherals the design's pins reach.
      peripherals = m.peripherals || {};
      $("kbd").hidden = !peripherals.keyboard;
      $("uart").hidden = !peripherals.uart;
      $("tilt").hidden = !peripherals.accelerometer;
      $("sound").hidden = !peripherals.audio;
      $("devices").hidden = !(peripherals.keyboard || peripherals.uart || peripherals.accelerometer || peripherals.audio);
      if (peripherals.keyboard) {
        $("board-hint").textContent = "Click the board and type: keys go to the design's keyboard. Buttons are pressed while the mouse is down (shift-click holds one down).";
      }
      if (m.tilt) [tilt.x, tilt.y, tilt.z] = m.tilt;
      showTilt();
      if (mode === "bot") {
        $("save").textContent = "Save motors";
        $("save").title = "Download the motors so far as a --motors script";
      }
      if (m.driver) {
        $("driver-note").textContent = m.driver + " drives the bot.";
        $("driver-note").hidden = false;
        for (const b of document.querySelectorAll(".wheel button")) b.disabled = true;
      }
      break;
    case "state": showState(m); break;
    case "log":
      for (const e of m.entries) {
        if (e.kind === "sample") path.push([e.x, e.y]);
        else if (e.kind === "uart") consoleText(e.text, e.baud);
        else if (e.kind === "audio") playSamples(e.rate, e.samples);
      }
      drawWorld();
      break;
    case "frame": pendingFrame = m; break;
    case "stimulus": download("live-stimulus.txt", m.text); break;
    case "motors": download("live-motors.txt", m.text); break;
    case "error": showError(m.message); break;
    case "closed":
      $("status").textContent = "the run ended";
      $("status").classList.add("offline");
      break;
  }
}

function connect() {
  ws = new WebSocket(`ws://${location.host}/ws`);
  ws.binaryType = "arraybuffer";
  ws.onopen = () => {
    $("status").textContent = "live";
    $("status").classList.remove("offline");
  };
  ws.onclose = () => {
    if ($("status").textContent !== "the run ended") {
      $("status").textContent = "disconnected";
      $("status").classList.add("offline");
    }
  };
  ws.onmessage = onMessage;
}

drawBoard(NEXYS4);
connect();
