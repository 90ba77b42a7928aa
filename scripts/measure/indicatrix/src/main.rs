//! Issue 34: a round brilliant rendered by indicatrix 0.9.0 and by Iris, side by side.
//! See README.md for what each subcommand does and the commands that made the images.

mod glb;
mod images;
mod lighting;
mod render;

use glam::Vec3;
use indicatrix::optics::{
    materials::GemMaterial,
    raytracer::{Camera, EnvironmentSource, Ray, intersect_polyhedron},
};
use indicatrix::renderer::env_map::EnvironmentMap;
use lighting::{Convention, Lighting};
use std::fmt::Write as _;

/// Face-up camera: straight down the stone's axis from this many girdle radii above the
/// girdle plane's centre (a 6.5 mm stone seen from 32.5 cm), with this vertical field of
/// view (the girdle fills 87 % of the frame). So far away because indicatrix's light tent
/// darkens a 16° head shadow round the direction from the stone to the eye, per pixel,
/// which no environment map can follow: from here that direction is within 0.6° of +Y
/// over the whole stone, where the baked map puts it (at 12 radii, 4.8°, indicatrix's
/// own studio and baked renders differed by 9 % in mean luminance; from here by 1 %).
const DISTANCE: f32 = 100.0;
const FOV_DEG: f32 = 1.32;

fn usage() -> ! {
    eprintln!(
        "usage:
  indicatrix-vs-iris planes --glb STONE.glb
  indicatrix-vs-iris iris-camera --glb STONE.glb
  indicatrix-vs-iris bake --glb STONE.glb --lighting tent|ring [--width 2048] [--ss 3] --out ENV.exr
  indicatrix-vs-iris render --glb STONE.glb --stone diamond|moissanite --lighting tent|ring
        [--env studio|baked] [--size 512] [--time S] [--spp N] [--seed K] [--threads T]
        [--max-bounces 12] --out PREFIX          (PREFIX.exr linear sRGB, PREFIX.png, PREFIX.txt)
  indicatrix-vs-iris compose --glb STONE.glb --left A.exr --right B.exr [--left2 A2.exr --right2 B2.exr]
        --label-left TEXT --label-right TEXT [--sub-left TEXT --sub-right TEXT] [--footer TEXT]
        --out SIDE.png [--stats STATS.txt]"
    );
    std::process::exit(2)
}

struct Args(Vec<String>);

impl Args {
    fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .position(|a| a == name)
            .map(|i| self.0.get(i + 1).unwrap_or_else(|| usage()).as_str())
    }
    fn req(&self, name: &str) -> &str {
        self.get(name).unwrap_or_else(|| {
            eprintln!("missing {name}");
            usage()
        })
    }
    fn num<T: std::str::FromStr>(&self, name: &str, default: T) -> T {
        self.get(name)
            .map_or(default, |v| v.parse().unwrap_or_else(|_| panic!("bad {name} {v:?}")))
    }
}

/// The camera: face-up by default; `--cam-yaw`/`--cam-pitch` (degrees), `--cam-distance`
/// (girdle radii) and `--fov` (degrees) give other views (for checks).
struct View {
    yaw_deg: f32,
    pitch_deg: f32,
    distance: f32,
    fov_deg: f32,
}

impl View {
    fn from_args(args: &Args) -> Self {
        Self {
            yaw_deg: args.num("--cam-yaw", 0.0),
            pitch_deg: args.num("--cam-pitch", 90.0),
            distance: args.num("--cam-distance", DISTANCE),
            fov_deg: args.num("--fov", FOV_DEG),
        }
    }

    fn camera(&self) -> Camera {
        // Pitch 90°: straight down; indicatrix then puts image-up along -Z and image-right
        // along +X (camera.rs, the pole case), which is also what Iris's look-at does for a
        // camera looking straight down (up = -Z).
        let pitch = if self.pitch_deg == 90.0 {
            std::f32::consts::FRAC_PI_2
        } else {
            self.pitch_deg.to_radians()
        };
        Camera::new(self.yaw_deg.to_radians(), pitch, self.distance, self.fov_deg)
    }

    /// Iris's `--camera-look-at` for the same camera, in the file's units.
    fn iris_look_at(&self, radius: f64) -> String {
        let o = self.camera().origin.as_dvec3() * radius;
        let clean = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
        format!("{},{},{}:0,0,0:{}", clean(o.x), clean(o.y), clean(o.z), self.fov_deg)
    }

    fn describe(&self) -> String {
        format!(
            "camera yaw {}°, pitch {}°, distance {} girdle radii, vertical FOV {}° (looking at the girdle centre)",
            self.yaw_deg, self.pitch_deg, self.distance, self.fov_deg
        )
    }
}

fn material(stone: &str, planes: &[indicatrix::geometry::GpuFacetPlane]) -> GemMaterial {
    // `NAME-iso`: the stone with its birefringence removed (one index, n_o: what Iris's
    // `--polarization off` renders), for isolating the birefringent transport.
    if let Some(base) = stone.strip_suffix("-iso") {
        let mut m = material(base, planes);
        m.optical_character = indicatrix::optics::materials::OpticalCharacter::Isotropic;
        m.birefringence_delta = 0.0;
        m.uniaxial_extraordinary_dispersion = None;
        return m;
    }
    let name = match stone {
        "diamond" => "Diamond",
        "moissanite" => "Synthetic Moissanite",
        other => panic!("unknown stone {other:?} (diamond, moissanite)"),
    };
    let m = GemMaterial::by_name(name).expect("a built-in material");
    // The viewer's size rule with no stone size set (colourless stones: no effect).
    indicatrix::render_setup::material_for_stone(m, 0.0, planes)
}

fn stone_mask(planes: &[indicatrix::geometry::GpuFacetPlane], view: &View, w: u32, h: u32) -> Vec<bool> {
    let cam = view.camera();
    (0..w * h)
        .map(|i| {
            let ray: Ray = cam.generate_ray((i % w) as f32, (i / w) as f32, w as f32, h as f32, 0.5, 0.5);
            intersect_polyhedron(ray, planes).is_some()
        })
        .collect()
}

fn write_exr_gray(path: &str, w: usize, h: usize, v: &[f32]) {
    let img = image::Rgb32FImage::from_fn(w as u32, h as u32, |x, y| {
        let g = v[y as usize * w + x as usize];
        image::Rgb([g, g, g])
    });
    image::DynamicImage::ImageRgb32F(img)
        .save(path)
        .unwrap_or_else(|e| panic!("writing {path}: {e}"));
}

fn main() {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let Some(cmd) = argv.first().cloned() else { usage() };
    let args = Args(argv);
    match cmd.as_str() {
        "planes" => {
            let s = glb::read_planes(args.req("--glb"));
            println!(
                "{} facet planes; girdle radius {} (file units); table at y = {:.5}, culet at y = {:.5} girdle radii; worst vertex outside a plane {:.2e}",
                s.planes.len(),
                s.radius,
                s.y_max,
                s.y_min,
                s.worst_outside
            );
            for p in &s.planes {
                let n = Vec3::from_array(p.normal);
                let tilt = n.y.clamp(-1.0, 1.0).acos().to_degrees();
                let az = n.x.atan2(n.z).to_degrees();
                println!("  n = ({:+.5}, {:+.5}, {:+.5})  tilt {tilt:7.3}°  azimuth {az:8.3}°  d = {:.5}", n.x, n.y, n.z, p.d);
            }
        }
        "iris-camera" => {
            let s = glb::read_planes(args.req("--glb"));
            println!("{}", View::from_args(&args).iris_look_at(s.radius));
        }
        "bake" => {
            let s = glb::read_planes(args.req("--glb"));
            let l = Lighting::by_name(args.req("--lighting"));
            let width: usize = args.num("--width", 2048);
            let ss: usize = args.num("--ss", 3);
            let out = args.req("--out");
            let cal = lighting::calibrate(&l, &s.planes, 200_000);
            let t = std::time::Instant::now();
            let map = lighting::bake(&l, cal.k, width, ss, Convention::Iris);
            write_exr_gray(out, width, width / 2, &map);
            // A preview through the display transform (D65 grey of luminance = texel).
            let preview: Vec<Vec3> = map.iter().map(|&g| images::rgb_to_xyz(Vec3::splat(g))).collect();
            images::display(width as u32, (width / 2) as u32, &preview)
                .save(format!("{out}.png"))
                .unwrap();
            let max = map.iter().copied().fold(0.0f32, f32::max);
            let mean_up: f32 = map[..map.len() / 2].iter().sum::<f32>() / (map.len() / 2) as f32;
            let report = format!(
                "{out}: {} x {} equirectangular, Iris convention (+Y up, centre along -Z, nearest texel), {ss}x{ss} directions per texel, grey linear sRGB\n\
                 lighting: {}\n\
                 k (luminance of unit rig radiance, measured through indicatrix's tracer) = {:.6}\n\
                 traced environment chromaticity x,y = {:.4}, {:.4} (D65: 0.3127, 0.3290)\n\
                 largest spread of the rig's radiance over 400-700 nm relative to 560 nm: {:.2e} (0 = one spectrum everywhere)\n\
                 head shadow baked round +Y (the face-up eye)\n\
                 max texel {max:.4}, mean of the upper half {mean_up:.4}; baked in {:.1} s\n",
                width,
                width / 2,
                l.describe(),
                cal.k,
                cal.xy.0,
                cal.xy.1,
                cal.spectral_spread,
                t.elapsed().as_secs_f64()
            );
            print!("{report}");
            std::fs::write(format!("{out}.txt"), report).unwrap();
        }
        "render" => {
            let glb_path = args.req("--glb");
            let s = glb::read_planes(glb_path);
            let stone = args.req("--stone");
            let furnace = args.req("--lighting") == "furnace";
            let l = Lighting::by_name(if furnace { "tent" } else { args.req("--lighting") });
            let env_kind = if furnace { "furnace" } else { args.get("--env").unwrap_or("studio") };
            let size: u32 = args.num("--size", 512);
            let seed: u32 = args.num("--seed", 0);
            let threads: usize = args.num("--threads", 2);
            let max_bounces: u32 = args.num("--max-bounces", 12);
            let budget = render::Budget {
                time: args.get("--time").map(|t| t.parse().expect("--time seconds")),
                spp: args.get("--spp").map(|t| t.parse().expect("--spp count")),
            };
            if budget.time.is_none() && budget.spp.is_none() {
                eprintln!("give --time and/or --spp");
                usage();
            }
            let out = args.req("--out");
            let mat = material(stone, &s.planes);
            let map;
            let (env, env_text) = match env_kind {
                "furnace" => {
                    map = EnvironmentMap::uniform(4, 2, [1.0, 1.0, 1.0]);
                    (EnvironmentSource::HdrMap(&map), "white furnace: uniform RGB (1, 1, 1) map".to_string())
                }
                "studio" => (l.studio(), format!("analytic studio: {}", l.describe())),
                "baked" => {
                    let cal = lighting::calibrate(&l, &s.planes, 200_000);
                    let w = 2048;
                    let texels = lighting::bake(&l, cal.k, w, 3, Convention::Indicatrix);
                    map = EnvironmentMap::from_rgb(w, w / 2, texels.iter().map(|&g| [g, g, g]).collect())
                        .expect("a map");
                    (
                        EnvironmentSource::HdrMap(&map),
                        format!(
                            "the studio baked to a {w}x{} grey RGB map (indicatrix EnvironmentMap, head shadow round +Y): {}",
                            w / 2,
                            l.describe()
                        ),
                    )
                }
                other => panic!("unknown --env {other:?} (studio, baked)"),
            };
            let view = View::from_args(&args);
            let cam = view.camera();
            eprintln!("rendering {stone} / {} / {env_kind} at {size}x{size}, seed {seed}, {threads} threads ...", l.name);
            let r = render::render(&cam, size, &s.planes, &mat, max_bounces, env, seed, threads, &budget);
            images::write_exr_from_xyz(&format!("{out}.exr"), size, &r.xyz);
            images::display(size, size, &r.xyz)
                .save(format!("{out}.png"))
                .unwrap();
            let mut t = String::new();
            writeln!(t, "renderer: indicatrix {} (BUILD_ID {}), CPU spectral path tracer (8 hero wavelengths, Stokes-Mueller polarized, birefringent split for uniaxial stones), trace_spectral_ray_with_finish_soa per sample as in renderer::cpu_frame", indicatrix::VERSION, indicatrix::BUILD_ID).unwrap();
            writeln!(t, "stone: {glb_path}: {} facet planes from Iris's mesh, girdle radius 1; material {:?} ({:?}, birefringence {})", s.planes.len(), mat.name, mat.optical_character, mat.birefringence_delta).unwrap();
            writeln!(t, "environment: {env_text}").unwrap();
            writeln!(t, "camera: {} = Iris --camera-look-at {}", view.describe(), view.iris_look_at(s.radius)).unwrap();
            writeln!(t, "size {size}x{size}, max bounces {max_bounces}, seed {seed}, threads {threads}").unwrap();
            writeln!(t, "budget: time {:?} s, spp {:?}", budget.time, budget.spp).unwrap();
            writeln!(t, "result: {} spp in {:.2} s wall ({:.2} s CPU, {:.0} samples/s)", r.spp, r.seconds, r.cpu_seconds, f64::from(r.spp) * f64::from(size * size) / r.seconds).unwrap();
            writeln!(t, "spp {}", r.spp).unwrap();
            writeln!(t, "seconds {:.2}", r.seconds).unwrap();
            writeln!(t, "cpu_seconds {:.2}", r.cpu_seconds).unwrap();
            print!("{t}");
            std::fs::write(format!("{out}.txt"), t).unwrap();
        }
        "compose" => {
            let s = glb::read_planes(args.req("--glb"));
            let (w, h, left) = images::read_exr_xyz(args.req("--left"));
            let (w2, h2, right) = images::read_exr_xyz(args.req("--right"));
            assert_eq!((w, h), (w2, h2), "the two images differ in size");
            let mask = stone_mask(&s.planes, &View::from_args(&args), w, h);
            let dl = images::display(w, h, &left);
            let dr = images::display(w, h, &right);
            // `--zoom X,Y,SIZE,FACTOR`: the panels show the mean of both seeds (when given)
            // cropped to SIZE×SIZE at (X, Y) and enlarged FACTOR times (nearest pixel).
            let zoomed = args.get("--zoom").map(|z| {
                let v: Vec<u32> = z.split(',').map(|n| n.parse().expect("--zoom X,Y,SIZE,FACTOR")).collect();
                let view = |xyz: &[Vec3], second: Option<&str>| {
                    let mean: Vec<Vec3> = match second {
                        Some(p) => {
                            let (_, _, b) = images::read_exr_xyz(p);
                            xyz.iter().zip(&b).map(|(a, b)| 0.5 * (*a + *b)).collect()
                        }
                        None => xyz.to_vec(),
                    };
                    let d = images::display(w, h, &mean);
                    let crop = image::imageops::crop_imm(&d, v[0], v[1], v[2], v[2]).to_image();
                    image::imageops::resize(&crop, v[2] * v[3], v[2] * v[3], image::imageops::FilterType::Nearest)
                };
                (view(&left, args.get("--left2")), view(&right, args.get("--right2")))
            });
            let (pl, pr) = match &zoomed {
                Some((a, b)) => (a, b),
                None => (&dl, &dr),
            };
            let panels = [
                (pl, args.req("--label-left"), args.get("--sub-left").unwrap_or("")),
                (pr, args.req("--label-right"), args.get("--sub-right").unwrap_or("")),
            ];
            let img = images::compose(&panels, args.get("--footer").unwrap_or(""));
            let out = args.req("--out");
            img.save(out).unwrap();
            let mut t = String::new();
            let stone_px = mask.iter().filter(|&&m| m).count();
            writeln!(t, "{out}: stone pixels {stone_px} of {}", w * h).unwrap();
            if args.get("--left2").is_some() {
                writeln!(t, "  (brightness and colour: mean of seeds 0 and 1; noise: RMS(seed 0 - seed 1)/sqrt 2 of one image)").unwrap();
            }
            writeln!(t, "  {:>8} {:>15} {:>8} {:>9} {:>8} {:>9} {:>12} {:>12}", "mean Y", "mean x, y", "luma", "bright%", "fire%", "mean sat", "noise 8-bit", "noise rel Y").unwrap();
            for (name, xyz, disp, second) in [
                (args.req("--label-left"), &left, &dl, args.get("--left2")),
                (args.req("--label-right"), &right, &dr, args.get("--right2")),
            ] {
                // Brightness and colour from the mean of the two seeds (twice the samples,
                // less noise in the colour numbers); noise from their difference.
                let (st, n8, nrel) = match second {
                    Some(p) => {
                        let (_, _, xyz2) = images::read_exr_xyz(p);
                        let d2 = images::display(w, h, &xyz2);
                        let (n8, nrel) = images::noise(xyz, disp, &xyz2, &d2, &mask);
                        let mean: Vec<Vec3> = xyz.iter().zip(&xyz2).map(|(a, b)| 0.5 * (*a + *b)).collect();
                        let dm = images::display(w, h, &mean);
                        (images::stats(&mean, &dm, &mask), n8, nrel)
                    }
                    None => (images::stats(xyz, disp, &mask), f64::NAN, f64::NAN),
                };
                writeln!(t, "{name}").unwrap();
                writeln!(
                    t,
                    "  {:>8.4} {:>15} {:>8.4} {:>8.2}% {:>7.2}% {:>9.3} {:>12.2} {:>12.4}",
                    st.mean_y,
                    format!("{:.4}, {:.4}", st.mean_xy.0, st.mean_xy.1),
                    st.mean_display_luma,
                    100.0 * st.bright_fraction,
                    100.0 * st.fire_fraction,
                    st.mean_saturation,
                    n8,
                    nrel
                )
                .unwrap();
            }
            print!("{t}");
            if let Some(p) = args.get("--stats") {
                std::fs::write(p, t).unwrap();
            }
        }
        _ => usage(),
    }
}
