// The live view's page: shows the frames the server announces, turns mouse and form input
// into control changes (src/view/controls.rs), asks for the final render.
// `window.iris` holds what the page last saw, for people debugging it and for the browser
// test (tests/view_browser.rs).
"use strict";

const TOKEN = new URLSearchParams(location.search).get("token") || "";
const withToken = (path) => path + (path.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(TOKEN);
const $ = (id) => document.getElementById(id);

window.iris = {
  framesShown: 0, frameId: null, generation: 0, pixelSum: null, plan: "", method: "",
  status: null, final: null, error: "", controls: null, connected: false,
};

// ---------------------------------------------------------------- server calls
async function post(path, body) {
  const r = await fetch(withToken(path), {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  const answer = await r.json().catch(() => ({ error: r.statusText }));
  if (!r.ok) throw new Error(answer.error || r.statusText);
  return answer;
}

function showError(message) {
  window.iris.error = message || "";
  $("error").textContent = message || "";
}

// Changes go out one at a time; while one is in flight the newest waiting one replaces
// the others (an orbit drag sends many).
let inFlight = false;
let waiting = null;
function change(delta) {
  waiting = Object.assign(waiting || {}, delta);
  if (!inFlight) flush();
}
async function flush() {
  if (!waiting) return;
  const body = waiting;
  waiting = null;
  inFlight = true;
  try {
    const answer = await post("/controls", body);
    window.iris.requested = answer.generation;
    showError("");
  } catch (e) {
    showError(e.message);
  } finally {
    inFlight = false;
    if (waiting) flush();
  }
}

// ---------------------------------------------------------------- camera
let camera = null; // {eye: [x,y,z], target: [x,y,z], fov}
let dragging = false;
const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const scale = (a, s) => a.map((v) => v * s);
const len = (a) => Math.hypot(a[0], a[1], a[2]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => scale(a, 1 / (len(a) || 1));

function orbit(dx, dy) {
  const off = sub(camera.eye, camera.target);
  const r = len(off);
  let az = Math.atan2(off[0], off[2]);
  let el = Math.asin(Math.max(-1, Math.min(1, off[1] / r)));
  az -= dx * 0.008;
  el = Math.max(-1.55, Math.min(1.55, el + dy * 0.008));
  const eye = [r * Math.cos(el) * Math.sin(az), r * Math.sin(el), r * Math.cos(el) * Math.cos(az)];
  camera = { ...camera, eye: add(camera.target, eye) };
  change({ camera });
}

function pan(dx, dy, height) {
  const forward = norm(sub(camera.target, camera.eye));
  const right = norm(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const dist = len(sub(camera.target, camera.eye));
  const perPixel = (2 * dist * Math.tan((camera.fov * Math.PI) / 360)) / height;
  const move = add(scale(right, -dx * perPixel), scale(up, dy * perPixel));
  camera = { ...camera, eye: add(camera.eye, move), target: add(camera.target, move) };
  change({ camera });
}

function zoom(steps) {
  const off = sub(camera.eye, camera.target);
  const k = Math.exp(steps * 0.0015);
  camera = { ...camera, eye: add(camera.target, scale(off, k)) };
  change({ camera });
}

function bindMouse() {
  const box = $("frame-box");
  let drag = null;
  box.addEventListener("contextmenu", (e) => e.preventDefault());
  box.addEventListener("mousedown", (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
    dragging = true;
    e.preventDefault();
  });
  window.addEventListener("mousemove", (e) => {
    if (!drag || !camera) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.pan) pan(dx, dy, box.clientHeight || 360);
    else orbit(dx, dy);
  });
  window.addEventListener("mouseup", () => { drag = null; dragging = false; });
  box.addEventListener("wheel", (e) => {
    if (!camera) return;
    e.preventDefault();
    zoom(e.deltaY);
  }, { passive: false });
}

// ---------------------------------------------------------------- controls
function fill(select, values) {
  for (const v of values) {
    const o = document.createElement("option");
    o.value = o.textContent = v;
    select.appendChild(o);
  }
}

function showControls(c) {
  window.iris.controls = c;
  // The page's own camera moves ahead of the server's echo while it drags.
  if (!(dragging || inFlight || waiting)) camera = c.camera;
  for (const key of ["stone", "metal", "studio", "env", "exposure", "method", "spectral"]) {
    const select = $(key);
    if (![...select.options].some((o) => o.value === c[key])) fill(select, [c[key]]);
    select.value = c[key];
  }
  $("turn").value = c.turn;
  $("turn-value").textContent = c.turn + "°";
}

function bindControls() {
  for (const select of document.querySelectorAll("[data-control]")) {
    select.addEventListener("change", () => change({ [select.id]: select.value }));
  }
  $("view").addEventListener("change", () => {
    if ($("view").value) change({ view: $("view").value });
    $("view").value = "";
  });
  $("turn").addEventListener("input", () => {
    $("turn-value").textContent = $("turn").value + "°";
    change({ turn: Number($("turn").value) });
  });
  $("final").addEventListener("submit", async (e) => {
    e.preventDefault();
    const body = {
      width: Number($("final-width").value), height: Number($("final-height").value),
      units: Number($("final-units").value),
    };
    $("render").disabled = true;
    $("state").textContent = "rendering the final image…";
    try {
      const answer = await post("/render", body);
      window.iris.final = answer;
      $("command").textContent = answer.command;
      $("final-link").href = withToken("/final/" + answer.id);
      $("final-output").textContent = answer.output;
      $("final-result").hidden = false;
      showError("");
    } catch (err) {
      showError(err.message);
    } finally {
      $("render").disabled = false;
    }
  });
}

// ---------------------------------------------------------------- frames and status
function showStatus(s) {
  window.iris.status = s;
  $("state").textContent = s.state + (s.error ? ": " + s.error : "");
  if (s.state === "error") showError(s.error);
  if (!s.plan) return;
  window.iris.method = s.method;
  const rows = s.plan.map((st) => `<tr class="${st.used ? "used" : ""}"><th>${st.name}</th><td></td></tr>`);
  const body = $("plan").tBodies[0];
  body.innerHTML = rows.join("");
  s.plan.forEach((st, i) => { body.rows[i].cells[0].textContent = st.name; body.rows[i].cells[1].textContent = st.reason; });
  window.iris.plan = s.plan.map((st) => `${st.name}: ${st.reason}`).join("\n");
  const notes = $("notes");
  notes.innerHTML = "";
  for (const n of s.notes || []) {
    const li = document.createElement("li");
    li.textContent = n;
    notes.appendChild(li);
  }
}

function pixelSum(img) {
  const c = document.createElement("canvas");
  c.width = img.naturalWidth;
  c.height = img.naturalHeight;
  const g = c.getContext("2d");
  g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let sum = 0;
  for (let i = 0; i < d.length; i += 4) sum += d[i] + 3 * d[i + 1] + 7 * d[i + 2];
  return sum;
}

function showFrame(f) {
  const img = $("frame");
  img.onload = () => {
    window.iris.framesShown += 1;
    window.iris.frameId = f.id;
    window.iris.generation = f.generation;
    window.iris.pixelSum = pixelSum(img);
    window.iris.units = f.units;
    window.iris.denoised = f.denoised;
  };
  img.src = withToken("/frame/" + f.id);
  $("units").textContent = `${f.units} ${window.iris.status?.unit === "passes" ? "passes" : "spp"}`;
  $("estimate").textContent = f.estimate == null ? "" : `error ≈ ${(100 * f.estimate).toFixed(1)} %`;
  $("overlay").textContent = f.denoised ? "denoised" : "";
}

function connect() {
  const events = new EventSource(withToken("/events"));
  events.addEventListener("open", () => { window.iris.connected = true; });
  events.addEventListener("state", (e) => {
    const s = JSON.parse(e.data);
    camera = s.controls.camera;
    showControls(s.controls);
    showStatus(s.status);
    $("scene").textContent = s.scene;
    if (s.frame != null) showFrame({ id: s.frame, generation: s.generation, units: 0 });
  });
  events.addEventListener("status", (e) => showStatus(JSON.parse(e.data)));
  events.addEventListener("frame", (e) => showFrame(JSON.parse(e.data)));
  events.addEventListener("controls", (e) => showControls(JSON.parse(e.data)));
  events.addEventListener("final", (e) => {
    const f = JSON.parse(e.data);
    if (f.state === "rendering") $("state").textContent = "rendering the final image…";
  });
  events.addEventListener("bye", () => {
    $("state").textContent = "the server stopped";
    events.close();
  });
}

async function start() {
  const choices = await (await fetch(withToken("/choices"))).json();
  for (const key of ["stone", "metal", "studio", "env", "view", "method", "spectral"]) fill($(key), choices[key]);
  $("turn").max = choices.turn_frames - 1;
  bindMouse();
  bindControls();
  connect();
}

start().catch((e) => showError("cannot start: " + e.message));
