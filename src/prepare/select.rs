//! Naming parts of a scene description for `--stone NAME=SELECTOR` and `--metal
//! NAME=SELECTOR` ([`super::looks`]): the names a loader stored in its labels
//! (`material 4 "Glass"`, `node 3 "Gem" mesh 1 "Cut" primitive 0`, OBJ `group "rim"
//! part 2`), and which materials or meshes a selector picks.
//!
//! Rules: a selector is `material:NAME`, `mesh:NAME` or a bare `NAME`. NAME matches an
//! element when it equals one of the quoted names in its label (a mesh's node name or
//! glTF mesh name, an OBJ object or group name) or the whole label (`material 2` for an
//! unnamed one); exact matches first, else ignoring case. A bare NAME is looked up among
//! material names first and then mesh names; when it names both a material and a mesh
//! and the two choices differ (the meshes using the material are not exactly the meshes
//! named) it is ambiguous, and the error asks for `material:` or `mesh:`. No match is an
//! error listing the names the file has.

use crate::error::{Error, Result};
use crate::scene::desc::SceneDesc;
use std::collections::BTreeSet;

/// What a selector names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Selector {
    /// `NAME`: a material, else a mesh (see the module rules).
    Any(String),
    /// `material:NAME`.
    Material(String),
    /// `mesh:NAME`.
    Mesh(String),
}

impl Selector {
    /// Parses the text after `=`; `None` when the name is empty.
    pub fn parse(s: &str) -> Option<Selector> {
        let s = s.trim();
        let (make, name): (fn(String) -> Selector, &str) =
            if let Some(n) = s.strip_prefix("material:") {
                (Selector::Material, n)
            } else if let Some(n) = s.strip_prefix("mesh:") {
                (Selector::Mesh, n)
            } else {
                (Selector::Any, s)
            };
        let name = name.trim();
        (!name.is_empty()).then(|| make(name.to_string()))
    }
}

/// The elements a selector picked (indices into `SceneDesc::materials` or `::meshes`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Picked {
    /// Materials: every mesh using one changes.
    Materials(Vec<usize>),
    /// Meshes: they get a material of their own.
    Meshes(Vec<usize>),
}

/// The quoted names in a loader's label, unescaped (the loaders quote with Rust's `{:?}`),
/// in order: `node 3 "Gem" mesh 1 "Cut" primitive 0` → `["Gem", "Cut"]`.
pub fn quoted_names(label: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut chars = label.chars();
    while let Some(c) = chars.next() {
        if c != '"' {
            continue;
        }
        let mut name = String::new();
        while let Some(c) = chars.next() {
            match c {
                '"' => break,
                '\\' => match chars.next() {
                    Some('n') => name.push('\n'),
                    Some('t') => name.push('\t'),
                    Some('r') => name.push('\r'),
                    Some('0') => name.push('\0'),
                    Some('u') => {
                        // `\u{XXXX}`
                        let hex: String = chars
                            .by_ref()
                            .skip_while(|&c| c == '{')
                            .take_while(|&c| c != '}')
                            .collect();
                        if let Some(ch) =
                            u32::from_str_radix(&hex, 16).ok().and_then(char::from_u32)
                        {
                            name.push(ch);
                        }
                    }
                    Some(other) => name.push(other),
                    None => break,
                },
                c => name.push(c),
            }
        }
        out.push(name);
    }
    out
}

/// Indices of the labels `name` matches: exactly if any does, else ignoring case.
fn matching<'a>(labels: impl Iterator<Item = &'a str> + Clone, name: &str) -> Vec<usize> {
    let hits = |eq: &dyn Fn(&str) -> bool| -> Vec<usize> {
        labels
            .clone()
            .enumerate()
            .filter(|(_, l)| eq(l) || quoted_names(l).iter().any(|q| eq(q)))
            .map(|(i, _)| i)
            .collect()
    };
    let exact = hits(&|s: &str| s == name);
    if exact.is_empty() {
        hits(&|s: &str| s.eq_ignore_ascii_case(name))
    } else {
        exact
    }
}

/// What `selector` picks in `desc`; `flag` (e.g. `--stone ruby=Gem`) names it in errors.
pub fn pick(desc: &SceneDesc, selector: &Selector, flag: &str) -> Result<Picked> {
    let materials = || desc.materials.iter().map(|m| m.name.as_str());
    let meshes = || desc.meshes.iter().map(|m| m.name.as_str());
    let (name, mats, mesh) = match selector {
        Selector::Material(n) => (n, matching(materials(), n), Vec::new()),
        Selector::Mesh(n) => (n, Vec::new(), matching(meshes(), n)),
        Selector::Any(n) => (n, matching(materials(), n), matching(meshes(), n)),
    };
    match (mats.is_empty(), mesh.is_empty()) {
        (true, true) => Err(no_match(desc, selector, name, flag)),
        (false, true) => Ok(Picked::Materials(mats)),
        (true, false) => Ok(Picked::Meshes(mesh)),
        (false, false) => {
            let users: BTreeSet<usize> = desc
                .meshes
                .iter()
                .enumerate()
                .filter(|(_, m)| m.material.is_some_and(|i| mats.contains(&i)))
                .map(|(i, _)| i)
                .collect();
            if users == mesh.iter().copied().collect() {
                Ok(Picked::Materials(mats))
            } else {
                Err(Error::Usage(format!(
                    "{flag}: {name:?} in {} names both a material ({}) and a mesh ({}) that \
                     does not use only it; write =material:{name} or =mesh:{name}",
                    desc.source.display(),
                    list(mats.iter().map(|&i| desc.materials[i].name.clone())),
                    list(mesh.iter().map(|&i| desc.meshes[i].name.clone())),
                )))
            }
        }
    }
}

/// The error for a selector that matches nothing: the names the file has.
fn no_match(desc: &SceneDesc, selector: &Selector, name: &str, flag: &str) -> Error {
    let names = |labels: Vec<&str>| -> String {
        let set: BTreeSet<String> = labels
            .into_iter()
            .flat_map(|l| {
                let q = quoted_names(l);
                if q.is_empty() {
                    vec![l.to_string()]
                } else {
                    q
                }
            })
            .collect();
        if set.is_empty() {
            "none".to_string()
        } else {
            list(set.into_iter().map(|s| format!("{s:?}")))
        }
    };
    let material_names = names(desc.materials.iter().map(|m| m.name.as_str()).collect());
    let mesh_names = names(desc.meshes.iter().map(|m| m.name.as_str()).collect());
    let what = match selector {
        Selector::Material(_) => "material",
        Selector::Mesh(_) => "mesh",
        Selector::Any(_) => "material or mesh",
    };
    Error::Usage(format!(
        "{flag}: no {what} named {name:?} in {}; materials: {material_names}; meshes: \
         {mesh_names}",
        desc.source.display()
    ))
}

/// Up to 12 items, comma-separated, then "and N more".
fn list(items: impl Iterator<Item = String>) -> String {
    let all: Vec<String> = items.collect();
    let mut s: Vec<String> = all.iter().take(12).cloned().collect();
    if all.len() > 12 {
        s.push(format!("and {} more", all.len() - 12));
    }
    s.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_give_their_quoted_names() {
        assert_eq!(
            quoted_names(r#"node 3 "Gem" mesh 1 "Cut \"A\"" primitive 0"#),
            vec!["Gem".to_string(), "Cut \"A\"".to_string()]
        );
        assert_eq!(quoted_names("material 2"), Vec::<String>::new());
        assert_eq!(
            quoted_names(&format!("material 0 {:?}", "Pavé\tstone")),
            vec!["Pavé\tstone".to_string()]
        );
        assert_eq!(
            quoted_names(r#"material 3 "glass" (lib.mtl line 5)"#),
            vec!["glass".to_string()]
        );
    }

    #[test]
    fn selectors_parse_their_kind() {
        assert_eq!(Selector::parse("Gem"), Some(Selector::Any("Gem".into())));
        assert_eq!(
            Selector::parse("material: Gold "),
            Some(Selector::Material("Gold".into()))
        );
        assert_eq!(
            Selector::parse("mesh:Prongs"),
            Some(Selector::Mesh("Prongs".into()))
        );
        assert_eq!(Selector::parse("mesh:"), None);
        assert_eq!(Selector::parse(" "), None);
    }
}
