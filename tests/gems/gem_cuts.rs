//! `iris gem` and `assets/gems/`: every cut is closed (every edge shared by exactly two
//! triangles, in opposite directions, after welding equal positions), outward-wound,
//! convex and flat-shaded; its measured proportions equal the stated ones (angles within
//! 0.1°); the .glb loads with Iris's loader with the named stone's IOR, dispersion and
//! absorption; bad arguments fail without writing; the shipped previews equal a
//! regeneration and render to a finite, non-black image.
//!
//! Geometry is measured from the files `iris gem --bare` writes, read back with Iris's
//! glTF loader: facet normals from the triangles' positions (grouped into facets by the
//! stored flat normal), sizes from the vertex positions.

use crate::common;

use glam::{DVec3, Vec3};
use iris::assets::gems::{write_gem_assets, GEM_ASSETS};
use iris::material::MaterialDesc;
use iris::scene::desc::{MeshDesc, SceneDesc};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Writes `iris gem` with `args` (plus `-o dir/name`) and loads it.
fn gem(dir: &Path, name: &str, args: &[&str]) -> SceneDesc {
    let out = dir.join(name);
    let mut all: Vec<&str> = vec!["gem"];
    all.extend_from_slice(args);
    let o = out.to_string_lossy().into_owned();
    all.extend_from_slice(&["-o", &o]);
    let run = common::iris(&all, dir);
    assert!(run.status.success(), "{args:?}: {}", common::stderr(&run));
    iris::load::load_scene(&out).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn key(p: Vec3) -> [u32; 3] {
    // + 0.0 turns −0.0 into +0.0, so the two zeros weld.
    p.to_array().map(|x| (x + 0.0).to_bits())
}

fn triangle(m: &MeshDesc, t: [u32; 3]) -> [DVec3; 3] {
    t.map(|i| m.positions[i as usize].as_dvec3())
}

/// Asserts the mesh is closed, consistently and outward wound, convex and flat-shaded;
/// returns its size (largest bounding-box extent).
fn check_solid(label: &str, m: &MeshDesc) -> f64 {
    // Closed and consistent: after welding, each directed edge occurs once and its
    // reverse once (so every edge is shared by exactly two triangles, wound oppositely).
    let mut edges: HashMap<([u32; 3], [u32; 3]), u32> = HashMap::new();
    for t in &m.indices {
        let k = t.map(|i| key(m.positions[i as usize]));
        assert!(
            k[0] != k[1] && k[1] != k[2] && k[0] != k[2],
            "{label}: degenerate"
        );
        for j in 0..3 {
            *edges.entry((k[j], k[(j + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "{label}: directed edge used {n} times");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "{label}: open or flipped edge"
        );
    }
    let lo = m.positions.iter().fold(Vec3::MAX, |a, &p| a.min(p));
    let hi = m.positions.iter().fold(Vec3::MIN, |a, &p| a.max(p));
    let size = f64::from((hi - lo).max_element());
    let centroid =
        m.positions.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / m.positions.len() as f64;
    let mut volume = 0.0;
    for &t in &m.indices {
        let [a, b, c] = triangle(m, t);
        volume += a.dot(b.cross(c)) / 6.0;
        let n = (b - a).cross(c - a).normalize();
        // Outward: the face normal points away from the centroid (convex solid).
        assert!(
            n.dot((a + b + c) / 3.0 - centroid) > 0.0,
            "{label}: inward triangle"
        );
        // Convex: no vertex in front of any triangle's plane. 3e-6 of the size: f32
        // positions are rounded by ≤ 6e-8 relative, which tilts a plane through a
        // triangle ≥ 1/50 of the size by ≤ ~3e-6 rad, i.e. ≤ 3e-6 of the size at worst;
        // a real dent (a wrong step angle) is ≥ 1e-3 of the size.
        for p in &m.positions {
            let d = n.dot(p.as_dvec3() - a);
            assert!(d < 3e-6 * size, "{label}: not convex ({d:e} m)");
        }
        // Flat shaded: the stored normals are the face's (1e-4: the face normal from
        // f32 positions errs by ≤ ~3e-6 rad, see above).
        for i in t {
            let sn = m.normals[i as usize].as_dvec3();
            assert!((sn - n).length() < 1e-4, "{label}: normal {sn} vs face {n}");
        }
    }
    assert!(volume > 0.0, "{label}: signed volume {volume}");
    size
}

/// One outward unit normal per facet (from the largest triangle of each group of
/// triangles sharing a stored normal).
fn facet_normals(m: &MeshDesc) -> Vec<DVec3> {
    let mut best: HashMap<[u32; 3], (f64, DVec3)> = HashMap::new();
    for &t in &m.indices {
        let [a, b, c] = triangle(m, t);
        let cross = (b - a).cross(c - a);
        let e = best
            .entry(key(m.normals[t[0] as usize]))
            .or_insert((0.0, DVec3::ZERO));
        if cross.length() > e.0 {
            *e = (cross.length(), cross.normalize());
        }
    }
    best.into_values().map(|(_, n)| n).collect()
}

/// Angle of a facet to the girdle plane, degrees (0 for the table, 90 for the girdle).
fn tilt(n: DVec3) -> f64 {
    n.y.abs().acos().to_degrees()
}

/// Facets on the crown (`crown`) or pavilion whose tilt is within 0.1° of `angle`,
/// among those `keep` selects.
fn count_at(normals: &[DVec3], crown: bool, angle: f64, keep: impl Fn(DVec3) -> bool) -> usize {
    normals
        .iter()
        .filter(|n| (n.y > 0.0) == crown && n.y.abs() > 0.01 && keep(**n))
        .filter(|n| (tilt(**n) - angle).abs() < 0.1)
        .count()
}

fn bare(dir: &Path, cut: &str) -> SceneDesc {
    gem(
        dir,
        &format!("{cut}.glb"),
        &["--cut", cut, "--stone", "quartz", "--bare", "--size", "7"],
    )
}

#[test]
fn every_cut_is_closed_outward_convex_and_flat_shaded() {
    let dir = common::scratch_dir("gem_cuts_solids");
    for cut in ["round", "emerald", "oval", "pear"] {
        for size in ["0.5", "6.5", "30"] {
            let s = gem(
                &dir,
                "g.glb",
                &["--cut", cut, "--stone", "diamond", "--bare", "--size", size],
            );
            assert_eq!(s.meshes.len(), 1, "{cut}");
            let measured = check_solid(&format!("{cut} {size} mm"), &s.meshes[0]);
            let stated: f64 = size.parse::<f64>().unwrap_or(0.0) / 1000.0;
            // The size is the largest extent (diameter or length), f32 rounding only.
            assert!(
                (measured / stated - 1.0).abs() < 1e-6,
                "{cut}: {measured} vs {stated}"
            );
        }
        // The preview's stone is the same solid (translated).
        let p = gem(&dir, "p.glb", &["--cut", cut, "--stone", "ruby"]);
        check_solid(&format!("{cut} preview"), &p.meshes[0]);
    }
}

#[test]
fn round_brilliant_has_tolkowsky_proportions() {
    let dir = common::scratch_dir("gem_cuts_round");
    let s = bare(&dir, "round");
    let m = &s.meshes[0];
    let normals = facet_normals(m);
    assert_eq!(normals.len(), 73);
    // 8 bezels at the crown angle, 8 pavilion mains at the pavilion angle.
    assert_eq!(count_at(&normals, true, 34.5, |_| true), 8);
    assert_eq!(count_at(&normals, false, 40.75, |_| true), 8);
    // Table: 53 % of the diameter (corner to corner); girdle 2 % thick.
    let radius = |p: &Vec3| f64::from(p.x.hypot(p.z));
    let top = m.positions.iter().map(|p| p.y).fold(f32::MIN, f32::max);
    let table = m
        .positions
        .iter()
        .filter(|p| p.y == top)
        .map(radius)
        .fold(0.0, f64::max);
    let girdle = m.positions.iter().map(radius).fold(0.0, f64::max);
    // 1e-5: f32 rounding of mm coordinates (~1e-7 relative).
    assert!((table / girdle - 0.53).abs() < 1e-5, "{}", table / girdle);
    let band: Vec<f32> = m
        .positions
        .iter()
        .filter(|p| (radius(p) / girdle - 1.0).abs() < 1e-6)
        .map(|p| p.y)
        .collect();
    let thick =
        band.iter().fold(f32::MIN, |a, &b| a.max(b)) - band.iter().fold(f32::MAX, |a, &b| a.min(b));
    assert!(
        (f64::from(thick) / (2.0 * girdle) - 0.02).abs() < 1e-5,
        "{thick}"
    );
}

#[test]
fn emerald_cut_has_its_step_angles_and_shape() {
    let dir = common::scratch_dir("gem_cuts_emerald");
    let s = bare(&dir, "emerald");
    let m = &s.meshes[0];
    let normals = facet_normals(m);
    assert_eq!(normals.len(), 65);
    // Side and end facets (normal in the YZ or XY plane): each step angle on 2 sides and
    // 2 ends; all 12 crown and 16 pavilion side/end facets are accounted for.
    let side_or_end = |n: DVec3| n.x.abs() < 1e-5 || n.z.abs() < 1e-5;
    for a in [45.0, 37.0, 28.0] {
        assert_eq!(count_at(&normals, true, a, side_or_end), 4, "crown {a}°");
    }
    for a in [52.0, 45.0, 40.0, 36.0] {
        assert_eq!(
            count_at(&normals, false, a, side_or_end),
            4,
            "pavilion {a}°"
        );
    }
    let tilted = |crown: bool| {
        normals
            .iter()
            .filter(|n| {
                (n.y > 0.0) == crown && n.y.abs() > 0.01 && n.y.abs() < 0.9999 && side_or_end(**n)
            })
            .count()
    };
    assert_eq!((tilted(true), tilted(false)), (12, 16));
    // Length/width 1.5, table 62 % of the width (f32 rounding: 1e-5).
    let lo = m.positions.iter().fold(Vec3::MAX, |a, &p| a.min(p));
    let hi = m.positions.iter().fold(Vec3::MIN, |a, &p| a.max(p));
    let (length, width) = (f64::from(hi.x - lo.x), f64::from(hi.z - lo.z));
    assert!((length / width - 1.5).abs() < 1e-5, "{}", length / width);
    let table: Vec<&Vec3> = m.positions.iter().filter(|p| p.y == hi.y).collect();
    let tw = table.iter().map(|p| p.z).fold(f32::MIN, f32::max)
        - table.iter().map(|p| p.z).fold(f32::MAX, f32::min);
    assert!(
        (f64::from(tw) / width - 0.62).abs() < 1e-5,
        "{}",
        f64::from(tw) / width
    );
    // The pavilion ends in a keel along X of length length − width.
    let keel: Vec<&Vec3> = m.positions.iter().filter(|p| p.y == lo.y).collect();
    let kl = keel.iter().map(|p| p.x).fold(f32::MIN, f32::max)
        - keel.iter().map(|p| p.x).fold(f32::MAX, f32::min);
    assert!((f64::from(kl) - (length - width)).abs() < 1e-7, "{kl}");
}

#[test]
fn oval_is_the_brilliant_stretched_to_length_width_1_4() {
    let dir = common::scratch_dir("gem_cuts_oval");
    let s = bare(&dir, "oval");
    let m = &s.meshes[0];
    let normals = facet_normals(m);
    assert_eq!(normals.len(), 73);
    let lo = m.positions.iter().fold(Vec3::MAX, |a, &p| a.min(p));
    let hi = m.positions.iter().fold(Vec3::MIN, |a, &p| a.max(p));
    let ratio = f64::from(hi.x - lo.x) / f64::from(hi.z - lo.z);
    assert!((ratio - 1.4).abs() < 1e-5, "{ratio}");
    // On the minor axis (normal in the YZ plane) the Tolkowsky angles are kept…
    let minor = |n: DVec3| n.x.abs() < 1e-5;
    assert_eq!(count_at(&normals, true, 34.5, minor), 2);
    assert_eq!(count_at(&normals, false, 40.75, minor), 2);
    // …and on the major axis they are flattened to atan(tan α / 1.4).
    let major = |n: DVec3| n.z.abs() < 1e-5;
    let flat = |a: f64| (a.to_radians().tan() / 1.4).atan().to_degrees();
    assert_eq!(count_at(&normals, true, flat(34.5), major), 2);
    assert_eq!(count_at(&normals, false, flat(40.75), major), 2);
}

/// Interior angle of the polygon `ring` (in order round it) at vertex `i`, degrees.
fn corner_angle(ring: &[DVec3], i: usize) -> f64 {
    let n = ring.len();
    let (a, b) = (ring[(i + n - 1) % n] - ring[i], ring[(i + 1) % n] - ring[i]);
    a.angle_between(b).to_degrees()
}

#[test]
fn pear_has_a_point_a_round_end_and_stated_angles() {
    let dir = common::scratch_dir("gem_cuts_pear");
    let s = bare(&dir, "pear");
    let m = &s.meshes[0];
    let normals = facet_normals(m);
    assert_eq!(normals.len(), 73);
    let lo = m.positions.iter().fold(Vec3::MAX, |a, &p| a.min(p));
    let hi = m.positions.iter().fold(Vec3::MIN, |a, &p| a.max(p));
    let (length, width) = (f64::from(hi.x - lo.x), f64::from(hi.z - lo.z));
    // L/W 1.6 (f32 rounding: 1e-5).
    assert!((length / width - 1.6).abs() < 1e-5, "{}", length / width);
    // The girdle's top ring (y = +1 % of the width), in order round the Y axis.
    let y_g = 0.01 * width;
    let mut ring: Vec<DVec3> = m
        .positions
        .iter()
        .map(|p| p.as_dvec3())
        .filter(|p| (p.y - y_g).abs() < 1e-9)
        .collect();
    ring.sort_by(|a, b| a.z.atan2(a.x).total_cmp(&b.z.atan2(b.x)));
    ring.dedup();
    assert_eq!(ring.len(), 16);
    let tip = (0..16).max_by(|&i, &j| ring[i].x.total_cmp(&ring[j].x));
    let end = (0..16).min_by(|&i, &j| ring[i].x.total_cmp(&ring[j].x));
    let (tip, end) = (tip.unwrap_or(0), end.unwrap_or(0));
    // One point, on the long axis at +X: the round end's outline is a half circle of
    // radius W/2 centred at x₀ = −L/2 + W/2, each wing an arc of radius
    // ρ = (a² + R²)/(2R) (a = L − R) tangent to it at the widest point and through the
    // point; the ring's corner at the point is 180° − (φ_w + φ₁), φ_w = atan((ρ − R)/a)
    // the wing's normal at the point and φ₁ = φ_w + (90° − φ_w)/4 at the next vertex.
    let (r, a) = (0.5 * width, length - 0.5 * width);
    let rho = (a * a + r * r) / (2.0 * r);
    let phi_w = ((rho - r) / a).atan().to_degrees();
    let point = 180.0 - (2.0 * phi_w + (90.0 - phi_w) / 4.0);
    assert!(ring[tip].z.abs() < 1e-9 && (ring[tip].x - 0.5 * length).abs() < 1e-8);
    // 0.1°: the tolerance (f32 rounding of the corners: ~1e-5°).
    assert!(
        (corner_angle(&ring, tip) - point).abs() < 0.1,
        "point {} vs {point}",
        corner_angle(&ring, tip)
    );
    assert!(point < 90.0, "{point}");
    // The round end: a regular 16-gon's corner, 157.5°.
    assert!(ring[end].z.abs() < 1e-9 && (ring[end].x + 0.5 * length).abs() < 1e-8);
    assert!((corner_angle(&ring, end) - 157.5).abs() < 0.1);
    // Crown and pavilion: the five bezels and mains of the round end keep Tolkowsky's
    // 34.5° and 40.75°; the point's (normal in the XY plane, towards +X) are flattened to
    // atan(R tan α / a) (the apex and culet lie over the round end's centre).
    assert_eq!(count_at(&normals, true, 34.5, |_| true), 5);
    assert_eq!(count_at(&normals, false, 40.75, |_| true), 5);
    let at_point = |n: DVec3| n.z.abs() < 1e-5 && n.x > 0.0;
    let flat = |alpha: f64| (r * alpha.to_radians().tan() / a).atan().to_degrees();
    assert_eq!(count_at(&normals, true, flat(34.5), at_point), 1);
    assert_eq!(count_at(&normals, false, flat(40.75), at_point), 1);
    // Table: 53 % of the width and of the length (f32 rounding: 1e-5).
    let table: Vec<&Vec3> = m.positions.iter().filter(|p| p.y == hi.y).collect();
    let extent = |f: fn(&Vec3) -> f32| {
        let (a, b) = table
            .iter()
            .map(|p| f(p))
            .fold((f32::MAX, f32::MIN), |(a, b), v| (a.min(v), b.max(v)));
        f64::from(b - a)
    };
    assert!((extent(|p| p.z) / width - 0.53).abs() < 1e-5);
    assert!((extent(|p| p.x) / length - 0.53).abs() < 1e-5);
    // The culet: one vertex, under the round end's centre; total depth
    // 0.02 + 0.47·tan 34.5°/2 + tan 40.75°/2 = 61.21 % of the width.
    let culet: Vec<&Vec3> = m.positions.iter().filter(|p| p.y == lo.y).collect();
    let x0 = f64::from(lo.x) + r;
    assert!(culet
        .iter()
        .all(|p| (f64::from(p.x) - x0).abs() < 1e-8 && p.z.abs() < 1e-8));
    let depth = f64::from(hi.y - lo.y) / width;
    let stated = 0.02 + 0.235 * 34.5f64.to_radians().tan() + 0.5 * 40.75f64.to_radians().tan();
    assert!((depth - stated).abs() < 1e-5, "{depth} vs {stated}");
}

/// Stated values: (name, n_d, Abbe number, coloured).
const STONES: [(&str, f32, f32, bool); 6] = [
    ("diamond", 2.417, 55.0, false),
    ("sapphire", 1.770, 72.0, true),
    ("ruby", 1.770, 72.0, true),
    ("cubic-zirconia", 2.16, 28.0, false),
    ("quartz", 1.544, 70.0, false),
    ("crown-glass", 1.5168, 64.17, false),
];

fn stone_material(s: &SceneDesc) -> &MaterialDesc {
    let i = s.meshes[0].material.expect("material");
    &s.materials[i]
}

#[test]
fn gem_files_carry_the_stones_optics() {
    let dir = common::scratch_dir("gem_cuts_stones");
    for (name, n_d, abbe, coloured) in STONES {
        let s = gem(
            &dir,
            &format!("{name}.glb"),
            &["--cut", "round", "--stone", name, "--bare"],
        );
        let m = stone_material(&s);
        assert_eq!(m.ior, n_d, "{name}");
        // The file stores 20/V as the shortest decimal of the f32: exact to 1 ulp.
        assert!(
            (m.dispersion - 20.0 / abbe).abs() < 1e-6,
            "{name}: {}",
            m.dispersion
        );
        assert_eq!(
            (m.transmission, m.roughness, m.metallic),
            (1.0, 0.0, 0.0),
            "{name}"
        );
        assert!(m.thickness > 0.0, "{name}: thin-walled");
        if coloured {
            assert_eq!(m.attenuation_distance, 0.004, "{name}");
            let c = m.attenuation_color;
            let dominant = if name == "ruby" { c.x } else { c.z };
            assert!(dominant > 3.0 * c.y, "{name}: {c}");
        } else {
            assert!(m.attenuation_distance.is_infinite(), "{name}");
        }
        assert!(s.cameras.is_empty() && s.lights.is_empty() && s.environment.is_none());
    }
    // The preview adds a camera, a white floor, emissive panels and a faint environment.
    let p = gem(
        &dir,
        "preview.glb",
        &["--cut", "oval", "--stone", "sapphire"],
    );
    assert_eq!(p.cameras.len(), 1);
    assert!(p.environment.is_some());
    assert_eq!(stone_material(&p).ior, 1.77);
    let emitters = p
        .materials
        .iter()
        .filter(|m| m.emissive.max_element() > 0.0)
        .count();
    assert_eq!(emitters, 2);
    assert!(p
        .materials
        .iter()
        .any(|m| m.name.contains("Floor") && m.base_color.x > 0.8));
}

#[test]
fn bad_arguments_fail_and_write_nothing() {
    let dir = common::scratch_dir("gem_cuts_errors");
    let cases: [(&[&str], &str); 7] = [
        (
            &["--cut", "pear-ish", "--stone", "diamond"],
            "round, emerald, oval, pear",
        ),
        (&["--cut", "round", "--stone", "glass"], "crown-glass"),
        (
            &["--cut", "round", "--stone", "ruby", "--size", "0"],
            "--size",
        ),
        (
            &["--cut", "round", "--stone", "ruby", "--size", "-2"],
            "--size",
        ),
        (
            &["--cut", "round", "--stone", "ruby", "--size", "nan"],
            "--size",
        ),
        (
            &["--cut", "round", "--stone", "ruby", "--size", "5000"],
            "--size",
        ),
        (
            &["--cut", "round", "--stone", "ruby", "--size", "big"],
            "--size",
        ),
    ];
    for (args, hint) in cases {
        let mut all = vec!["gem"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["-o", "out.glb"]);
        let o = common::iris(&all, &dir);
        let err = common::stderr(&o);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(err.contains(hint), "{args:?}: {err}");
    }
    let o = common::iris(
        &["gem", "--cut", "round", "--stone", "ruby", "-o", "out.png"],
        &dir,
    );
    assert!(!o.status.success());
    assert!(
        common::stderr(&o).contains(".glb"),
        "{}",
        common::stderr(&o)
    );
    let o = common::iris(
        &[
            "gem",
            "--cut",
            "oval",
            "--stone",
            "ruby",
            "-o",
            "missing/out.glb",
        ],
        &dir,
    );
    assert!(!o.status.success());
    assert!(
        common::stderr(&o).contains("missing"),
        "{}",
        common::stderr(&o)
    );
    // Nothing written, no temporary left.
    assert!(
        common::entries(&dir).is_empty(),
        "{:?}",
        common::entries(&dir)
    );
}

fn gems_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/gems")
}

#[test]
fn committed_gems_match_regeneration() {
    let scratch = common::scratch_dir("gem_cuts_regen");
    let written = write_gem_assets(&scratch).expect("generate");
    assert_eq!(written.len(), GEM_ASSETS.len());
    for path in &written {
        let name = path.file_name().expect("name");
        let committed = std::fs::read(gems_dir().join(name)).unwrap_or_else(|e| {
            panic!("assets/gems/{name:?}: {e} (regenerate: iris gen-assets assets)")
        });
        let fresh = std::fs::read(path).expect("read");
        assert!(
            fresh == committed,
            "assets/gems/{name:?} differs from a regeneration"
        );
        // Small: a few tens of KB.
        assert!(
            committed.len() < 40_000,
            "{name:?}: {} bytes",
            committed.len()
        );
    }
}

#[test]
fn committed_gems_render_finite_and_not_black() {
    let dir = common::scratch_dir("gem_cuts_render");
    for (name, ..) in GEM_ASSETS {
        let scene = gems_dir().join(name);
        let out = dir.join(format!("{name}.exr"));
        let o = common::iris(
            &[
                "render",
                &scene.to_string_lossy(),
                "-o",
                &out.to_string_lossy(),
                "--size",
                "48x36",
                "--spp",
                "4",
                "--method",
                "path",
                "--quiet",
            ],
            &dir,
        );
        assert!(o.status.success(), "{name}: {}", common::stderr(&o));
        let img = iris::output::exr_io::decode(&out).expect("read exr");
        assert!(
            img.data.iter().all(|p| p.is_finite()),
            "{name}: non-finite pixel"
        );
        let mean = img.data.iter().map(|p| p.element_sum()).sum::<f32>() / img.data.len() as f32;
        // The lit white floor fills most of the frame: far from black (> 1e-3).
        let lit = img.data.iter().filter(|p| p.max_element() > 0.0).count();
        assert!(
            mean > 1e-3 && lit * 2 > img.data.len(),
            "{name}: mean {mean}, lit {lit}"
        );
    }
}
