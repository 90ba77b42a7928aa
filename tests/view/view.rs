//! `iris view` over HTTP, without a browser (tests/view/view_browser.rs drives the page): the
//! token and Host guard, nothing served outside the page's assets, changes checked by the
//! command line's rules, every page getting the same frames, a change ending the old
//! render's frames, the final render reproduced by its printed command, Ctrl-C.

use crate::common;
use common::view::View;
use std::time::Duration;

const SCENE: &str = "assets/scenes/ruby.glb";
const LONG: Duration = Duration::from_secs(120);

fn start(name: &str) -> View {
    let out = common::scratch_dir(name);
    View::start(SCENE, &out, &["--width", "96", "--threads", "2"])
}

#[test]
fn requests_without_the_token_or_from_another_host_are_refused() {
    let v = start("view_token");
    let (s, _) = v.request("GET", "/", None, None);
    assert_eq!(s, 403);
    let (s, body) = v.request("GET", "/state?token=0123", None, None);
    assert_eq!(s, 403);
    assert!(String::from_utf8_lossy(&body).contains("token"));
    let wrong_host = format!("evil.example:{}", v.port);
    let (s, _) = v.request("GET", &v.with_token("/"), Some(&wrong_host), None);
    assert_eq!(s, 403);
    let (s, page) = v.get("/");
    assert_eq!(s, 200);
    assert!(page.contains("<title>Iris view</title>"));
    assert_eq!(v.get("/app.js").0, 200);
    assert_eq!(v.get("/style.css").0, 200);
    // The browser's own request for an icon carries no token: no content, not 403.
    let (s, body) = v.request("GET", "/favicon.ico", None, None);
    assert_eq!((s, body.len()), (204, 0));
    let (s, _) = v.request("GET", "/favicon.ico", Some(&wrong_host), None);
    assert_eq!(s, 403);
}

#[test]
fn nothing_outside_the_page_assets_is_served() {
    let v = start("view_paths");
    for path in [
        "/../Cargo.toml",
        "/%2e%2e/Cargo.toml",
        "/src/view/page/app.js",
        "/assets/scenes/ruby.glb",
        "/ruby.glb",
        "/frame/../../Cargo.toml",
        "/frame/abc",
        "/frame/999999",
        "/final/1",
        "/etc/passwd",
    ] {
        let (s, body) = v.get(path);
        assert_eq!(s, 404, "{path}: {body}");
        assert!(!body.contains("[package]"), "{path}");
    }
}

#[test]
fn bad_changes_are_refused_naming_the_flag_or_the_control() {
    let v = start("view_bad");
    for (change, says) in [
        (r#"{"stone": "unobtainium"}"#, "--stone"),
        (r#"{"exposure": "99"}"#, "--exposure"),
        (r#"{"method": "magic"}"#, "--method"),
        (r#"{"env": "sky:elevation=200"}"#, "elevation"),
        (r#"{"colour": "red"}"#, "colour"),
        (
            r#"{"camera": {"eye": [0, 0, 1], "target": [0, 0, 1], "fov": 30}}"#,
            "camera",
        ),
        (r#"{"turn": "left"}"#, "turn"),
        (r#"{"reset": 1}"#, "reset"),
        (r#"{"pivot": [0, "a", 0]}"#, "pivot"),
        (r#"{"view": "sideways"}"#, "view"),
        ("not json", "JSON"),
    ] {
        let (s, body) = v.post("/controls", change);
        assert_eq!(s, 400, "{change}: {body}");
        assert!(body.to_string().contains(says), "{change}: {body}");
    }
    let (s, body) = v.post("/render", r#"{"width": 0, "height": 10, "units": 4}"#);
    assert_eq!(s, 400);
    assert!(body.to_string().contains("width"), "{body}");
    // Nothing restarted.
    assert_eq!(v.wait_state(LONG, |_| true)["restarts"], 0);
}

/// Frame events (generation, id) of a stream until it holds `n` frames of `generation`.
fn frames_until(events: &mut common::view::Events, generation: u64, n: usize) -> Vec<(u64, u64)> {
    let mut seen = Vec::new();
    for (name, data) in events {
        if name == "frame" {
            seen.push((
                data["generation"].as_u64().unwrap(),
                data["id"].as_u64().unwrap(),
            ));
            if seen.iter().filter(|f| f.0 == generation).count() >= n {
                break;
            }
        }
    }
    seen
}

#[test]
fn every_page_gets_the_same_frames_and_a_change_ends_the_old_ones() {
    let v = start("view_frames");
    v.wait_state(LONG, |s| s["frame"].is_u64());
    let (mut a, mut b) = (v.events(), v.events());
    let state = v.wait_state(LONG, |_| true);
    let mut camera = state["controls"]["camera"].clone();
    camera["eye"][0] = serde_json::json!(camera["eye"][0].as_f64().unwrap() + 0.01);
    let (s, answer) = v.post(
        "/controls",
        &serde_json::json!({ "camera": camera }).to_string(),
    );
    assert_eq!(s, 200, "{answer}");
    let generation = answer["generation"].as_u64().unwrap();
    assert_eq!(generation, 2);
    let (fa, fb) = (
        frames_until(&mut a, generation, 3),
        frames_until(&mut b, generation, 3),
    );
    for seen in [&fa, &fb] {
        // Once the new generation shows, the old one never does again.
        let first_new = seen.iter().position(|f| f.0 == generation).unwrap();
        assert!(
            seen[first_new..].iter().all(|f| f.0 == generation),
            "{seen:?}"
        );
        assert!(seen.windows(2).all(|w| w[0].1 < w[1].1), "{seen:?}");
    }
    // The same frames in both, over the ids both saw.
    let (lo, hi) = (
        fa[0].1.max(fb[0].1),
        fa.last().unwrap().1.min(fb.last().unwrap().1),
    );
    let pick = |s: &[(u64, u64)]| {
        s.iter()
            .filter(|f| (lo..=hi).contains(&f.1))
            .copied()
            .collect::<Vec<_>>()
    };
    assert!(hi >= lo);
    assert_eq!(pick(&fa), pick(&fb));
    // A frame announced is a PNG of the live size.
    let (s, png) = v.request(
        "GET",
        &v.with_token(&format!("/frame/{}", fa.last().unwrap().1)),
        None,
        None,
    );
    assert_eq!(s, 200);
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn the_final_render_is_reproduced_by_its_command_line() {
    let v = start("view_final");
    let (s, _) = v.post("/controls", r#"{"stone": "sapphire", "turn": 30}"#);
    assert_eq!(s, 200);
    let (s, answer) = v.post("/render", r#"{"width": 80, "height": 45, "units": 4}"#);
    assert_eq!(s, 200, "{answer}");
    let command = answer["command"].as_str().unwrap();
    assert!(command.starts_with("iris render assets/scenes/ruby.glb --camera-look-at "));
    assert!(command.contains("--turn 30/360") && command.contains("--stone sapphire"));
    let args: Vec<String> = answer["args"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap().to_string())
        .collect();
    let written = std::path::PathBuf::from(answer["output"].as_str().unwrap());
    assert!(written.starts_with(&v.out_dir));
    // The same arguments from the shell, into another file.
    let (x, y) = (
        std::fs::read(&written).unwrap(),
        common::view::rerun(&args, &v.out_dir.join("again.png")),
    );
    assert!(x == y, "the view's final render and its command's differ");
    // The page can fetch it.
    let (s, png) = v.request(
        "GET",
        &v.with_token(&format!("/final/{}", answer["id"])),
        None,
        None,
    );
    assert_eq!((s, png), (200, x));
}

#[test]
fn ctrl_c_stops_the_server() {
    let mut v = start("view_stop");
    v.wait_state(LONG, |s| s["frame"].is_u64());
    // Two open event streams, as two tabs or `curl -N /events` hold them.
    let streams = [v.events(), v.events()];
    let pid = v.child.id().to_string();
    assert!(std::process::Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap()
        .success());
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(s) = v.child.try_wait().unwrap() {
            break s;
        }
        assert!(start.elapsed() < LONG, "iris view did not stop on SIGINT");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(status.code(), Some(130));
    assert!(std::net::TcpStream::connect(("127.0.0.1", v.port)).is_err());
    // Each stream's last event is `bye`, then it ends.
    for events in streams {
        let names: Vec<String> = events.map(|(name, _)| name).collect();
        assert_eq!(names.first().map(String::as_str), Some("state"));
        assert_eq!(names.last().map(String::as_str), Some("bye"), "{names:?}");
    }
}

const GEM: &str = "assets/gems/round_diamond.glb";

#[test]
fn the_view_orbits_the_stones_and_its_stone_control_leaves_the_floor_alone() {
    let out = common::scratch_dir("view_gem");
    let v = View::start(GEM, &out, &["--width", "96", "--threads", "2"]);
    let first = v.wait_state(LONG, |s| s["status"]["plan"].is_array());
    // The subject is the diamond alone (the file also holds a floor and two light panels),
    // and the first camera's pivot is its centre.
    let subject = &first["subject"];
    assert_eq!(subject["kind"], "stones");
    let names = subject["names"].as_array().unwrap();
    assert_eq!(names.len(), 1, "{subject}");
    assert!(names[0].as_str().unwrap().contains("Diamond"), "{subject}");
    assert_eq!(first["controls"]["pivot"], subject["centre"]);
    let radius = subject["radius"].as_f64().unwrap();
    assert!(radius > 0.001 && radius < 0.01, "{subject}");
    // The stone control: only the diamond's material changes.
    let (s, answer) = v.post("/controls", r#"{"stone": "sapphire"}"#);
    assert_eq!(s, 200, "{answer}");
    let generation = answer["generation"].clone();
    let state = v.wait_state(LONG, |s| {
        s["status"]["generation"] == generation && s["status"]["looks"].is_array()
    });
    let looks = state["status"]["looks"].as_array().unwrap();
    assert_eq!(looks.len(), 1, "{looks:?}");
    let changed = looks[0]["materials"].as_array().unwrap();
    assert_eq!(changed.len(), 1, "{looks:?}");
    assert!(
        changed[0].as_str().unwrap().contains("Diamond"),
        "{looks:?}"
    );
    assert_eq!(looks[0]["meshes"], 1);
    for other in ["Floor", "light"] {
        assert!(!looks[0].to_string().contains(other), "{looks:?}");
    }
}

#[test]
fn presets_reset_and_the_pivot_are_about_the_subject() {
    let v = start("view_aim");
    let home = v.wait_state(LONG, |s| s["frame"].is_u64());
    let centre = home["subject"]["centre"].clone();
    // A preset frames the subject and orbits about its centre.
    let (s, answer) = v.post("/controls", r#"{"view": "top"}"#);
    assert_eq!(s, 200, "{answer}");
    assert_eq!(answer["controls"]["pivot"], centre);
    assert_ne!(answer["controls"]["camera"], home["controls"]["camera"]);
    let generation = answer["generation"].as_u64().unwrap();
    // The pivot alone restarts nothing.
    let (s, answer) = v.post("/controls", r#"{"pivot": [0.001, 0.002, 0.003]}"#);
    assert_eq!(s, 200, "{answer}");
    assert_eq!(answer["generation"].as_u64(), Some(generation));
    let pivot = &answer["controls"]["pivot"];
    assert!((pivot[2].as_f64().unwrap() - 0.003).abs() < 1e-9, "{pivot}");
    // Reset: the first camera and pivot again.
    let (s, answer) = v.post("/controls", r#"{"reset": true}"#);
    assert_eq!(s, 200, "{answer}");
    assert_eq!(answer["controls"]["camera"], home["controls"]["camera"]);
    assert_eq!(answer["controls"]["pivot"], centre);
    // A pick outside the image, or where nothing is, is refused and changes nothing.
    for (pick, says) in [("[2, 0.5]", "pick"), ("[0.5]", "pick")] {
        let (s, body) = v.post("/controls", &format!(r#"{{"pick": {pick}}}"#));
        assert_eq!(s, 400, "{pick}: {body}");
        assert!(body.to_string().contains(says), "{body}");
    }
}

#[test]
fn a_bad_scene_or_flag_fails_before_listening() {
    let out = common::scratch_dir("view_bad_scene");
    let missing = out.join("missing.glb");
    for args in [
        vec![
            "view".to_string(),
            missing.display().to_string(),
            "--no-open".into(),
        ],
        vec![
            "view".into(),
            SCENE.into(),
            "--no-open".into(),
            "--width".into(),
            "10".into(),
        ],
    ] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
            .args(&args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        assert!(!o.status.success());
        let (out, err) = (
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr),
        );
        assert!(!out.contains("http://"), "{out}");
        let names = if args[1].ends_with("missing.glb") {
            "missing.glb"
        } else {
            "--width"
        };
        assert!(err.contains(names), "{err}");
    }
}
