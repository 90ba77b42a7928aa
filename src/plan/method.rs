//! `--method auto`: which method renders a scene, decided from fixed-seed photon probes of
//! the scene ([`crate::photon::probe`], [`caustic::probe_share`]) and the camera's
//! projection, with a reason naming the evidence. The probes' seeds are fixed, so the plan
//! printed before a render and the render always agree.

use crate::integrator::{caustic, Method};
use crate::photon::emit::PhotonEmitter;
use crate::photon::probe::{has_caustic_paths, kept_share};
use crate::scene::desc::Projection;
use crate::scene::Scene;

/// Resolves [`Method::Auto`] for `scene` seen through a camera of `projection` among the
/// path tracer, bidirectional path tracing, the hybrid, vertex connection and merging and
/// SPPM. Returns the method and the reason. Two numbers decide besides the materials:
/// - the **kept share** k ([`kept_share`]): of the light the lights bring to their first
///   non-delta hits, the part a diffuse bounce brings to a second one. An enclosed room
///   keeps about its albedo (the McGuire Cornell boxes: 0.57–0.59); every open scene
///   measured keeps at most 0.24 (TransmissionRoughnessTest; the studio-lit stones 0.002).
///   Where k ≥ [`AUTO_ENCLOSED_FROM`], most light reaching the camera has bounced, and
///   light subpaths find it more cheaply than camera paths do.
/// - the **caustic share** s ([`caustic::probe_share`]): of the light at first non-delta
///   hits, the part that came through delta bounces (L S+ D).
///
/// The rule:
/// 1. no light reaches a diffuse-like surface through specular ones ([`has_caustic_paths`])
///    → **BPT** if enclosed, else **path**;
/// 2. a transmissive material is rough ([`rough_glass`]): light focused through rough glass
///    (L G+ D) is neither the path tracer's strength (a point light is reached only by
///    next-event estimation at the last rough interface: fireflies) nor the hybrid's
///    caustic map's (delta chains only) → **VCM**, whose light subpaths carry every chain;
/// 3. s < [`AUTO_HYBRID_BELOW`] → **VCM** if enclosed, else the **hybrid** (the path tracer
///    for everything it reaches, the caustic map only for the L S+ D paths);
/// 4. otherwise (the caustics are the picture: a stone under a narrow spot, a point-light
///    caustic seen directly, a floor seen through water) → **VCM**.
///
/// VCM and BPT need a pinhole (light subpaths connect to the camera): under an orthographic
/// camera rules 2 and 4 pick **SPPM** and rules 1 and 3 the path tracer and the hybrid.
///
/// The evidence for each rule (relative RMSE between two seeds at equal time, per scene,
/// `scripts/auto-evidence.sh`) is in BENCHMARKS.md, "Choosing VCM and BPT"; VCM against
/// SPPM on the caustic sphere and the Cornell water box in "Vertex connection and merging";
/// the hybrid against SPPM, whence the 4 % of rule 3, in "Converging faster".
pub fn resolve_method(
    method: Method,
    scene: &Scene,
    projection: &Projection,
) -> (Method, Option<String>) {
    if method != Method::Auto {
        return (method, None);
    }
    let (m, why) = choose(scene, matches!(projection, Projection::Perspective { .. }));
    (m, Some(format!("--method auto: {why}")))
}

/// The rule of [`resolve_method`] for a pinhole camera or not.
fn choose(scene: &Scene, pinhole: bool) -> (Method, String) {
    if scene.has_media() {
        return media_method(scene);
    }
    let emitter = PhotonEmitter::new(scene);
    if emitter.is_empty() {
        return (
            Method::Path,
            "no light to trace photons from: path tracer".into(),
        );
    }
    let orthographic = "VCM and BPT need a perspective camera; this one is orthographic";
    if !has_caustic_paths(scene, &emitter, CAUSTIC_PROBE_PHOTONS) {
        let (enclosed, room) = enclosure(scene, &emitter);
        let (m, how) = match (enclosed, pinhole) {
            (true, true) => (Method::Bpt, "bidirectional path tracing (BPT)".to_string()),
            (true, false) => (Method::Path, format!("path tracer ({orthographic})")),
            (false, _) => (Method::Path, "path tracer".to_string()),
        };
        return (m, format!("no caustic paths found; {room}: {how}"));
    }
    let (bidirectional, named) = if pinhole {
        (Method::Vcm, "VCM".to_string())
    } else {
        (Method::Sppm, format!("SPPM ({orthographic})"))
    };
    if let Some(name) = rough_glass(scene) {
        return (
            bidirectional,
            format!(
                "rough transmissive material {name} focuses light the path tracer reaches only \
                 by chance and the hybrid's caustic map does not carry: {named}"
            ),
        );
    }
    let share = caustic::probe_share(scene, CAUSTIC_PROBE_PHOTONS);
    let carry = format!(
        "caustics carry {:.2} % of the light reaching diffuse surfaces",
        100.0 * share
    );
    let below = 100.0 * AUTO_HYBRID_BELOW;
    if share >= AUTO_HYBRID_BELOW {
        return (
            bidirectional,
            format!("{carry} (the hybrid is chosen under {below:.0} %): {named}"),
        );
    }
    let (enclosed, room) = enclosure(scene, &emitter);
    let (m, how) = if enclosed && pinhole {
        (Method::Vcm, "VCM")
    } else {
        (Method::Hybrid, "path tracer + caustic map (hybrid)")
    };
    (m, format!("{carry} (under {below:.0} %); {room}: {how}"))
}

/// Whether the scene counts as enclosed ([`kept_share`] ≥ [`AUTO_ENCLOSED_FROM`]), with
/// the reason's words.
fn enclosure(scene: &Scene, emitter: &PhotonEmitter) -> (bool, String) {
    let kept = kept_share(scene, emitter, CAUSTIC_PROBE_PHOTONS);
    let enclosed = kept >= AUTO_ENCLOSED_FROM;
    let room = format!(
        "a diffuse bounce keeps {:.1} % of the light in the scene ({} from {:.0} %)",
        100.0 * kept,
        if enclosed {
            "enclosed"
        } else {
            "open; enclosed"
        },
        100.0 * AUTO_ENCLOSED_FROM
    );
    (enclosed, room)
}

/// The first transmissive material with a rough surface (GGX roughness factor above
/// [`ROUGH_GLASS`]), by its label (`material N "name"`), if any.
fn rough_glass(scene: &Scene) -> Option<String> {
    scene
        .materials()
        .iter()
        .find(|m| m.is_transmissive() && m.desc.roughness > ROUGH_GLASS)
        .map(|m| m.desc.name.clone())
}

/// Roughness above which a transmissive material counts as rough glass for `--method auto`.
pub const ROUGH_GLASS: f32 = 0.05;

/// The caustic share under which `--method auto` picks the hybrid (or, enclosed, VCM) over
/// VCM or SPPM ([`resolve_method`], from the measurements cited there).
pub const AUTO_HYBRID_BELOW: f64 = 0.04;

/// The kept share from which `--method auto` counts a scene as enclosed and picks the
/// bidirectional methods ([`resolve_method`]): between the open scenes' largest (0.24) and
/// the Cornell boxes' smallest (0.57) measured.
pub const AUTO_ENCLOSED_FROM: f64 = 0.35;

/// Probe photons behind the decisions (the number [`resolve_method`] uses).
pub const CAUSTIC_PROBE_PHOTONS: u32 = 4096;

/// Probe photons for the volumetric caustic share.
const VOLUME_PROBE_PHOTONS: u32 = 20_000;

/// The volumetric caustic share from which `auto` adds the volumetric caustic map: 0.01 %
/// of the light scattered in media arriving through specular bounces. Low on purpose: the
/// share is of all the light the media scatter, and a beam through a prism in a hazy room
/// is a small part of it (0.06 % in `hazy_prism.glb`, whose lamp fills its own tube with
/// scattered light) yet the picture's subject, which the path tracer reaches only by chance.
pub const AUTO_VOLUME_CAUSTICS_FROM: f64 = 1e-4;

/// `auto` in a scene with scattering media: the path tracer, or the hybrid with its
/// volumetric caustic map when light reaches the media through specular bounces
/// ([`crate::photon::probe::volume_caustic_share`]).
fn media_method(scene: &Scene) -> (Method, String) {
    let emitter = PhotonEmitter::new(scene);
    let share = if emitter.is_empty() {
        0.0
    } else {
        crate::photon::probe::volume_caustic_share(scene, &emitter, VOLUME_PROBE_PHOTONS)
    };
    let carry = format!(
        "light scatters in media; {:.2} % of it arrives through specular bounces",
        100.0 * share
    );
    if share >= AUTO_VOLUME_CAUSTICS_FROM {
        (
            Method::Hybrid,
            format!(
                "{carry}: the hybrid, whose volumetric caustic map carries that light (the \
                 volumetric path tracer for the rest)"
            ),
        )
    } else {
        (
            Method::Path,
            format!(
                "{carry} (the volumetric caustic map is added from {:.2} %): the volumetric \
                 path tracer",
                100.0 * AUTO_VOLUME_CAUSTICS_FROM
            ),
        )
    }
}
