//! Stones and settings (`--stone`, `--metal`): replacing materials of the loaded scene
//! description, before anything else the preparation decides (the floor, the plan and
//! the studio then see the stone). Artists' gem models often carry a viewer's placeholder
//! material (an opaque cyan with a clearcoat); `--stone diamond` makes them a diamond.
//!
//! A flag is `NAME` or `NAME=SELECTOR` ([`super::select`] for the selector rules):
//! - `--stone NAME`: one of the stones of `iris gem` ([`Stone`], the one table in
//!   `authoring/stones.rs`): a smooth dispersive dielectric volume (KHR ior n_d, dispersion
//!   20/V_d), coloured stones with Beer–Lambert absorption;
//! - `--metal NAME`: a measured metal ([`Metal`]: gold, silver, platinum, copper,
//!   rose-gold), an opaque conductor with its spectral complex index, polished unless
//!   `--metal-roughness` says otherwise (GGX perceptual roughness).
//!
//! What changes, exactly:
//! - `=SELECTOR` naming materials changes those materials (every mesh using them);
//!   naming meshes gives those meshes a new material (their old one, which other meshes
//!   may share, is left as it was);
//! - a flag without a selector (at most one) changes every material no selector named
//!   except emissive ones (lights stay lights), and gives meshes without a material one;
//!   so `--stone diamond --metal gold=Setting` makes the material `Setting` gold and
//!   everything else that does not glow diamond;
//! - two selectors naming the same material, or the same mesh, are an error; a mesh named
//!   by a mesh selector takes that flag even if its material is named by another.
//!
//! A changed material keeps only its name (suffixed with the flag, e.g. `material 0
//! "material" (--stone diamond)`), `doubleSided` and nested-media priority; textures,
//! colour, emission and alpha go. Coloured stones reach their colour after
//! [`COLOUR_DISTANCE`] × (the model's size / 6.5 mm): a model in any units is as saturated
//! as the 6.5 mm stone of `iris gem`, taking as its size the largest bounding-box side of
//! the meshes the material ends up on (the largest of their per-mesh sides).

use super::select::{pick, Picked, Selector};
use crate::authoring::cuts::DEFAULT_SIZE_MM;
use crate::authoring::stones::{Stone, COLOUR_DISTANCE, STONES};
use crate::error::{Error, Result};
use crate::material::MaterialDesc;
use crate::scene::desc::{MeshDesc, SceneDesc};
use crate::spectrum::metals::{Metal, METALS};
use glam::Vec3;

/// What a material becomes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Look {
    /// A gem material from the `iris gem` table.
    Stone(Stone),
    /// A measured metal with this GGX perceptual roughness in [0, 1].
    Metal {
        /// The metal.
        metal: Metal,
        /// Perceptual roughness (α = roughness²); 0 = polished (a mirror).
        roughness: f32,
    },
}

/// One `--stone` or `--metal` flag.
#[derive(Debug, Clone, PartialEq)]
pub struct LookFlag {
    /// What the selected materials become.
    pub look: Look,
    /// Which materials or meshes; `None` = every material no other flag names.
    pub selector: Option<Selector>,
    /// The flag as written, for messages and material names (`--stone ruby=Gem`).
    pub text: String,
}

/// What one flag changed, for the render notes.
#[derive(Debug, Clone, PartialEq)]
pub struct Applied {
    /// The flag as written.
    pub flag: String,
    /// The original names of the materials it replaced or copied for some mesh.
    pub materials: Vec<String>,
    /// How many meshes use them.
    pub meshes: usize,
}

impl std::fmt::Display for Applied {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.materials.is_empty() {
            return write!(f, "{}: changes no material on a mesh", self.flag);
        }
        let shown: Vec<&str> = self.materials.iter().take(3).map(String::as_str).collect();
        let more = match self.materials.len() {
            n if n > 3 => format!(" and {} more", n - 3),
            _ => String::new(),
        };
        let meshes = match self.meshes {
            1 => "1 mesh".to_string(),
            n => format!("{n} meshes"),
        };
        write!(f, "{}: {}{more} ({meshes})", self.flag, shown.join(", "))
    }
}

impl LookFlag {
    /// Parses `--stone NAME[=SELECTOR]`; unknown stones list the known ones.
    pub fn stone(arg: &str) -> Result<LookFlag> {
        let (name, selector) = split(arg, "--stone")?;
        let stone = Stone::parse(name)?;
        Ok(LookFlag {
            look: Look::Stone(stone),
            selector,
            text: format!("--stone {}", arg.trim()),
        })
    }

    /// Parses `--metal NAME[=SELECTOR]` with the `--metal-roughness` value (in [0, 1]).
    pub fn metal(arg: &str, roughness: f32) -> Result<LookFlag> {
        let (name, selector) = split(arg, "--metal")?;
        let metal = Metal::named(name).ok_or_else(|| {
            let names: Vec<&str> = METALS.iter().map(|m| m.name()).collect();
            Error::Usage(format!(
                "--metal {name:?}: unknown metal (expected one of: {})",
                names.join(", ")
            ))
        })?;
        if !(0.0..=1.0).contains(&roughness) {
            return Err(Error::Usage(format!(
                "--metal-roughness {roughness}: expected a value from 0 to 1"
            )));
        }
        Ok(LookFlag {
            look: Look::Metal { metal, roughness },
            selector,
            text: format!("--metal {}", arg.trim()),
        })
    }

    /// The material this flag gives in place of `old` (see the module docs).
    fn material(&self, old: &MaterialDesc, colour_distance: f32) -> MaterialDesc {
        let name = format!("{} ({})", old.name, self.text);
        let mut m = match self.look {
            Look::Stone(stone) => stone.material_desc(name, colour_distance),
            Look::Metal { metal, roughness } => MaterialDesc {
                name,
                base_color: metal.linear_srgb().clamp(Vec3::ZERO, Vec3::ONE).extend(1.0),
                metallic: 1.0,
                roughness,
                conductor: Some(metal),
                ..MaterialDesc::default()
            },
        };
        m.double_sided = old.double_sided;
        m.priority = old.priority;
        m
    }
}

/// `NAME[=SELECTOR]` → the name and the selector.
fn split<'a>(arg: &'a str, flag: &str) -> Result<(&'a str, Option<Selector>)> {
    match arg.split_once('=') {
        None => Ok((arg.trim(), None)),
        Some((name, sel)) => match Selector::parse(sel) {
            Some(s) => Ok((name.trim(), Some(s))),
            None => Err(Error::Usage(format!(
                "{flag} {arg:?}: empty selector after '=' (NAME=MATERIAL, NAME=mesh:MESH or \
                 NAME=material:MATERIAL)"
            ))),
        },
    }
}

/// The stones `--stone` accepts, for messages (`diamond, sapphire, …`).
pub fn stone_names() -> String {
    STONES.map(Stone::name).join(", ")
}

/// Applies the flags to `desc` (see the module docs); returns what each changed, in flag
/// order. Errors name the flag and the file; a birefringent stone (a crystal) on an open
/// surface is refused as an `extras.iris_crystal` there is
/// ([`crate::scene::validate::check_crystals_closed`]).
pub fn apply(desc: &mut SceneDesc, flags: &[LookFlag]) -> Result<Vec<Applied>> {
    if flags.is_empty() {
        return Ok(Vec::new());
    }
    let rest: Vec<usize> = (0..flags.len())
        .filter(|&i| flags[i].selector.is_none())
        .collect();
    if rest.len() > 1 {
        return Err(Error::Usage(format!(
            "{} and {}: only one --stone or --metal may go without =SELECTOR (it changes \
             every material the others do not name)",
            flags[rest[0]].text, flags[rest[1]].text
        )));
    }
    let (mut by_material, mut by_mesh) = (
        vec![None::<usize>; desc.materials.len()],
        vec![None::<usize>; desc.meshes.len()],
    );
    for (fi, flag) in flags.iter().enumerate() {
        let Some(selector) = &flag.selector else {
            continue;
        };
        let (owners, picked, what) = match pick(desc, selector, &flag.text)? {
            Picked::Materials(ix) => (&mut by_material, ix, "material"),
            Picked::Meshes(ix) => (&mut by_mesh, ix, "mesh"),
        };
        for i in picked {
            if let Some(other) = owners[i].replace(fi) {
                let label = match what {
                    "material" => &desc.materials[i].name,
                    _ => &desc.meshes[i].name,
                };
                return Err(Error::Usage(format!(
                    "{} and {} both name {what} {label} in {}",
                    flags[other].text,
                    flag.text,
                    desc.source.display()
                )));
            }
        }
    }
    if let Some(&r) = rest.first() {
        for (owner, m) in by_material.iter_mut().zip(&desc.materials) {
            if owner.is_none() && !is_emitter(m) {
                *owner = Some(r);
            }
        }
    }
    let mut applied: Vec<Applied> = flags
        .iter()
        .map(|f| Applied {
            flag: f.text.clone(),
            materials: Vec::new(),
            meshes: 0,
        })
        .collect();
    let originals = desc.materials.clone();
    // Materials: changed in place, sized by the meshes that keep them.
    for (mi, owner) in by_material.iter().enumerate() {
        let Some(fi) = *owner else { continue };
        let users: Vec<&MeshDesc> = desc
            .meshes
            .iter()
            .zip(&by_mesh)
            .filter(|(m, o)| m.material == Some(mi) && o.is_none())
            .map(|(m, _)| m)
            .collect();
        let new = flags[fi].material(&originals[mi], colour_distance(&users));
        if !users.is_empty() {
            applied[fi].materials.push(originals[mi].name.clone());
            applied[fi].meshes += users.len();
        }
        desc.materials[mi] = new;
    }
    // Meshes: a new material per (flag, old material), for the meshes a mesh selector
    // names and, under the selector-less flag, the meshes without a material.
    let mesh_flag: Vec<Option<usize>> = desc
        .meshes
        .iter()
        .zip(&by_mesh)
        .map(|(m, o)| match (o, m.material, rest.first()) {
            (Some(fi), _, _) => Some(*fi),
            (None, None, Some(&r)) => Some(r),
            _ => None,
        })
        .collect();
    let default = MaterialDesc::default();
    let mut made: Vec<(usize, Option<usize>, usize)> = Vec::new();
    for mesh_i in 0..desc.meshes.len() {
        let Some(fi) = mesh_flag[mesh_i] else {
            continue;
        };
        let old = desc.meshes[mesh_i].material;
        let index = match made.iter().find(|(f, o, _)| *f == fi && *o == old) {
            Some(&(_, _, index)) => index,
            None => {
                let users: Vec<&MeshDesc> = desc
                    .meshes
                    .iter()
                    .zip(&mesh_flag)
                    .filter(|(m, f)| m.material == old && **f == Some(fi))
                    .map(|(m, _)| m)
                    .collect();
                let base = old.and_then(|i| originals.get(i)).unwrap_or(&default);
                let new = flags[fi].material(base, colour_distance(&users));
                applied[fi].materials.push(base.name.clone());
                desc.materials.push(new);
                made.push((fi, old, desc.materials.len() - 1));
                desc.materials.len() - 1
            }
        };
        desc.meshes[mesh_i].material = Some(index);
        applied[fi].meshes += 1;
    }
    // A birefringent stone is a crystal: its surface must be closed, as a file's is.
    crate::scene::validate::check_crystals_closed(desc)?;
    Ok(applied)
}

/// Whether a material emits light: the selector-less flag leaves it (lights stay lights).
pub fn is_emitter(m: &MaterialDesc) -> bool {
    m.emissive.max_element() > 0.0
}

/// [`COLOUR_DISTANCE`] scaled from the 6.5 mm stone of `iris gem` to the largest
/// bounding-box side among `meshes` (world units); unscaled without geometry.
fn colour_distance(meshes: &[&MeshDesc]) -> f32 {
    let size = meshes
        .iter()
        .filter(|m| !m.positions.is_empty())
        .map(|m| {
            let (lo, hi) = m.positions.iter().fold(
                (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            );
            (hi - lo).max_element()
        })
        .filter(|s| s.is_finite() && *s > 0.0)
        .fold(0.0f32, f32::max);
    if size > 0.0 {
        COLOUR_DISTANCE * size / (DEFAULT_SIZE_MM as f32 * 1e-3)
    } else {
        COLOUR_DISTANCE
    }
}
