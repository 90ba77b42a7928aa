//! The birefringence scenes (polarized transport, `extras.iris_crystal`), generated and
//! shipped (CC0) in `assets/scenes/`. Units are metres, +Y up, linear RGB; the optic axes
//! are given in world space (every mesh here is only translated).
//!
//! | file | objects | materials | light | camera |
//! |---|---|---|---|---|
//! | `calcite_rhomb.glb` | a calcite cleavage rhombohedron ([`CALCITE`]: edges 30 mm, 28.3 mm high, turned −69° about +Y) lying on a cleavage face 0.3 mm above a white card (90 × 64 mm) printed with "CALCITE" (0.8 mm strokes, letters 4 × 5.6 mm), a row of seven 2 mm dots 6 mm apart and a 40 × 0.6 mm rule; its top face, which lies back-right of its bottom face, over the right half of the print; the card on a grey table | calcite (`{"stone": "calcite", "optic_axis": …}`: the rhomb's blunt-vertex diagonal, 44.6° from the vertical, its horizontal part towards −X, +Z at 120° from +X; the print's extraordinary image lies h·tan ρ = 28.3 mm × tan 6.24° = 3.1 mm from its ordinary one the other way, towards +X, −Z: up and a little right in the picture, as calcite's extraordinary ray leans away from the axis); card 0.85, ink 0.03, table 0.3 | a 24 × 24 cm panel of radiance 6, 50 cm away, 65° up, front-left; scene extras `iris_environment: 0.5` | eye 18° from the vertical, 28 cm from (6, 12, −2) mm, yfov 12°, 16:9 |
//! | `moissanite_and_diamond.glb` | two 6.5 mm round brilliants ([`Cut::Round`], Tolkowsky proportions), table up, side by side along X (centres 8.8 mm apart, the diamond at −X), in the `iris gem` preview's setting ([`add_setting`]: white floor, key and rim panels, faint environment) | moissanite (`{"stone": "moissanite", "optic_axis": [1, 0, 0]}`: the optic axis in the girdle plane, along the line through both stones, ⊥ the camera's plane of view, so light entering the table from the camera splits into n_o = 2.647 (D in the plane of view) and n_e = 2.689 (D ∥ X) without walk-off); diamond (isotropic, n_d 2.417) | the preview's | 40° from the table normal (50° up) from +Z, yfov 25°, 16:9 |
//! | `pleochroic_tourmaline.glb` | two green tourmaline bars (20 × 5 × 5 mm, along X) side by side 0.2 mm above a light table (54 × 40 mm) on a dark table | tourmaline: the far bar (−Z) with its optic axis c vertical (along the view: both modes ordinary, E ⊥ c, dark green), the near bar with c along its length (X, across the view: half the light E ⊥ c, half E ∥ c, the E ∥ c half light yellowish green) | the light table (radiance 1) below the bars; scene extras `iris_environment: 0.08` | eye 25° from the vertical, 6 cm from the bars, yfov 30°, 16:9 |
//!
//! The rhomb is the real cleavage form: three edges of equal length meet at each of its two
//! blunt vertices at 101.9° to each other (the rhombus faces' obtuse angle; their acute
//! angle 78.1°), so the faces meet at 105.1° and 74.9°; the three-fold axis through the
//! blunt vertices is the optic axis c, 44.6° from every face normal (E. S. Dana, *A
//! Textbook of Mineralogy*; calcite's cleavage {10-14}).
//!
//! With a polarizer (`iris render FILE --polarizer DEG`, 0° = the image's horizontal):
//! the rhomb keeps one image of the print (the ordinary one, its D ⊥ the principal plane,
//! or the extraordinary one at 90° to it); `pleochroic_tourmaline.glb --polarizer 0`
//! (along the near bar's c) shows that bar in its E ∥ c colour, light yellowish green,
//! `--polarizer 90` in its E ⊥ c colour, the far bar's. The moissanite's doubling (0.3 %
//! of the depth seen through the table, tests/gems/moissanite_doubling.rs) is under a pixel at
//! the gallery's size.

use super::parts::{add_mesh, add_panel, camera};
use crate::authoring::cuts::preview::{add_setting, direction, preview_camera};
use crate::authoring::cuts::{polyhedron, Cut};
use crate::authoring::gem::newell;
use crate::authoring::lathe::sin_cos;
use crate::authoring::scene::placed;
use crate::authoring::shapes::{cuboid, ground_plane, push_flat_facing_away, TriMesh};
use crate::authoring::stones::Stone;
use crate::material::MaterialDesc;
use crate::scene::desc::{EnvironmentDesc, SceneDesc};
use glam::{DVec3, Mat3, Quat, Vec3};

/// A rhombohedron with edges of equal length meeting at its two blunt vertices at
/// `blunt_angle` degrees to each other, one face down (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rhomb {
    /// Edge length, metres.
    pub edge: f64,
    /// Angle between the edges at a blunt vertex (the faces' obtuse angle), degrees, in
    /// (90°, 120°).
    pub blunt_angle: f64,
    /// Turn about +Y, degrees (from +Z towards +X), of the rhomb on its face.
    pub azimuth: f64,
}

/// Calcite's cleavage rhombohedron: the faces' obtuse angle, degrees (101°55′).
pub const CALCITE_BLUNT_ANGLE: f64 = 101.9;

impl Rhomb {
    /// The three edges from the lower blunt vertex (at the origin): e₁, e₂ along the
    /// bottom face (y = 0), e₃ rising. With ψ = [`Rhomb::azimuth`] = 0, e₁ = L·X̂,
    /// e₂ = L(cos β, 0, sin β) and e₃ = L(cos β, h, z) with e₃·e₂ = L² cos β, which gives
    /// z = cos β (1 − cos β)/sin β and h = √(1 − cos²β − z²); β the blunt angle.
    pub fn edges(&self) -> [DVec3; 3] {
        let (s, c) = sin_cos(self.blunt_angle.to_radians());
        let z = c * (1.0 - c) / s;
        let h = (1.0 - c * c - z * z).sqrt();
        let (sa, ca) = sin_cos(self.azimuth.to_radians());
        // Rotation about +Y by ψ: (x, z) ↦ (x cos ψ + z sin ψ, −x sin ψ + z cos ψ).
        let turn = |v: DVec3| DVec3::new(v.x * ca + v.z * sa, v.y, -v.x * sa + v.z * ca);
        [DVec3::X, DVec3::new(c, 0.0, s), DVec3::new(c, h, z)].map(|v| turn(v) * self.edge)
    }

    /// The six rhombus faces (corners in order round each), lower blunt vertex at the
    /// origin.
    pub fn faces(&self) -> Vec<Vec<DVec3>> {
        let e = self.edges();
        let top = e[0] + e[1] + e[2];
        let mut faces = Vec::with_capacity(6);
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            faces.push(vec![DVec3::ZERO, e[a], e[a] + e[b], e[b]]);
            faces.push(vec![top, top - e[a], top - e[a] - e[b], top - e[b]]);
        }
        faces
    }

    /// The closed, flat-shaded, outward-wound mesh ([`polyhedron`]).
    pub fn mesh(&self) -> TriMesh {
        polyhedron(self.faces())
    }

    /// The unit optic axis: the diagonal through the blunt vertices, (e₁ + e₂ + e₃)/|…|,
    /// pointing up.
    pub fn optic_axis(&self) -> DVec3 {
        let e = self.edges();
        (e[0] + e[1] + e[2]).normalize()
    }

    /// Height of the top face above the bottom one, metres.
    pub fn height(&self) -> f64 {
        self.edges()[2].y
    }
}

/// A unit vector as JSON, each component rounded to 6 decimals (the loader normalizes).
fn axis_json(v: DVec3) -> serde_json::Value {
    let r = |x: f64| (x * 1e6).round() / 1e6;
    serde_json::json!([r(v.x), r(v.y), r(v.z)])
}

/// A crystal stone's material with its optic axis along `axis` (world space).
fn crystal_material(stone: Stone, title: &str, thickness: f32, axis: DVec3) -> MaterialDesc {
    let mut m = stone.material(thickness);
    m.name = title.into();
    let crystal = serde_json::json!({"stone": stone.name(), "optic_axis": axis_json(axis)});
    // The typed crystal is the loader's reading of the key written.
    m.crystal = crate::load::gltf::crystal::crystal(&crystal).ok();
    m.extras = Some(serde_json::json!({ "iris_crystal": crystal }));
    m
}

/// 5 × 7 bitmaps of the letters [`print`] knows ('#' ink), top row first.
fn glyph(ch: char) -> [&'static str; 7] {
    match ch {
        'A' => [
            ".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#",
        ],
        'C' => [
            ".###.", "#...#", "#....", "#....", "#....", "#...#", ".###.",
        ],
        'E' => [
            "#####", "#....", "#....", "####.", "#....", "#....", "#####",
        ],
        'I' => [
            ".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.",
        ],
        'L' => [
            "#....", "#....", "#....", "#....", "#....", "#....", "#####",
        ],
        'T' => [
            "#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#..",
        ],
        _ => ["....."; 7],
    }
}

/// Pushes the flat horizontal polygon `pts` (corners in order), facing +Y.
fn push_up(mesh: &mut TriMesh, pts: Vec<DVec3>) {
    let n = newell(&pts);
    let below = pts[0] - DVec3::Y;
    push_flat_facing_away(mesh, pts, n, below);
}

/// Pushes the quad [x0, x1] × [z0, z1] at height `y`, facing +Y.
fn push_patch(mesh: &mut TriMesh, (x0, x1): (f64, f64), (z0, z1): (f64, f64), y: f64) {
    let corners = [(x0, z0), (x1, z0), (x1, z1), (x0, z1)];
    push_up(mesh, corners.map(|(x, z)| DVec3::new(x, y, z)).to_vec());
}

/// `text` in the 5 × 7 font with square pixels of side `px` at height `y`, its top-left
/// corner at (`x`, `z`), reading along +X with rows along +Z (each run of ink in a row one
/// quad; one pixel between letters).
fn print(mesh: &mut TriMesh, text: &str, (x, z): (f64, f64), px: f64, y: f64) {
    for (i, ch) in text.chars().enumerate() {
        let left = x + 6.0 * px * i as f64;
        for (row, bits) in glyph(ch).iter().enumerate() {
            let z0 = z + px * row as f64;
            let mut start = None;
            for (col, b) in bits.bytes().chain([b'.']).enumerate() {
                match (b == b'#', start) {
                    (true, None) => start = Some(col),
                    (false, Some(s)) => {
                        let xs = (left + px * s as f64, left + px * col as f64);
                        push_patch(mesh, xs, (z0, z0 + px), y);
                        start = None;
                    }
                    _ => {}
                }
            }
        }
    }
}

/// A disc of `radius` centred at `c` (y = its height), a 24-gon facing +Y.
fn dot(mesh: &mut TriMesh, c: DVec3, radius: f64) {
    let pts: Vec<DVec3> = (0..24)
        .map(|k| {
            let (s, co) = sin_cos(f64::from(k) * std::f64::consts::PI / 12.0);
            c + DVec3::new(radius * co, 0.0, radius * s)
        })
        .collect();
    push_up(mesh, pts);
}

/// The rhomb of `calcite_rhomb.glb`.
pub const CALCITE: Rhomb = Rhomb {
    edge: 0.03,
    blunt_angle: CALCITE_BLUNT_ANGLE,
    azimuth: -69.0,
};

/// A calcite rhomb on a printed card: the print seen through it doubled (module docs).
pub fn calcite_rhomb() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Calcite rhomb on a printed card (double refraction)".into(),
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.5))),
        ..SceneDesc::default()
    };
    let (card_y, ink_y, lift) = (0.0003, 0.00035, 0.0006);
    let table = MaterialDesc::diffuse("Table", Vec3::splat(0.3));
    add_mesh(&mut s, "Table", ground_plane(0.3, 0.3), table, None);
    let card = ground_plane(0.045, 0.032);
    let white = MaterialDesc::diffuse("Card", Vec3::splat(0.85));
    add_mesh(
        &mut s,
        "Card",
        card,
        white,
        Some(Vec3::new(0.0, card_y, 0.0)),
    );
    let mut ink = TriMesh::default();
    let px = 0.0008;
    print(&mut ink, "CALCITE", (-20.5 * px, -0.0088), px, ink_y);
    for k in -3..=3 {
        let at = DVec3::new(f64::from(k) * 0.006, ink_y, 0.001);
        dot(&mut ink, at, 0.001);
    }
    push_patch(&mut ink, (-0.02, 0.02), (0.0057, 0.0063), ink_y);
    let black = MaterialDesc::diffuse("Ink", Vec3::splat(0.03));
    add_mesh(&mut s, "Ink", ink, black, None);
    let rhomb = CALCITE;
    let e = rhomb.edges();
    // The bottom face's centre at (15.8, 6.7) mm: the right half of the print is seen
    // through the top face, which lies back-left of it.
    let base = DVec3::new(0.008, lift, 0.0075) - 0.5 * (e[0] + e[1]);
    let m = crystal_material(
        Stone::Calcite,
        "Calcite (Iceland spar)",
        rhomb.height() as f32,
        rhomb.optic_axis(),
    );
    add_mesh(
        &mut s,
        "Calcite rhomb",
        rhomb.mesh(),
        m,
        Some(base.as_vec3()),
    );
    let key = direction(65.0, -40.0);
    add_panel(
        &mut s,
        "Key light",
        6.0,
        (0.12, 0.12),
        key_rotation(key),
        (0.5 * key).as_vec3(),
    );
    let target = Vec3::new(0.006, 0.012, -0.002);
    let eye = target + (0.28 * direction(72.0, 0.0)).as_vec3();
    s.cameras.push(camera(eye, target, 12.0, 16.0 / 9.0));
    s
}

/// The rotation turning +Y into −`dir` (a panel at `dir` facing the origin).
fn key_rotation(dir: DVec3) -> Mat3 {
    Mat3::from_quat(Quat::from_rotation_arc(
        Vec3::Y,
        (-dir).normalize().as_vec3(),
    ))
}

/// Size of the two brilliants of `moissanite_and_diamond.glb`, metres.
pub const BRILLIANT_SIZE: f64 = 0.0065;

/// A moissanite beside a diamond, both 6.5 mm round brilliants, in the preview's setting
/// (module docs).
pub fn moissanite_and_diamond() -> SceneDesc {
    let size = BRILLIANT_SIZE;
    let stone = Cut::Round.mesh(size);
    let (lo, hi) = stone.positions.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())),
    );
    let depth = (hi.y - lo.y) as f32;
    let mut s = SceneDesc {
        name: "Round brilliants: moissanite and diamond, 6.5 mm".into(),
        ..SceneDesc::default()
    };
    let lift = 0.02 * size - lo.y;
    let half_gap = 0.68 * size;
    let moissanite = crystal_material(
        Stone::Moissanite,
        &Stone::Moissanite.title(),
        depth,
        DVec3::X,
    );
    for (name, m, x) in [
        ("Round brilliant moissanite", moissanite, half_gap),
        (
            "Round brilliant diamond",
            Stone::Diamond.material(depth),
            -half_gap,
        ),
    ] {
        s.materials.push(m);
        let at = DVec3::new(x, lift, 0.0).as_vec3();
        let material = s.materials.len() - 1;
        s.meshes
            .push(placed(name, stone.clone(), material, Some(at)));
    }
    let centre = DVec3::new(0.0, lift + 0.5 * (lo.y + hi.y), 0.0);
    add_setting(&mut s, centre, size);
    s.cameras
        .push(preview_camera(centre, 0.75 * size, (50.0, 0.0), 16.0 / 9.0));
    s
}

/// Two tourmaline bars on a light table, one with its optic axis along the view and one
/// across it (module docs).
pub fn pleochroic_tourmaline() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Tourmaline bars on a light table (pleochroism)".into(),
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.08))),
        ..SceneDesc::default()
    };
    let table = MaterialDesc::diffuse("Table", Vec3::splat(0.05));
    add_mesh(&mut s, "Table", ground_plane(0.2, 0.2), table, None);
    let light = MaterialDesc::emitter("Light table", Vec3::ONE);
    let panel = ground_plane(0.027, 0.02);
    add_mesh(
        &mut s,
        "Light table",
        panel,
        light,
        Some(Vec3::new(0.0, 0.0005, 0.0)),
    );
    let half = Vec3::new(0.01, 0.0025, 0.0025);
    let y = 0.0005 + 0.0002 + f64::from(half.y);
    for (name, axis, z) in [
        ("Tourmaline, c along the view", DVec3::Y, -0.004),
        ("Tourmaline, c along the bar", DVec3::X, 0.004),
    ] {
        let m = crystal_material(Stone::Tourmaline, name, 2.0 * half.y, axis);
        let at = DVec3::new(0.0, y, z).as_vec3();
        add_mesh(&mut s, name, cuboid(half), m, Some(at));
    }
    let target = Vec3::new(0.0, 0.002, 0.0);
    let eye = target + (0.06 * direction(65.0, 0.0)).as_vec3();
    s.cameras.push(camera(eye, target, 30.0, 16.0 / 9.0));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angle_deg(a: DVec3, b: DVec3) -> f64 {
        a.normalize()
            .dot(b.normalize())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    #[test]
    fn the_rhomb_has_calcite_cleavage_angles_and_its_optic_axis() {
        for azimuth in [0.0, 37.0] {
            let r = Rhomb { azimuth, ..CALCITE };
            let e = r.edges();
            for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                assert!((e[a].length() - 0.03).abs() < 1e-12);
                // At the blunt vertex every face angle is 101.9°.
                assert!((angle_deg(e[a], e[b]) - 101.9).abs() < 1e-9);
            }
            // Across a face the other angle is 78.1°.
            assert!((angle_deg(-e[0], e[1]) - 78.1).abs() < 1e-9);
            // Faces meet at 105.1° along the blunt corners' edges (105°05′ = 105.08° for
            // 101°55′ faces; 105.06° for 101.9°), 74.9° along the others.
            let n = |a: usize, b: usize| e[a].cross(e[b]);
            let dihedral = 180.0 - angle_deg(n(0, 1), n(1, 2));
            assert!((dihedral - 105.08).abs() < 0.04, "{dihedral}");
            // The optic axis is 44.6° from every face normal, 45.4° from the faces.
            let c = r.optic_axis();
            for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                let t = angle_deg(c, n(a, b));
                let t = t.min(180.0 - t);
                assert!((t - 44.6).abs() < 0.05, "{t}");
            }
            assert!(e[0].y == 0.0 && e[1].y == 0.0 && r.height() > 0.0);
        }
    }

    #[test]
    fn the_rhomb_is_closed_and_outward() {
        let m = CALCITE.mesh();
        assert_eq!(m.indices.len(), 12);
        let key = |i: u32| m.positions[i as usize].to_array().map(f32::to_bits);
        let mut edges = std::collections::HashMap::new();
        for t in &m.indices {
            for k in 0..3 {
                let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&c| c == 2), "not watertight");
        let centre = 0.5 * CALCITE.edges().iter().sum::<DVec3>();
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            let n = (b - a).cross(c - a);
            assert!(
                n.dot((a + b + c) / 3.0 - centre) > 0.0,
                "face points inwards"
            );
        }
    }

    #[test]
    fn scenes_encode_deterministically_and_small() {
        for build in [calcite_rhomb, moissanite_and_diamond, pleochroic_tourmaline] {
            let a = crate::authoring::glb::encode_glb(&build()).expect("encode");
            let b = crate::authoring::glb::encode_glb(&build()).expect("encode");
            assert_eq!(a, b);
            assert!(a.len() < 100_000, "{} bytes", a.len());
        }
    }
}
