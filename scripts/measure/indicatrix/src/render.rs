//! The indicatrix render: its CPU spectral path tracer over the whole frame, progressive
//! rounds of one sample per pixel on every thread until a time or sample budget.
//!
//! Per sample this is exactly `indicatrix::renderer::cpu_frame`'s `cpu_sample_xyz` (the
//! shared core of the desktop viewer, the render worker and the browser): the pixel's
//! `PixelRotations`, `sample_draws(pixel, sample_num)`, `Camera::generate_ray` with the
//! draws' jitter, `trace_spectral_ray_with_finish_soa` (all facets polished), and
//! `add_finite_sample`. Only the outer loop differs (a time budget, threads), and `seed`
//! renumbers the pixels' random streams so that two seeds give independent images.

use glam::Vec3;
use indicatrix::{
    geometry::GpuFacetPlane,
    optics::{
        materials::GemMaterial,
        raytracer::{
            Camera, EnvironmentSource, add_finite_sample, build_plane_soa, pixel_rotations,
            sample_draws, trace_spectral_ray_with_finish_soa,
        },
    },
};
use std::time::{Duration, Instant};

pub struct Budget {
    pub time: Option<f64>,
    pub spp: Option<u32>,
}

pub struct Rendered {
    /// Mean XYZ per pixel (row-major, row 0 at the top).
    pub xyz: Vec<Vec3>,
    pub spp: u32,
    pub seconds: f64,
    /// Process CPU time (user + system) spent in the render loop.
    pub cpu_seconds: f64,
}

pub fn cpu_seconds() -> f64 {
    // /proc/self/stat fields 14 and 15: utime, stime in clock ticks (100 Hz on Linux).
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, s)| s);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|s| s.parse::<f64>().ok()).unwrap_or(0.0);
    // After ")" the first field is field 3 (state): utime is field 14 -> index 11.
    (ticks(11) + ticks(12)) / 100.0
}

#[allow(clippy::too_many_arguments)]
pub fn render(
    camera: &Camera,
    size: u32,
    planes: &[GpuFacetPlane],
    material: &GemMaterial,
    max_bounces: u32,
    env: EnvironmentSource<'_>,
    seed: u32,
    threads: usize,
    budget: &Budget,
) -> Rendered {
    let soa = build_plane_soa(planes);
    let n = (size * size) as usize;
    let mut sums: Vec<Vec<Vec3>> = (0..threads)
        .map(|t| vec![Vec3::ZERO; (n + threads - 1 - t) / threads])
        .collect();
    let start = Instant::now();
    let cpu0 = cpu_seconds();
    let mut spp = 0u32;
    loop {
        std::thread::scope(|scope| {
            for (t, part) in sums.iter_mut().enumerate() {
                let soa = &soa;
                scope.spawn(move || {
                    for (j, sum) in part.iter_mut().enumerate() {
                        let pixel = (t + j * threads) as u32;
                        let key = pixel.wrapping_add(seed.wrapping_mul(size * size));
                        let rot = pixel_rotations(key);
                        let draws = sample_draws(key, spp, &rot);
                        let (x, y) = (pixel % size, pixel / size);
                        let ray = camera.generate_ray(
                            x as f32,
                            y as f32,
                            size as f32,
                            size as f32,
                            draws.jitter_x,
                            draws.jitter_y,
                        );
                        let xyz = trace_spectral_ray_with_finish_soa(
                            ray,
                            planes,
                            soa,
                            &[],
                            material,
                            max_bounces,
                            env,
                            draws.seed,
                            draws.hero_rand,
                            None,
                        );
                        add_finite_sample(sum, xyz);
                    }
                });
            }
        });
        spp += 1;
        let elapsed = start.elapsed();
        if budget.spp.is_some_and(|s| spp >= s)
            || budget
                .time
                .is_some_and(|t| elapsed >= Duration::from_secs_f64(t))
        {
            break;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu0;
    let mut xyz = vec![Vec3::ZERO; n];
    for (t, part) in sums.iter().enumerate() {
        for (j, s) in part.iter().enumerate() {
            xyz[t + j * threads] = *s / spp as f32;
        }
    }
    Rendered {
        xyz,
        spp,
        seconds,
        cpu_seconds: cpu,
    }
}
