//! An `iris view` process for the tests (tests/view/view.rs, tests/view/view_browser.rs), and a
//! minimal HTTP/1.0 client for it: each request closes its connection, so a body (an
//! event stream too) is read to its end without chunked decoding.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `iris view` (killed when dropped).
pub struct View {
    /// The process.
    pub child: Child,
    /// Its port on 127.0.0.1.
    pub port: u16,
    /// Its token.
    pub token: String,
    /// The URL it printed.
    pub url: String,
    /// Where its final renders go.
    pub out_dir: PathBuf,
}

impl View {
    /// Starts `iris view SCENE --no-open --port 0 --out-dir OUT` with `extra` flags and
    /// reads the URL it prints.
    pub fn start(scene: &str, out_dir: &Path, extra: &[&str]) -> View {
        let mut child = Command::new(env!("CARGO_BIN_EXE_iris"))
            .args(["view", scene, "--no-open", "--port", "0", "--out-dir"])
            .arg(out_dir)
            .args(extra)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start iris view");
        let stdout = child.stdout.take().expect("stdout");
        let mut lines = BufReader::new(stdout).lines();
        let url = loop {
            let line = lines
                .next()
                .expect("iris view ended before printing its URL")
                .expect("read stdout");
            if let Some(url) = line.strip_prefix("iris view: http://") {
                break format!("http://{url}");
            }
        };
        // Keep reading stdout so the process never blocks on a full pipe.
        std::thread::spawn(move || for _ in lines {});
        let port = url
            .split(':')
            .nth(2)
            .and_then(|p| p.split('/').next())
            .and_then(|p| p.parse().ok())
            .expect("port in the URL");
        let token = url.split("token=").nth(1).expect("token").to_string();
        View {
            child,
            port,
            token,
            url,
            out_dir: out_dir.to_path_buf(),
        }
    }

    /// `path` with the token appended.
    pub fn with_token(&self, path: &str) -> String {
        let sep = if path.contains('?') { '&' } else { '?' };
        format!("{path}{sep}token={}", self.token)
    }

    /// One request; (status, body).
    pub fn request(
        &self,
        method: &str,
        path: &str,
        host: Option<&str>,
        body: Option<&str>,
    ) -> (u16, Vec<u8>) {
        let mut s = TcpStream::connect(("127.0.0.1", self.port)).expect("connect");
        s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
        let host = host.map_or(format!("127.0.0.1:{}", self.port), str::to_string);
        let mut head = format!("{method} {path} HTTP/1.0\r\nHost: {host}\r\n");
        if let Some(b) = body {
            head += &format!(
                "Content-Type: application/json\r\nContent-Length: {}\r\n",
                b.len()
            );
        }
        head += "\r\n";
        s.write_all(head.as_bytes()).unwrap();
        if let Some(b) = body {
            s.write_all(b.as_bytes()).unwrap();
        }
        let mut raw = Vec::new();
        s.read_to_end(&mut raw).expect("read the answer");
        let split = raw
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("end of the headers");
        let status = std::str::from_utf8(&raw[9..12]).unwrap().parse().unwrap();
        (status, raw[split + 4..].to_vec())
    }

    /// GET with the token; (status, body as text).
    pub fn get(&self, path: &str) -> (u16, String) {
        let (s, b) = self.request("GET", &self.with_token(path), None, None);
        (s, String::from_utf8_lossy(&b).into_owned())
    }

    /// POST JSON with the token; (status, body as JSON or the text as a string).
    pub fn post(&self, path: &str, body: &str) -> (u16, serde_json::Value) {
        let (s, b) = self.request("POST", &self.with_token(path), None, Some(body));
        let v = serde_json::from_slice(&b)
            .unwrap_or_else(|_| serde_json::Value::String(String::from_utf8_lossy(&b).into()));
        (s, v)
    }

    /// The event stream: (name, JSON) pairs as they come.
    pub fn events(&self) -> Events {
        let mut s = TcpStream::connect(("127.0.0.1", self.port)).expect("connect");
        s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
        let head = format!(
            "GET {} HTTP/1.0\r\nHost: 127.0.0.1:{}\r\nAccept: text/event-stream\r\n\r\n",
            self.with_token("/events"),
            self.port
        );
        s.write_all(head.as_bytes()).unwrap();
        let mut reader = BufReader::new(s);
        let mut line = String::new();
        // Skip the headers.
        loop {
            line.clear();
            reader.read_line(&mut line).expect("headers");
            if line.trim().is_empty() {
                break;
            }
        }
        Events { reader }
    }

    /// Polls `/state` until `done` says yes (or panics after `limit`).
    pub fn wait_state(
        &self,
        limit: Duration,
        done: impl Fn(&serde_json::Value) -> bool,
    ) -> serde_json::Value {
        let start = Instant::now();
        loop {
            let (status, body) = self.get("/state");
            assert_eq!(status, 200, "{body}");
            let v: serde_json::Value = serde_json::from_str(&body).unwrap();
            if done(&v) {
                return v;
            }
            assert!(start.elapsed() < limit, "timed out waiting; last state {v}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

/// Runs `iris render ARGS` (the arguments after `render`, from the crate's root) with the
/// value of `-o` replaced by `out`; the bytes it wrote.
pub fn rerun(args: &[String], out: &Path) -> Vec<u8> {
    let o = args.iter().position(|a| a == "-o").expect("an -o argument");
    let mut shell = args.to_vec();
    shell[o + 1] = out.display().to_string();
    let run = Command::new(env!("CARGO_BIN_EXE_iris"))
        .arg("render")
        .args(&shell)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "iris render {shell:?}: {err}");
    std::fs::read(out).unwrap()
}

impl Drop for View {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A server-sent event stream.
pub struct Events {
    reader: BufReader<TcpStream>,
}

impl Iterator for Events {
    type Item = (String, serde_json::Value);

    fn next(&mut self) -> Option<Self::Item> {
        let (mut name, mut data) = (String::new(), String::new());
        let mut line = String::new();
        loop {
            line.clear();
            if self.reader.read_line(&mut line).ok()? == 0 {
                return None;
            }
            let l = line.trim_end_matches(['\r', '\n']);
            if l.is_empty() {
                if !name.is_empty() {
                    let json = serde_json::from_str(&data).unwrap_or(serde_json::Value::Null);
                    return Some((name, json));
                }
                continue;
            }
            if let Some(n) = l.strip_prefix("event:") {
                name = n.trim().to_string();
            } else if let Some(d) = l.strip_prefix("data:") {
                data += d.trim_start();
            }
        }
    }
}

/// Where the scene's subject (the stones, `iris::prepare::subject`) is in the image a view
/// camera sees: the fraction of the image it covers and its centroid (fractions of the
/// width and height from the top-left), from one ray per pixel of a `w`×`h` image.
/// `camera` is the view's `{"eye", "target", "fov"}` JSON; `turn` in degrees.
pub struct Mask {
    /// Fraction of the pixels whose first hit is on the subject.
    pub area: f64,
    /// Centroid of those pixels, (x, y) in [0, 1]² (0.5, 0.5 when there are none).
    pub centroid: (f64, f64),
}

/// [`Mask`] of `scene` (from the crate's root) seen by the view camera `camera`.
pub fn subject_mask(scene: &str, camera: &serde_json::Value, (w, h): (u32, u32)) -> Mask {
    let xyz = |key: &str| {
        let v: Vec<String> = camera[key]
            .as_array()
            .expect("camera point")
            .iter()
            .map(|x| x.as_f64().unwrap().to_string())
            .collect();
        v.join(",")
    };
    let look = format!(
        "{}:{}:{}",
        xyz("eye"),
        xyz("target"),
        camera["fov"].as_f64().unwrap()
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let extra = [
        "--camera-look-at".to_string(),
        look,
        "--size".into(),
        format!("{w}x{h}"),
    ];
    let path = root.join(scene).display().to_string();
    let p = iris::view::aim::prepared(&path, &extra).expect("prepare the scene");
    let subject = p.subject.as_ref().expect("the subject");
    let cam = iris::camera::Camera::new(&p.camera, w, h);
    let (mut n, mut sx, mut sy) = (0u64, 0.0f64, 0.0f64);
    for y in 0..h {
        for x in 0..w {
            let ray = cam.generate_ray(glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            let on = p
                .scene
                .intersect(&ray)
                .is_some_and(|hit| subject.holds(p.scene.triangle(hit.prim).mesh as usize));
            if on {
                n += 1;
                sx += (f64::from(x) + 0.5) / f64::from(w);
                sy += (f64::from(y) + 0.5) / f64::from(h);
            }
        }
    }
    let area = n as f64 / f64::from(w * h);
    let centroid = if n == 0 {
        (0.5, 0.5)
    } else {
        (sx / n as f64, sy / n as f64)
    };
    Mask { area, centroid }
}
