//! The gem stage (`iris gem-report`): a stone alone on an instrument's axis, table up,
//! seen straight down by a distant viewer, lit only by the instrument
//! ([`crate::studio::instrument`]). It is the preparation of the gem report's renders, in
//! place of [`super::prepare`]'s drop-in choices, which a measurement must not make: no
//! floor, no studio, no file lights or cameras, no other objects.
//!
//! ## What is kept
//! The file is loaded and validated ([`crate::load::load_scene`]), `--stone` flags are
//! applied ([`super::looks`]), then only the **stone**: the meshes whose material is a
//! transmissive volume (KHR_materials_transmission > 0 with KHR_materials_volume
//! thickness > 0). None is an error naming the file and its meshes. Lights, cameras,
//! the file's environment and fog, and every other mesh are dropped.
//!
//! ## Frames
//! - **Table direction** ([`Table`]): `auto` takes the outward normal of the stone's
//!   largest flat facet among those facing up (normal within 45° of the file's +Y;
//!   coplanar triangles with the same normal to 10⁻³ count as one facet), else +Y, the
//!   frame of Iris's own gems ([`crate::authoring::cuts`]: girdle plane y = 0, table up).
//! - **Scale.** The stone is first centred on its bounding box and scaled by the power of
//!   two that brings its largest coordinate into [2^-½, 2^½) (exact in floating point;
//!   lengths of its materials, the attenuation distance, the volume thickness and
//!   Rayleigh's σ_s, scaled with it), so every figure is the same for the same stone at
//!   any size the file's f32 coordinates can hold, and the table search and the ray
//!   tracing never meet products of coordinates beyond f32's range. A stone whose extent
//!   is outside [`EXTENTS`] is refused with an error naming the file.
//!   Lengths the stage reports ([`GemStage::girdle_radius`], [`GemStage::height`],
//!   [`GemStage::half_field`]) are in the file's units.
//! - The stone is turned so the table direction is +Y (the shortest rotation), then moved
//!   so the centre of its bounding box is the origin. The **girdle radius** is the largest
//!   distance of a vertex from the Y axis then (half the girdle diameter of a round stone).
//! - **Tilt** t (degrees): the stone turns by t about +X through the origin (right-handed:
//!   +Y goes towards +Z), so the table tips towards the bottom of the image; viewer and
//!   lighting stay, as when a stone is rocked under the instrument (Sasian et al. 2007's
//!   tilt views).
//! - **Viewer**: an orthographic camera on the +Y axis looking down −Y, image right = +X,
//!   image up = −Z, square, half-size the largest |x| or |z| of any vertex at any of the
//!   report's tilts plus 4 %: every image of a report has the same scale, and the stone's
//!   axis is the image centre at tilt 0. Parallel rays: the viewer is far compared with the
//!   stone, and the instrument's obscuration is part of its lighting instead.
//!
//! ## Wavelength and colour
//! The renders use RGB transport with the stone's index at one wavelength ([`ShotSetup::lambda_nm`]):
//! every stone material's n(λ) model ([`crate::material::MaterialDesc::spectral_ior`]) is
//! replaced by the constant n(λ), so a render is deterministic and noise-free in colour,
//! and two renders at two Fraunhofer lines show the dispersion between them.
//!
//! A **birefringent** stone (a crystal material, [`crate::material::CrystalDesc`], that is
//! not isotropic: [`GemStage::birefringent`]) splits unpolarized light into two modes of
//! orthogonal polarization, each carrying half of it. The stage shows one mode at a time
//! ([`ShotSetup::mode`]) as an isotropic stone of that mode's index at the wavelength
//! ([`mode_index`]): with n₁ ≤ n₂ ≤ n₃ the principal indices at λ, the fast mode's index
//! runs over [n₁, n₂] with the direction of travel and the slow mode's over [n₂, n₃]
//! (Born & Wolf §15.3), and each takes the middle of its range. For a uniaxial stone one
//! of them is the ordinary mode, exactly n_o in every direction, the other the
//! extraordinary wave at (n_o + n_e)/2. The gem report renders each shot once per mode and
//! takes the mean of the two images ([`crate::app::gem_report::shots`]), so every figure,
//! fire included, is that of both modes' light, each dispersing with its own n(λ).
//! Simplified: each mode keeps its index through the stone (reflections inside do not
//! exchange light between the modes), the extraordinary index does not vary with the
//! direction, and the crystal's absorption per mode gives way to the material's
//! colour. For the
//! instruments that code angles in colour channels ([`ShotSetup::grey_body`]: ASET,
//! Ideal-Scope, the direction code) a coloured stone's body colour is made grey with the
//! same luminance-weighted absorption ([`grey`]), so a blue sapphire does not paint
//! ASET's red band dark; a base colour texture still tints.
//!
//! Units: the file's (metres for glTF); angles in degrees at the API.

mod frame;

pub use frame::EXTENTS;

use super::looks::{self, LookFlag};
use super::Prepared;
use crate::accel::Backend;
use crate::error::{Error, LoadError, LoadErrorKind, Result};
use crate::light::env::Environment;
use crate::material::CrystalDesc;
use crate::polar::crystal::Which;
use crate::scene::desc::{AddedLights, CameraDesc, MeshDesc, Projection, SceneDesc};
use crate::scene::Scene;
use frame::{bounds, normalised, reach, scale_lengths, turned, up_facet};
use glam::{Mat4, Quat, Vec3};
use std::path::Path;
use std::time::{Duration, Instant};

/// How the stone's table direction is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Table {
    /// The largest flat facet facing up, else +Y (see the module docs).
    Auto,
    /// This direction (a non-zero vector, normalised).
    Given(Vec3),
}

impl Table {
    /// Parses `--table`: `auto` or `X,Y,Z` (finite, not all zero).
    pub fn parse(s: &str) -> Result<Table> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("auto") {
            return Ok(Table::Auto);
        }
        let nums: Option<Vec<f64>> = t.split(',').map(|p| p.trim().parse().ok()).collect();
        let bad = |why: String| {
            Error::Usage(format!(
                "--table {s:?}: expected auto or a direction X,Y,Z (finite, not zero){why}"
            ))
        };
        match nums.as_deref() {
            Some(&[x, y, z]) => crate::math::unit_direction(glam::DVec3::new(x, y, z))
                .map(Table::Given)
                .map_err(|why| bad(format!("; the direction {why}"))),
            _ => Err(bad(String::new())),
        }
    }
}

/// The stone on the stage, ready to be prepared under any instrument and tilt.
pub struct GemStage {
    /// The stone alone, table +Y, bounding-box centre at the origin, untilted, in stage
    /// units (the file's times [`GemStage::scale`]).
    desc: SceneDesc,
    /// Stage units per file unit: a power of two (module docs).
    scale: f32,
    /// Whether a stone material is a crystal that is not isotropic: each shot is then
    /// rendered once per mode ([`ShotSetup::mode`]).
    pub birefringent: bool,
    /// The stone's mesh names, as the file names them.
    pub meshes: Vec<String>,
    /// The table direction in the file's frame (unit).
    pub table: Vec3,
    /// Whether the table direction came from a facet (`auto` found one) or was +Y/given.
    pub table_found: bool,
    /// Largest distance of a vertex from the axis, face-up (file units).
    pub girdle_radius: f32,
    /// Height of the stone along the axis (file units).
    pub height: f32,
    /// Half-size of every image's square field (file units).
    pub half_field: f32,
    /// Load and validation time.
    pub load_time: Duration,
}

/// One render's set-up on the stage.
#[derive(Debug, Clone)]
pub struct ShotSetup {
    /// The instrument's lighting.
    pub environment: Environment,
    /// Tilt about +X, degrees.
    pub tilt: f32,
    /// Wavelength whose index the stone takes, nm.
    pub lambda_nm: f32,
    /// Image side, pixels (square).
    pub size: u32,
    /// Make the stone's body colour grey (see the module docs): for the instruments that
    /// code directions in colour channels.
    pub grey_body: bool,
    /// The mode a birefringent stone shows (module docs); no effect on other stones.
    pub mode: Which,
}

impl GemStage {
    /// Loads `path`, applies `looks`, keeps the stone and puts it on the axis; `tilts`
    /// (degrees) are every tilt the caller will ask for, so the field fits them all.
    pub fn new(path: &Path, looks: &[LookFlag], table: Table, tilts: &[f32]) -> Result<GemStage> {
        let start = Instant::now();
        let mut desc = crate::load::load_scene(path)?;
        looks::apply(&mut desc, looks)?;
        let (stone, names) = stone_meshes(&desc)?;
        let (stone, scale) = normalised(path, stone)?;
        let (table, table_found) = match table {
            Table::Given(t) => (t, false),
            Table::Auto => match up_facet(&stone) {
                Some(n) => (n, true),
                None => (Vec3::Y, false),
            },
        };
        let orient = Quat::from_rotation_arc(table, Vec3::Y);
        let mut meshes: Vec<MeshDesc> = stone.into_iter().map(|m| turned(m, orient)).collect();
        let (lo, hi) = bounds(&meshes);
        let centre = 0.5 * (lo + hi);
        for m in &mut meshes {
            m.positions.iter_mut().for_each(|p| *p -= centre);
        }
        let girdle_radius = meshes
            .iter()
            .flat_map(|m| m.positions.iter())
            .map(|p| p.x.hypot(p.z))
            .fold(0.0f32, f32::max);
        let half_field = 1.04
            * tilts
                .iter()
                .chain(&[0.0])
                .map(|&t| reach(&meshes, t))
                .fold(0.0f32, f32::max);
        if !(half_field > 0.0 && half_field.is_finite()) {
            return Err(LoadError::new(
                path,
                "",
                LoadErrorKind::InvalidValue,
                "the stone has no extent across the viewing axis",
            )
            .into());
        }
        let mut materials = desc.materials;
        materials.iter_mut().for_each(|m| scale_lengths(m, scale));
        let birefringent = meshes
            .iter()
            .filter_map(|m| materials.get(m.material?)?.crystal)
            .any(|c| c.character() != crate::spectrum::crystals::Character::Isotropic);
        let stage_desc = SceneDesc {
            source: desc.source.clone(),
            meshes,
            materials,
            images: desc.images,
            ..SceneDesc::default()
        };
        Ok(GemStage {
            desc: stage_desc,
            scale,
            birefringent,
            meshes: names,
            table,
            table_found,
            girdle_radius: girdle_radius / scale,
            height: (hi.y - lo.y) / scale,
            half_field: half_field / scale,
            load_time: start.elapsed(),
        })
    }

    /// The render scene of `setup`: the stone tilted, its index at the wavelength, under
    /// the instrument, with the viewer's camera.
    pub fn prepare(&self, setup: &ShotSetup, accel: Backend) -> Result<Prepared> {
        let start = Instant::now();
        let mut desc = self.desc.clone();
        let tilt = Quat::from_rotation_x(setup.tilt.to_radians());
        desc.meshes = desc.meshes.into_iter().map(|m| turned(m, tilt)).collect();
        let used: Vec<usize> = desc.meshes.iter().filter_map(|m| m.material).collect();
        for i in used {
            let m = &mut desc.materials[i];
            if m.ior == 0.0 {
                continue;
            }
            let model = m
                .spectral_ior()
                .map_err(|e| Error::Usage(format!("material {:?}: {e}", m.name)))?;
            // A crystal becomes the isotropic stone of the mode shown (module docs).
            m.ior = match m.crystal.take() {
                Some(c) => mode_index(&c, setup.lambda_nm, setup.mode),
                None => model.ior(setup.lambda_nm),
            };
            m.dispersion = 0.0;
            m.ior_model = None;
            if setup.grey_body {
                grey(m);
            }
        }
        desc.environment_light = Some(setup.environment.clone());
        desc.added_lights = AddedLights::None;
        let scene = Scene::build(desc, accel)?;
        Ok(Prepared {
            scene,
            camera: self.camera(),
            size: (setup.size, setup.size),
            load_time: self.load_time + start.elapsed(),
            notes: Vec::new(),
            camera_note: None,
            looks: Vec::new(),
            subject: None,
        })
    }

    /// The viewer: orthographic, on +Y looking down, image up = −Z (see the module docs).
    pub fn camera(&self) -> CameraDesc {
        let h = self.half_field * self.scale;
        let eye = Vec3::new(0.0, 4.0 * (h + self.height * self.scale), 0.0);
        CameraDesc {
            name: "gem stage viewer".into(),
            projection: Projection::Orthographic { xmag: h, ymag: h },
            world_from_camera: Mat4::from_cols(
                Vec3::X.extend(0.0),
                Vec3::NEG_Z.extend(0.0),
                Vec3::Y.extend(0.0),
                eye.extend(1.0),
            ),
        }
    }
}

/// The index of the isotropic stand-in for mode `which` of crystal `c` at `nm`: the middle
/// of the range of indices the mode takes, (n₁ + n₂)/2 for the fast mode and (n₂ + n₃)/2
/// for the slow one, n₁ ≤ n₂ ≤ n₃ the principal indices (module docs).
pub fn mode_index(c: &CrystalDesc, nm: f32, which: Which) -> f32 {
    let mut n = c.indices(nm);
    n.sort_by(f32::total_cmp);
    match which {
        Which::Fast => 0.5 * (n[0] + n[1]),
        Which::Slow => 0.5 * (n[1] + n[2]),
    }
}

/// A material's body colour made grey of the same luminance-weighted absorption: each
/// channel's absorption coefficient −ln(c)/d replaced by their Rec. 709 luminance-weighted
/// mean (so the attenuation colour becomes the weighted geometric mean of its channels),
/// and the base colour factor (which tints transmission) by its luminance.
fn grey(m: &mut crate::material::MaterialDesc) {
    let w = Vec3::new(0.2126, 0.7152, 0.0722);
    let c = m.attenuation_color.max(Vec3::splat(1e-6));
    let ln = Vec3::new(c.x.ln(), c.y.ln(), c.z.ln());
    m.attenuation_color = Vec3::splat(w.dot(ln).exp());
    let b = m.base_color;
    let y = w.dot(b.truncate());
    m.base_color = glam::Vec4::new(y, y, y, b.w);
}

/// The stone's meshes (transmissive volumes) and their names; an error naming the file
/// and every mesh when there is none.
fn stone_meshes(desc: &SceneDesc) -> Result<(Vec<MeshDesc>, Vec<String>)> {
    let is_stone = |m: &MeshDesc| {
        m.material
            .and_then(|i| desc.materials.get(i))
            .is_some_and(|mat| mat.transmission > 0.0 && mat.thickness > 0.0)
    };
    let stone: Vec<MeshDesc> = desc
        .meshes
        .iter()
        .filter(|m| is_stone(m))
        .cloned()
        .collect();
    if stone.is_empty() {
        let names: Vec<&str> = desc.meshes.iter().map(|m| m.name.as_str()).collect();
        return Err(LoadError::new(
            &desc.source,
            format!("meshes {}", names.join(", ")),
            LoadErrorKind::InvalidValue,
            "no transmissive stone: no mesh has a transmissive volume material \
             (KHR_materials_transmission with KHR_materials_volume); --stone NAME makes its \
             materials a stone",
        )
        .into());
    }
    let names = stone.iter().map(|m| m.name.clone()).collect();
    Ok((stone, names))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_flag_parses_auto_and_directions() {
        assert_eq!(Table::parse("auto").unwrap(), Table::Auto);
        assert_eq!(Table::parse(" 0,0,2 ").unwrap(), Table::Given(Vec3::Z));
        assert!(Table::parse("0,0,0").is_err());
        assert!(Table::parse("1,2").is_err());
        assert!(Table::parse("up").is_err());
        assert!(Table::parse("nan,1,0").is_err());
        assert!(Table::parse("0,inf,0").is_err());
        // Lengths that overflow or underflow f32 when squared are still directions.
        for big in ["3e38,3e38,0", "1e300,1e300,0", "1e-30,1e-30,0"] {
            let Ok(Table::Given(d)) = Table::parse(big) else {
                panic!("{big} refused")
            };
            assert!(
                (d - Vec3::new(1.0, 1.0, 0.0) / 2f32.sqrt()).length() < 1e-6,
                "{big}: {d}"
            );
        }
    }

    #[test]
    fn grey_keeps_the_luminance_weighted_absorption() {
        let mut m = crate::material::MaterialDesc {
            attenuation_color: Vec3::new(0.2, 0.5, 0.9),
            base_color: glam::Vec4::new(1.0, 0.5, 0.25, 0.8),
            ..Default::default()
        };
        grey(&mut m);
        let a = m.attenuation_color;
        assert!(a.x == a.y && a.y == a.z);
        let expected = 0.2126 * 0.2f32.ln() + 0.7152 * 0.5f32.ln() + 0.0722 * 0.9f32.ln();
        assert!((a.x.ln() - expected).abs() < 1e-5);
        let y = 0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25;
        assert!((m.base_color - glam::Vec4::new(y, y, y, 0.8)).length() < 1e-6);
        // A clear stone stays clear.
        let mut clear = crate::material::MaterialDesc::default();
        grey(&mut clear);
        assert_eq!(clear.attenuation_color, Vec3::ONE);
    }
}
