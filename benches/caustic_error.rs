//! Error against run time on the caustic sphere scene (issue 5's performance goal): the
//! glass sphere on a white floor ([`iris::assets::bench::caustic_sphere`]) rendered at
//! 128 × 96 by `path`, `photon` and `sppm` with growing budgets, each image compared with a
//! long SPPM reference (2048 passes × 32 768 photons, another seed). Two lights:
//!
//! - `point`: a 1 cd point light. No camera path can reach a point light through glass, so
//!   the path tracer misses the caustic entirely and its error stops falling;
//! - `area`: a 10 × 10 cm emitter of the same power, which the path tracer can reach
//!   (slowly: the caustic is found only when a path through the sphere happens to hit
//!   the small light).
//!
//! Prints one row per render (method, budget, seconds, RMSE on linear RGB, RMSE / mean,
//! relative MSE) and, per relative-MSE level, the first time each method reached it and the path/SPPM time
//! ratio; writes the rows to `target/caustic_error.csv`. Run:
//! `cargo bench --bench caustic_error` (about 5 minutes on 2 cores).
#![forbid(unsafe_code)]

use iris::camera::Camera;
use iris::image::metrics::compare;
use iris::image::ImageRgb;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::RenderSettings;
use iris::scene::Scene;
use std::fmt::Write as _;

const W: u32 = 128;
const H: u32 = 96;

fn settings(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings::quiet_rgb((W, H), spp, seed, 0)
}

fn integrator(method: Method, photons: u64, passes: u32) -> Integrator {
    Integrator::new(
        method,
        32,
        &PhotonSettings {
            photons,
            passes,
            ..PhotonSettings::default()
        },
    )
    .expect("a resolved method")
}

fn rmse(a: &ImageRgb, b: &ImageRgb) -> f64 {
    compare(a, b).expect("same size").rmse
}

fn rel_mse(a: &ImageRgb, b: &ImageRgb) -> f64 {
    compare(a, b).expect("same size").rel_mse
}

struct Row {
    scene: &'static str,
    method: &'static str,
    budget: String,
    seconds: f64,
    rmse: f64,
    rel: f64,
    rel_mse: f64,
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is accepted.
    let mut rows: Vec<Row> = Vec::new();
    for (name, area) in [("point", None), ("area", Some(0.05f32))] {
        let (desc, cam) = iris::assets::bench::caustic_sphere(area);
        let desc = iris::scene::validate::validate(desc).expect("valid");
        let scene = Scene::build(desc, iris::accel::Backend::Auto).expect("build");
        let camera = Camera::new(&cam, W, H);
        let (reference, rs) = integrator(Method::Sppm, 32_768, 2048)
            .render(&scene, &camera, &settings(1, 1000))
            .expect("reference");
        let mean = reference
            .data
            .iter()
            .map(|p| (p.x + p.y + p.z) as f64 / 3.0)
            .sum::<f64>()
            / reference.data.len() as f64;
        eprintln!(
            "{name}: reference in {:.1} s, mean {mean:.5}",
            rs.time.as_secs_f64()
        );
        let mut run = |method: &'static str, budget: String, integ: Integrator, spp: u32| {
            let (img, st) = integ
                .render(&scene, &camera, &settings(spp, 7))
                .expect("render");
            let e = rmse(&img, &reference);
            let row = Row {
                scene: name,
                method,
                budget,
                seconds: st.time.as_secs_f64(),
                rmse: e,
                rel: e / mean,
                rel_mse: rel_mse(&img, &reference),
            };
            eprintln!(
                "{:6} {:7} {:>22} {:8.3} s  RMSE {:.4e}  RMSE/mean {:.4}  relMSE {:.4e}",
                row.scene, row.method, row.budget, row.seconds, row.rmse, row.rel, row.rel_mse
            );
            rows.push(row);
        };
        for spp in [1u32, 4, 16, 64, 256, 1024] {
            run(
                "path",
                format!("{spp} spp"),
                integrator(Method::Path, 0, 1),
                spp,
            );
        }
        for (photons, spp) in [
            (25_000u64, 1u32),
            (100_000, 4),
            (400_000, 16),
            (1_600_000, 64),
        ] {
            run(
                "photon",
                format!("{photons} photons {spp} spp"),
                integrator(Method::Photon, photons, 1),
                spp,
            );
        }
        for passes in [4u32, 16, 64, 256, 1024] {
            run(
                "sppm",
                format!("{passes} passes"),
                integrator(Method::Sppm, (W * H) as u64, passes),
                1,
            );
        }
    }
    // Time to reach each error level.
    for name in ["point", "area"] {
        for level in [3e-2, 1e-2, 3e-3, 1e-3] {
            let first = |m: &str| {
                rows.iter()
                    .filter(|r| r.scene == name && r.method == m && r.rel_mse <= level)
                    .map(|r| r.seconds)
                    .fold(f64::INFINITY, f64::min)
            };
            let (p, ph, s) = (first("path"), first("photon"), first("sppm"));
            eprintln!(
                "{name}: relMSE ≤ {level:.0e}: path {p:.2} s, photon {ph:.2} s, sppm {s:.2} s, path/sppm {:.1}×",
                p / s
            );
        }
    }
    let mut csv = String::from("scene,method,budget,seconds,rmse,rmse_over_mean,rel_mse\n");
    for r in &rows {
        let _ = writeln!(
            csv,
            "{},{},{},{:.4},{:.6e},{:.5},{:.6e}",
            r.scene, r.method, r.budget, r.seconds, r.rmse, r.rel, r.rel_mse
        );
    }
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/caustic_error.csv");
    if let Err(e) = std::fs::write(&out, csv) {
        eprintln!("cannot write {}: {e}", out.display());
    } else {
        eprintln!("wrote {}", out.display());
    }
}
