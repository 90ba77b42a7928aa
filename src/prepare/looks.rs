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
//! - `--stone NAME` without a selector changes the **stones** ([`stones`]): the materials no
//!   selector named that are transmissive volumes or crystals; in a file with none, the
//!   materials whose surfaces are closed (a gem model with a viewer's opaque placeholder),
//!   and meshes without a material whose surface is closed; in a file with neither, every
//!   material. A floor, a table or a backdrop (open surfaces, opaque) stays as it was; the
//!   note says which materials changed;
//! - `--metal NAME` without a selector, and either flag with `=*`, changes every material
//!   no selector named except emissive ones (lights stay lights), and gives meshes without
//!   a material one; so `--stone diamond --metal gold=Setting` makes the material
//!   `Setting` gold and the stones diamond, and `--stone diamond=*` makes everything that
//!   does not glow diamond;
//! - at most one flag goes without a selector or with `=*`;
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
    /// Which materials or meshes it changes.
    pub target: Target,
    /// The flag as written, for messages and material names (`--stone ruby=Gem`).
    pub text: String,
}

/// Which materials or meshes a flag changes (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// `--stone NAME`: the stones no selector named ([`stones`]).
    Stones,
    /// `--metal NAME` or `NAME=*`: every material no selector named, lights aside.
    Every,
    /// `NAME=SELECTOR`.
    Named(Selector),
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
    /// For a flag without a selector, which materials it took (the stones or every one).
    pub scope: Option<&'static str>,
}

impl std::fmt::Display for Applied {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let flag = match self.scope {
            Some(scope) => format!("{} ({scope})", self.flag),
            None => self.flag.clone(),
        };
        if self.materials.is_empty() {
            return write!(f, "{flag}: changes no material on a mesh");
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
        write!(f, "{flag}: {}{more} ({meshes})", shown.join(", "))
    }
}

impl LookFlag {
    /// Parses `--stone NAME[=SELECTOR]`; unknown stones list the known ones.
    pub fn stone(arg: &str) -> Result<LookFlag> {
        let (name, target) = split(arg, "--stone")?;
        let stone = Stone::parse(name)?;
        Ok(LookFlag {
            look: Look::Stone(stone),
            target: target.unwrap_or(Target::Stones),
            text: format!("--stone {}", arg.trim()),
        })
    }

    /// Parses `--metal NAME[=SELECTOR]` with the `--metal-roughness` value (in [0, 1]).
    pub fn metal(arg: &str, roughness: f32) -> Result<LookFlag> {
        let (name, target) = split(arg, "--metal")?;
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
            target: target.unwrap_or(Target::Every),
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

/// `NAME[=SELECTOR]` → the name and the target (`None` without `=`).
fn split<'a>(arg: &'a str, flag: &str) -> Result<(&'a str, Option<Target>)> {
    match arg.split_once('=') {
        None => Ok((arg.trim(), None)),
        Some((name, sel)) if sel.trim() == "*" => Ok((name.trim(), Some(Target::Every))),
        Some((name, sel)) => match Selector::parse(sel) {
            Some(s) => Ok((name.trim(), Some(Target::Named(s)))),
            None => Err(Error::Usage(format!(
                "{flag} {arg:?}: empty selector after '=' (NAME=MATERIAL, NAME=mesh:MESH, \
                 NAME=material:MATERIAL or NAME=* for every material)"
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
        .filter(|&i| !matches!(flags[i].target, Target::Named(_)))
        .collect();
    if rest.len() > 1 {
        return Err(Error::Usage(format!(
            "{} and {}: only one --stone or --metal may go without =SELECTOR or with =* (it \
             changes the stones, or every material, the others do not name)",
            flags[rest[0]].text, flags[rest[1]].text
        )));
    }
    let (mut by_material, by_mesh) = named_owners(desc, flags)?;
    // The flag without a selector: its materials, and whether it also takes the meshes
    // without a material (closed ones only, under the stones' second rule).
    let scope = rest
        .first()
        .map(|&r| (r, scope(desc, &flags[r].target, &by_material)));
    if let Some((r, (chosen, _))) = &scope {
        for &mi in chosen {
            by_material[mi] = Some(*r);
        }
    }
    let mut applied: Vec<Applied> = flags
        .iter()
        .map(|f| Applied {
            flag: f.text.clone(),
            materials: Vec::new(),
            meshes: 0,
            scope: match f.target {
                Target::Stones => Some("no selector: the stones; =* for every material"),
                Target::Every => Some("every material"),
                Target::Named(_) => None,
            },
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
        .map(|(m, o)| match (o, m.material, &scope) {
            (Some(fi), _, _) => Some(*fi),
            (None, None, Some((r, (_, bare)))) if bare.takes(m) => Some(*r),
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

/// For each material and each mesh, the flag (index into `flags`) that names it, if any.
type Owners = (Vec<Option<usize>>, Vec<Option<usize>>);

/// The flag that names each material and each mesh by its selector; an error when two
/// name the same one.
fn named_owners(desc: &SceneDesc, flags: &[LookFlag]) -> Result<Owners> {
    let (mut by_material, mut by_mesh) = (
        vec![None::<usize>; desc.materials.len()],
        vec![None::<usize>; desc.meshes.len()],
    );
    for (fi, flag) in flags.iter().enumerate() {
        let Target::Named(selector) = &flag.target else {
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
    Ok((by_material, by_mesh))
}

/// Which meshes without a material the flag without a selector takes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Bare {
    /// None.
    None,
    /// Those whose surface is closed.
    Closed,
    /// All.
    All,
}

impl Bare {
    fn takes(self, mesh: &MeshDesc) -> bool {
        match self {
            Bare::None => false,
            Bare::Closed => crate::scene::validate::mesh_is_closed(mesh),
            Bare::All => true,
        }
    }
}

/// The materials the flag without a selector changes (those no selector named,
/// `by_material[i]` is `None`) and which meshes without a material it takes: every
/// non-emissive material for [`Target::Every`]; for [`Target::Stones`] the stones
/// ([`stones`]).
fn scope(desc: &SceneDesc, target: &Target, by_material: &[Option<usize>]) -> (Vec<usize>, Bare) {
    let free: Vec<usize> = (0..desc.materials.len())
        .filter(|&i| by_material[i].is_none() && !is_emitter(&desc.materials[i]))
        .collect();
    match target {
        Target::Stones => stones(desc, &free),
        _ => (free, Bare::All),
    }
}

/// The stones among the materials `free`: the transmissive volumes (KHR transmission
/// and a volume) and crystals; in a file with none, the materials whose surfaces are
/// closed, with the closed meshes that have no material; with neither, all of them.
fn stones(desc: &SceneDesc, free: &[usize]) -> (Vec<usize>, Bare) {
    let volumes: Vec<usize> = free
        .iter()
        .copied()
        .filter(|&i| {
            let m = &desc.materials[i];
            m.crystal.is_some() || (m.transmission > 0.0 && m.thickness > 0.0)
        })
        .collect();
    if !volumes.is_empty() {
        return (volumes, Bare::None);
    }
    let closed: Vec<usize> = free
        .iter()
        .copied()
        .filter(|&i| {
            desc.meshes.iter().any(|m| m.material == Some(i))
                && crate::scene::validate::is_closed(desc, i)
        })
        .collect();
    let bare_closed = desc
        .meshes
        .iter()
        .any(|m| m.material.is_none() && Bare::Closed.takes(m));
    if !closed.is_empty() || bare_closed {
        return (closed, Bare::Closed);
    }
    (free.to_vec(), Bare::All)
}

/// The meshes of `desc` a `--stone NAME` without a selector would change: those with a
/// stone material ([`stones`], every material but the lights free), and the meshes without
/// a material it takes. The live view orbits and frames them ([`super::subject`]).
pub fn stone_meshes(desc: &SceneDesc) -> Vec<usize> {
    let free: Vec<usize> = (0..desc.materials.len())
        .filter(|&i| !is_emitter(&desc.materials[i]))
        .collect();
    let (materials, bare) = stones(desc, &free);
    (0..desc.meshes.len())
        .filter(|&i| match desc.meshes[i].material {
            Some(m) => materials.contains(&m),
            None => bare.takes(&desc.meshes[i]),
        })
        .collect()
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
