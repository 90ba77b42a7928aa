// The live view's page: shows the frames the server announces, turns mouse and form input
// into control changes (src/view/controls.rs), asks for the final render.
// The camera orbits, zooms and pans about a pivot the server chose (the scene's subject,
// src/view/aim.rs) or a double-click picked; Reset asks the server for the first camera.
// `window.iris` holds what the page last saw, for people debugging it and for the browser
// test (tests/view/view_browser.rs).
"use strict";

const TOKEN = new URLSearchParams(location.search).get("token") || "";
const withToken = (path) => path + (path.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(TOKEN);
const $ = (id) => document.getElementById(id);

window.iris = {
  framesShown: 0, frameId: null, generation: 0, pixelSum: null, plan: "", method: "",
  status: null, final: null, error: "", controls: null, connected: false, disconnected: false,
  subject: null, camera: null, pivot: null,
};

// Whether a change is on its way to the server or waiting to go.
Object.defineProperty(window.iris, "busy", { enumerable: true, get: () => !!(inFlight || waiting) });

// ---------------------------------------------------------------- server calls
async function post(path, body) {
  let r;
  try {
    r = await fetch(withToken(path), {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
    });
  } catch (e) {
    disconnected("the server does not answer");
    throw new Error("disconnected: the server does not answer");
  }
  const answer = await r.json().catch(() => ({ error: r.statusText }));
  if (!r.ok) throw new Error(answer.error || r.statusText);
  return answer;
}

function showError(message) {
  window.iris.error = message || "";
  $("error").textContent = message || "";
}

// The server is gone (it said bye, or its event stream or a request failed).
function disconnected(why) {
  window.iris.connected = false;
  window.iris.disconnected = true;
  $("state").textContent = "disconnected" + (why ? ": " + why : "");
  $("spinner").hidden = true;
  document.body.classList.add("offline");
}

// Changes go out one at a time; while one is in flight the newest waiting one replaces
// the others (an orbit drag sends many).
let inFlight = null;
let waiting = null;
function change(delta) {
  waiting = Object.assign(waiting || {}, delta);
  if (!inFlight) flush();
}
async function flush() {
  if (!waiting) return;
  const body = waiting;
  waiting = null;
  inFlight = body;
  try {
    const answer = await post("/controls", body);
    window.iris.requested = answer.generation;
    // The server's camera and pivot are the page's from now on unless the page has moved
    // the camera since (a preset, Reset and a pick set them on the server).
    if (!dragging && !(waiting && (waiting.camera || waiting.pivot))) adopt(answer.controls);
    showError("");
  } catch (e) {
    showError(e.message);
  } finally {
    inFlight = null;
    if (waiting) flush();
  }
}

// ---------------------------------------------------------------- camera
let camera = null; // {eye: [x,y,z], target: [x,y,z], fov}
let pivot = null; // [x,y,z]
let radius = 1; // the subject's, for the zoom's limits
let dragging = false;
const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const scale = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const len = (a) => Math.hypot(a[0], a[1], a[2]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => scale(a, 1 / (len(a) || 1));

// `v` turned by `angle` radians about the unit `axis` (Rodrigues).
function rotate(v, axis, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

function adopt(c) {
  camera = c.camera;
  pivot = c.pivot;
  window.iris.camera = camera;
  window.iris.pivot = pivot;
}

function moved() {
  window.iris.camera = camera;
  window.iris.pivot = pivot;
  change({ camera, pivot });
}

// Eye and target turn together about the pivot: about the vertical through it, then up or
// down about the horizontal across the view (the eye stays below the poles).
function orbit(dx, dy) {
  const about = (p, axis, a) => add(pivot, rotate(sub(p, pivot), axis, a));
  const yaw = -dx * 0.008;
  let eye = about(camera.eye, [0, 1, 0], yaw), target = about(camera.target, [0, 1, 0], yaw);
  const off = sub(eye, pivot);
  const el = Math.asin(Math.max(-1, Math.min(1, off[1] / (len(off) || 1))));
  const pitch = Math.max(-1.5, Math.min(1.5, el + dy * 0.008)) - el;
  // Straight above or below the pivot (the top view) any horizontal axis tilts it.
  const across = cross(off, [0, 1, 0]);
  const axis = len(across) > 1e-9 * len(off) ? norm(across) : [1, 0, 0];
  eye = about(eye, axis, pitch);
  target = about(target, axis, pitch);
  camera = { ...camera, eye, target };
  moved();
}

function pan(dx, dy, height) {
  const forward = norm(sub(camera.target, camera.eye));
  const right = norm(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const dist = Math.abs(dot(sub(pivot, camera.eye), forward)) || len(sub(camera.target, camera.eye));
  const perPixel = (2 * dist * Math.tan((camera.fov * Math.PI) / 360)) / height;
  const move = add(scale(right, -dx * perPixel), scale(up, dy * perPixel));
  camera = { ...camera, eye: add(camera.eye, move), target: add(camera.target, move) };
  pivot = add(pivot, move);
  moved();
}

// The camera scaled about the pivot (which stays where it is in the image), its distance
// kept from 1.2 to 200 subject radii (a camera already farther may come closer).
function zoom(steps) {
  const dist = len(sub(camera.eye, pivot)) || 1;
  const far = Math.max(200 * radius, dist);
  const k = Math.min(far, Math.max(1.2 * radius, dist * Math.exp(steps * 0.0015))) / dist;
  const at = (p) => add(pivot, scale(sub(p, pivot), k));
  camera = { ...camera, eye: at(camera.eye), target: at(camera.target) };
  moved();
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
  box.addEventListener("dblclick", (e) => {
    const r = $("frame").getBoundingClientRect();
    const x = (e.clientX - r.left) / r.width, y = (e.clientY - r.top) / r.height;
    if (x >= 0 && x <= 1 && y >= 0 && y <= 1) change({ pick: [x, y] });
  });
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
  const moving = dragging || (inFlight && inFlight.camera) || (waiting && waiting.camera);
  if (!moving) adopt(c);
  for (const key of ["stone", "metal", "studio", "env", "exposure", "method", "spectral"]) {
    const select = $(key);
    if (![...select.options].some((o) => o.value === c[key])) fill(select, [c[key]]);
    select.value = c[key];
  }
  $("turn").value = c.turn;
  $("turn-value").textContent = c.turn + "°";
}

// The subject and the live image's size, from the state.
function showSubject(s) {
  window.iris.subject = s.subject;
  radius = s.subject.radius || 1;
  // `material 0 "Diamond"` (the loader's label) reads as `Diamond`.
  const names = s.subject.names.map((n) => n.replace(/^material \d+ "(.*)"$/, "$1")).join(", ");
  $("stone-scope").textContent = s.subject.kind === "stones"
    ? "applies to the stones: " + names + " (the floor and lights keep theirs)"
    : "applies to every material but the lights (no stone found): " + names;
  const [w, h] = s.preview_size;
  // The picture fills the pane's width, as high as the window lets it, at the render's
  // aspect; the bars under it are as wide.
  $("frame-box").style.aspectRatio = `${w} / ${h}`;
  $("stage").style.maxWidth = `calc((100vh - 150px) * ${w / h})`;
  window.iris.aspect = w / h;
  finalHeight();
}

function finalHeight() {
  const a = window.iris.aspect || 4 / 3;
  $("final-height").value = Math.max(1, Math.round(Number($("final-width").value) / a));
}

function bindControls() {
  for (const select of document.querySelectorAll("[data-control]")) {
    select.addEventListener("change", () => change({ [select.id]: select.value }));
  }
  $("view").addEventListener("change", () => {
    if ($("view").value) change({ view: $("view").value });
    $("view").value = "";
  });
  $("reset").addEventListener("click", () => change({ reset: true }));
  $("turn").addEventListener("input", () => {
    $("turn-value").textContent = $("turn").value + "°";
    change({ turn: Number($("turn").value) });
  });
  $("final-width").addEventListener("input", finalHeight);
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
function list(id, items) {
  const ul = $(id);
  ul.innerHTML = "";
  for (const text of items) {
    const li = document.createElement("li");
    li.textContent = text;
    ul.appendChild(li);
  }
}

function showStatus(s) {
  window.iris.status = s;
  if (window.iris.disconnected) return;
  $("state").textContent = s.state + (s.error ? ": " + s.error : "");
  $("spinner").hidden = !["starting", "rendering"].includes(s.state);
  if (s.state === "error") showError(s.error);
  if (!s.plan) return;
  window.iris.method = s.method;
  $("method-name").textContent = s.method;
  $("purpose").textContent = s.purpose ? "— " + s.purpose : "";
  const rows = s.plan.map((st) => `<tr class="${st.used ? "used" : ""}"><th></th><td></td></tr>`);
  const body = $("plan").tBodies[0];
  body.innerHTML = rows.join("");
  s.plan.forEach((st, i) => { body.rows[i].cells[0].textContent = st.name; body.rows[i].cells[1].textContent = st.reason; });
  window.iris.plan = s.plan.map((st) => `${st.name}: ${st.reason}`).join("\n");
  list("looks", (s.looks || []).map((l) => l.text));
  list("notes", s.notes || []);
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

// "3 s", "4 min", "2.5 h".
function duration(ms) {
  const s = ms / 1000;
  if (s < 90) return `${Math.max(1, Math.round(s))} s`;
  if (s < 5400) return `${Math.round(s / 60)} min`;
  return `${(s / 3600).toFixed(1)} h`;
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
  const unit = window.iris.status?.unit === "passes" ? "passes" : "spp";
  $("units").textContent = f.units == null ? "–" : `${f.units} ${unit}`;
  $("estimate").textContent = f.estimate == null ? "" : `display error ≈ ${(100 * f.estimate).toFixed(2)} %`;
  const clean = f.clean_in_ms == null ? "" : f.clean_in_ms === 0 ? "clean"
    : `clean in ≈ ${duration(f.clean_in_ms)}`;
  $("clean").textContent = clean;
  $("clean-summary").textContent = f.clean_in_ms == null ? ""
    : f.clean_in_ms === 0 ? `Clean: the preview reached ${(100 * f.target).toFixed(1)} % display error.`
    : `Time to clean (${(100 * f.target).toFixed(1)} % display error): ≈ ${duration(f.clean_in_ms)} more at this size.`;
  $("overlay").textContent = f.denoised ? "denoised" : "";
}

function connect() {
  const events = new EventSource(withToken("/events"));
  events.addEventListener("open", () => {
    window.iris.connected = true;
    window.iris.disconnected = false;
    document.body.classList.remove("offline");
  });
  // The browser retries a dropped stream by itself; until it is back the page says so.
  events.addEventListener("error", () => {
    if (events.readyState !== EventSource.OPEN) disconnected("the server is not answering");
  });
  events.addEventListener("state", (e) => {
    const s = JSON.parse(e.data);
    adopt(s.controls);
    showControls(s.controls);
    showSubject(s);
    showStatus(s.status);
    $("scene").textContent = s.scene;
    if (s.frame != null) showFrame({ ...(s.last_frame || {}), id: s.frame, generation: s.generation });
  });
  events.addEventListener("status", (e) => showStatus(JSON.parse(e.data)));
  events.addEventListener("frame", (e) => showFrame(JSON.parse(e.data)));
  events.addEventListener("controls", (e) => showControls(JSON.parse(e.data)));
  events.addEventListener("final", (e) => {
    const f = JSON.parse(e.data);
    if (f.state === "rendering") $("state").textContent = "rendering the final image…";
  });
  events.addEventListener("bye", () => {
    events.close();
    disconnected("the server stopped");
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

start().catch((e) => { showError("cannot start: " + e.message); disconnected(""); });
