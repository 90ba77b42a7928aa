//! `iris view` in a real browser: Debian's headless Chromium driven over the Chrome DevTools
//! Protocol (a WebSocket; no browser is downloaded). On the ruby: the page loads and shows
//! a first frame; a mouse drag orbits the camera and the image changes; switching the stone
//! changes the plan; the Render button renders the final image, whose printed command line,
//! run from the shell, writes the same bytes. On the round diamond (a file with its own
//! floor and light panels): the stone stays in the middle of the frame through a 160-pixel
//! drag and the three-quarter preset (by one ray per pixel, [`common::view::subject_mask`]),
//! the first drag after the preset starts from it, Reset restores the first camera, a
//! double-click moves the pivot, and after Ctrl-C the page says "disconnected".
//! Screenshots of each step go to target/view-screenshots/ (docs/images/view-*.png are
//! copies).
//!
//! The browser is `$IRIS_CHROMIUM` or `chromium` on the PATH; without one the test says so
//! and passes, unless IRIS_REQUIRE_BROWSER=1 (set by `.ci/run`), which makes it fail.

use crate::common;
use common::view::View;
use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

const LIMIT: Duration = Duration::from_secs(180);

/// A headless Chromium and one page attached over CDP (killed when dropped).
struct Browser {
    child: Child,
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    next: u64,
    session: String,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn find_chromium() -> Option<String> {
    if let Ok(b) = std::env::var("IRIS_CHROMIUM") {
        return Some(b);
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join("chromium"))
        .find(|p| p.is_file())
        .map(|p| p.display().to_string())
}

impl Browser {
    fn launch(binary: &str, profile: &std::path::Path) -> Browser {
        let mut child = Command::new(binary)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--no-first-run",
                "--remote-debugging-port=0",
                "--window-size=1400,1000",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("start {binary}: {e}"));
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let ws_url = loop {
            let line = lines
                .next()
                .expect("chromium ended before its DevTools URL")
                .unwrap();
            if let Some(u) = line.strip_prefix("DevTools listening on ") {
                break u.trim().to_string();
            }
        };
        std::thread::spawn(move || for _ in lines {});
        let (ws, _) = tungstenite::connect(ws_url.as_str()).expect("CDP WebSocket");
        let mut b = Browser {
            child,
            ws,
            next: 1,
            session: String::new(),
        };
        let target = b.call("Target.createTarget", json!({"url": "about:blank"}));
        let attached = b.call(
            "Target.attachToTarget",
            json!({"targetId": target["targetId"], "flatten": true}),
        );
        b.session = attached["sessionId"].as_str().unwrap().to_string();
        b
    }

    /// One CDP command (on the page once attached); its result.
    fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next;
        self.next += 1;
        let mut msg = json!({"id": id, "method": method, "params": params});
        if !self.session.is_empty() {
            msg["sessionId"] = json!(self.session);
        }
        self.ws.send(Message::text(msg.to_string())).unwrap();
        loop {
            let m = self.ws.read().expect("CDP read");
            let Message::Text(t) = m else { continue };
            let v: Value = serde_json::from_str(t.as_str()).unwrap();
            if v["id"] == json!(id) {
                assert!(v.get("error").is_none(), "{method}: {v}");
                return v["result"].clone();
            }
        }
    }

    /// A JavaScript expression's value in the page.
    fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": expr, "returnByValue": true, "awaitPromise": true}),
        );
        assert!(r.get("exceptionDetails").is_none(), "{expr}: {r}");
        r["result"]["value"].clone()
    }

    /// Polls `expr` until it is truthy; its value.
    fn wait(&mut self, expr: &str) -> Value {
        let start = Instant::now();
        loop {
            let v = self.eval(expr);
            if !(v.is_null() || v == json!(false)) {
                return v;
            }
            let state = self.eval("JSON.stringify(window.iris || null)");
            assert!(
                start.elapsed() < LIMIT,
                "waited for {expr}; page state {state}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// The centre of an element, in CSS pixels.
    fn centre(&mut self, id: &str) -> (f64, f64) {
        let r = self.eval(&format!(
            "(() => {{ const e = document.getElementById('{id}'); \
             e.scrollIntoView({{block: 'center'}}); const r = e.getBoundingClientRect(); \
             return [r.x + r.width / 2, r.y + r.height / 2]; }})()"
        ));
        (r[0].as_f64().unwrap(), r[1].as_f64().unwrap())
    }

    fn mouse(&mut self, kind: &str, (x, y): (f64, f64), buttons: u32) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": kind, "x": x, "y": y, "button": "left", "buttons": buttons,
                   "clickCount": 1}),
        );
    }

    fn screenshot(&mut self, name: &str) {
        let shot = self.call("Page.captureScreenshot", json!({"format": "png"}));
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/view-screenshots");
        std::fs::create_dir_all(&dir).unwrap();
        let bytes = base64(shot["data"].as_str().unwrap());
        std::fs::write(dir.join(format!("{name}.png")), bytes).unwrap();
    }
}

/// Standard base64 (RFC 4648) to bytes.
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let digits: Vec<u8> = text.bytes().filter(|&c| c != b'=').map(value).collect();
    digits
        .chunks(4)
        .flat_map(|q| {
            let n = q
                .iter()
                .enumerate()
                .fold(0u32, |n, (i, &d)| n | u32::from(d) << (18 - 6 * i));
            (0..q.len() - 1).map(move |i| (n >> (16 - 8 * i)) as u8)
        })
        .collect()
}

/// The browser, or `None` (the test then passes, saying why) unless one is required.
fn chromium_or_skip() -> Option<String> {
    let found = find_chromium();
    if found.is_none() {
        let required = std::env::var("IRIS_REQUIRE_BROWSER").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "IRIS_REQUIRE_BROWSER=1 but no chromium (apt-get install chromium)"
        );
        eprintln!("SKIPPED: no chromium on the PATH (set IRIS_CHROMIUM, or IRIS_REQUIRE_BROWSER=1 to fail)");
    }
    found
}

#[test]
fn the_page_orbits_switches_and_renders_what_the_command_reproduces() {
    let Some(chromium) = chromium_or_skip() else {
        return;
    };
    let out = common::scratch_dir("view_browser");
    let mut view = View::start(
        "assets/scenes/ruby.glb",
        &out,
        &["--width", "320", "--threads", "2"],
    );
    let profile = out.join("profile");
    let mut b = Browser::launch(&chromium, &profile);
    b.call("Page.navigate", json!({"url": view.url}));

    // 1. A first frame.
    b.wait("window.iris && window.iris.framesShown >= 1 && window.iris.pixelSum !== null");
    b.wait("window.iris.status && window.iris.status.plan && true");
    let first_sum = b.eval("window.iris.pixelSum");
    let first_plan = b.eval("window.iris.plan");
    b.screenshot("first-frame");

    // 2. Drag to orbit: a new generation, and its image differs.
    let c = b.centre("frame-box");
    b.mouse("mousePressed", c, 1);
    for k in 1..=12 {
        b.mouse("mouseMoved", (c.0 + 5.0 * k as f64, c.1 + k as f64), 1);
    }
    b.mouse("mouseReleased", (c.0 + 60.0, c.1 + 12.0), 0);
    b.wait("window.iris.generation >= 2 && window.iris.framesShown > 1");
    let orbit_sum = b.wait(&format!(
        "window.iris.generation >= 2 && window.iris.pixelSum !== {first_sum} && window.iris.pixelSum"
    ));
    assert_ne!(orbit_sum, first_sum);
    b.wait("window.iris.units >= 16");
    b.eval("window.scrollTo(0, 0)");
    b.screenshot("orbit");

    // 3. Another stone: the plan changes.
    b.eval(
        "(() => { const s = document.getElementById('stone'); s.value = 'diamond'; \
            s.dispatchEvent(new Event('change')); return true; })()",
    );
    let plan = b.wait("window.iris.plan.includes('--stone diamond') && window.iris.plan");
    assert_ne!(plan, first_plan);
    b.wait("window.iris.controls && window.iris.controls.stone === 'diamond'");
    let generation = view.wait_state(LIMIT, |_| true)["generation"].clone();
    b.wait(&format!(
        "window.iris.generation === {generation} && window.iris.units >= 4"
    ));

    // 4. Render: the printed command writes the same image.
    b.eval(
        "(() => { const w = document.getElementById('final-width'); w.value = 96; \
            w.dispatchEvent(new Event('input')); \
            document.getElementById('final-units').value = 4; return true; })()",
    );
    let button = b.centre("render");
    b.mouse("mousePressed", button, 1);
    b.mouse("mouseReleased", button, 0);
    let answer = b.wait("window.iris.final");
    // The final render has the view's aspect (the ruby's camera is square).
    assert_eq!(
        b.eval("document.getElementById('final-height').value"),
        json!("96")
    );
    b.wait("!document.getElementById('final-result').hidden");
    b.screenshot("final");
    let command = answer["command"].as_str().unwrap();
    assert_eq!(
        b.eval("document.getElementById('command').textContent"),
        json!(command)
    );
    let written = answer["output"].as_str().unwrap().to_string();
    let again = out.join("from-shell.png");
    // The command line as a shell would split it: every argument is plain or single-quoted
    // (src/view/encode.rs), none here needs quotes.
    assert!(!command.contains('\''), "{command}");
    let words: Vec<String> = command.split_whitespace().map(String::from).collect();
    assert_eq!(&words[..2], ["iris", "render"]);
    assert!(
        std::fs::read(&written).unwrap() == common::view::rerun(&words[2..], &again),
        "{written} and the command's image differ"
    );

    // 5. The server killed without a word: the dropped event stream shows.
    view.child.kill().unwrap();
    let _ = view.child.wait();
    b.wait("window.iris.disconnected === true");
    assert_disconnected(&mut b);
}

#[test]
fn base64_decodes_rfc4648_vectors() {
    assert_eq!(base64("Zm9vYmFy"), b"foobar");
    assert_eq!(base64("Zm9vYg=="), b"foob");
    assert_eq!(base64("Zm8="), b"fo");
}

const GEM: &str = "assets/gems/round_diamond.glb";
/// The size of the subject masks ([`common::view::subject_mask`]).
const MASK: (u32, u32) = (96, 72);

/// Waits until the page has no change on its way and the server holds the camera it
/// shows; the server's state.
fn settled(b: &mut Browser, v: &View) -> Value {
    b.wait("window.iris.busy === false && window.iris.camera !== null");
    let page = b.eval("window.iris.camera");
    let state = v.wait_state(LIMIT, |_| true);
    let server = &state["controls"]["camera"];
    for key in ["eye", "target"] {
        for k in 0..3 {
            let (p, s) = (
                page[key][k].as_f64().unwrap(),
                server[key][k].as_f64().unwrap(),
            );
            assert!(
                (p - s).abs() <= 1e-6 * (1.0 + s.abs()),
                "page {page} server {server}"
            );
        }
    }
    state
}

fn distance(a: &Value, b: &Value) -> f64 {
    (0..3)
        .map(|k| (a[k].as_f64().unwrap() - b[k].as_f64().unwrap()).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The stone is in the middle of the frame and at least `share` of `first`'s area.
fn in_frame(state: &Value, first: &common::view::Mask, share: f64, what: &str) -> f64 {
    let m = common::view::subject_mask(GEM, &state["controls"]["camera"], MASK);
    let (cx, cy) = m.centroid;
    assert!(
        (cx - 0.5).abs() < 0.2 && (cy - 0.5).abs() < 0.2,
        "{what}: the stone's centroid ({cx:.2}, {cy:.2}) is off the middle"
    );
    assert!(
        m.area >= share * first.area,
        "{what}: the stone covers {:.4} of the frame, was {:.4}",
        m.area,
        first.area
    );
    m.area
}

fn drag(b: &mut Browser, (dx, dy): (f64, f64)) {
    let c = b.centre("frame-box");
    b.mouse("mousePressed", c, 1);
    for k in 1..=16 {
        let t = f64::from(k) / 16.0;
        b.mouse("mouseMoved", (c.0 + t * dx, c.1 + t * dy), 1);
    }
    b.mouse("mouseReleased", (c.0 + dx, c.1 + dy), 0);
}

/// The page says "disconnected" and its spinner is hidden.
fn assert_disconnected(b: &mut Browser) {
    let state = b.eval("document.getElementById('state').textContent");
    assert!(
        state.as_str().unwrap().starts_with("disconnected"),
        "{state}"
    );
    assert_eq!(
        b.eval("document.getElementById('spinner').hidden"),
        json!(true)
    );
}

/// Waits for a frame at rest of the server's current generation (denoised, when the build
/// has the denoiser), then takes a screenshot.
fn shot_at_rest(b: &mut Browser, v: &View, name: &str) {
    let generation = v.wait_state(LIMIT, |_| true)["generation"].clone();
    let denoised = if cfg!(feature = "denoise") {
        "window.iris.denoised === true"
    } else {
        "true"
    };
    b.wait(&format!(
        "window.iris.generation === {generation} && {denoised} && window.iris.units >= 8"
    ));
    b.eval("window.scrollTo(0, 0)");
    b.screenshot(name);
}

#[test]
fn the_stone_stays_in_frame_through_a_drag_a_preset_and_a_reset_and_ctrl_c_shows() {
    let Some(chromium) = chromium_or_skip() else {
        return;
    };
    let out = common::scratch_dir("view_browser_gem");
    let mut view = View::start(GEM, &out, &["--width", "400", "--threads", "2"]);
    let mut b = Browser::launch(&chromium, &out.join("profile"));
    b.call("Page.navigate", json!({"url": view.url}));
    b.wait("window.iris && window.iris.framesShown >= 1 && window.iris.subject !== null");
    // The Stone control says what it changes: the diamond, not the floor.
    let scope = b.eval("document.getElementById('stone-scope').textContent");
    let scope = scope.as_str().unwrap();
    assert!(scope.starts_with("applies to the stones:") && scope.contains("Diamond"));
    assert!(!scope.contains("Floor"), "{scope}");
    let home = settled(&mut b, &view);
    let first = common::view::subject_mask(GEM, &home["controls"]["camera"], MASK);
    assert!(
        first.area > 0.01,
        "the stone covers {:.4} of the first frame",
        first.area
    );
    shot_at_rest(&mut b, &view, "diamond-first-frame");

    // A 160-pixel drag orbits about the stone: it stays in the middle, as large.
    drag(&mut b, (160.0, 0.0));
    let orbited = settled(&mut b, &view);
    assert_ne!(orbited["controls"]["camera"], home["controls"]["camera"]);
    in_frame(&orbited, &first, 0.5, "after a 160-pixel drag");
    shot_at_rest(&mut b, &view, "diamond-orbit");

    // The three-quarter preset frames the stone, not the file's floor and lights.
    b.eval(
        "(() => { const s = document.getElementById('view'); s.value = 'threequarter'; \
            s.dispatchEvent(new Event('change')); return true; })()",
    );
    b.wait("window.iris.busy === false");
    let preset = settled(&mut b, &view);
    let area = in_frame(&preset, &first, 1.0, "after View → threequarter");
    assert!(area > 0.1, "the framed stone covers {area:.4} of the frame");
    shot_at_rest(&mut b, &view, "diamond-threequarter");

    // The first drag after the preset starts from the preset's camera.
    drag(&mut b, (20.0, 0.0));
    let nudged = settled(&mut b, &view);
    let (eye, preset_eye) = (
        &nudged["controls"]["camera"]["eye"],
        &preset["controls"]["camera"]["eye"],
    );
    let reach = distance(preset_eye, &preset["controls"]["pivot"]);
    assert!(
        distance(eye, preset_eye) < 0.3 * reach,
        "the drag after the preset moved the eye {} (orbit radius {reach})",
        distance(eye, preset_eye)
    );
    in_frame(&nudged, &first, 1.0, "after the preset and a drag");

    // Reset: the first camera and pivot again.
    let button = b.centre("reset");
    b.mouse("mousePressed", button, 1);
    b.mouse("mouseReleased", button, 0);
    let reset = settled(&mut b, &view);
    assert_eq!(reset["controls"]["camera"], home["controls"]["camera"]);
    assert_eq!(reset["controls"]["pivot"], home["controls"]["pivot"]);

    // A double-click on the stone moves the pivot onto its surface; nothing restarts.
    let generation = reset["generation"].clone();
    b.eval(
        "(() => { const r = document.getElementById('frame').getBoundingClientRect(); \
            document.getElementById('frame-box').dispatchEvent(new MouseEvent('dblclick', \
            {bubbles: true, clientX: r.x + r.width / 2, clientY: r.y + r.height / 2})); \
            return true; })()",
    );
    let picked = view.wait_state(LIMIT, |s| {
        s["controls"]["pivot"] != home["controls"]["pivot"]
    });
    assert_eq!(picked["generation"], generation);
    let radius = picked["subject"]["radius"].as_f64().unwrap();
    let off = distance(&picked["controls"]["pivot"], &picked["subject"]["centre"]);
    assert!(off <= 1.01 * radius, "picked {off} from the stone's centre");

    // Ctrl-C: the page says disconnected and stops the spinner.
    let pid = view.child.id().to_string();
    assert!(Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap()
        .success());
    b.wait("window.iris.disconnected && document.getElementById('state').textContent");
    assert_disconnected(&mut b);
    b.screenshot("diamond-disconnected");
    let _ = view.child.wait();
}
