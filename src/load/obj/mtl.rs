//! MTL parser: text → raw per-material records, with line numbers.
//!
//! Iris parses MTL itself instead of using `tobj::load_mtl_buf`: tobj 4.0.5 panics on a
//! colour with fewer than three components (`Kd 0.5`, legal MTL meaning grey), loses line
//! numbers and leaves `Tf`, `Tr` and the Iris keys as unparsed strings.
//!
//! Values are stored as written (colours are linear RGB, no conversion); the mapping to
//! [`MaterialDesc`](crate::material::MaterialDesc) lives in `material.rs`.
//!
//! Grammar accepted (one statement per line, `#` starts a comment):
//! - `newmtl NAME`; statements before the first `newmtl` are ignored with a warning;
//! - `Kd|Ks|Ke|Tf r [g b]` (one value means grey); `spectral`/`xyz` forms are unsupported;
//! - `Ns|Ni|d|Tr|Pr|Pm value` (`d -halo value` reads the value), `illum n`;
//! - `map_Kd [options] FILE` (options like `-s 1 1 1` are skipped and reported);
//! - the Iris keys `cauchy_b B` and `cauchy_c C` (both or neither, numbers; see
//!   `ExplicitIor`) and `iris_glass NAME` (a built-in Sellmeier glass,
//!   `spectrum::ior::KNOWN_NAMES`, case-insensitive, the rest of the line so
//!   `iris_glass fused silica` works); `iris_glass` may also be written as a comment,
//!   `# iris_glass NAME`, which other MTL readers skip silently;
//! - the Iris key `iris_spectrum D65|sun|blackbody K` (case-insensitive, K in 1000–40000):
//!   the spectral shape of the `Ke` emission (see `EmissionSpectrum`);
//! - `Ka`/`map_Ka` (ambient: meaningless for a path tracer) are ignored silently; every
//!   other key is recorded in [`RawMtl::unsupported`] for the loader's single warning.
//!
//! Errors: unparsable numbers → `Parse` naming the MTL line; a malformed or lone
//! `cauchy_b`/`cauchy_c`, an unknown or missing `iris_glass` name, or both `iris_glass` and
//! the Cauchy keys on one material, or a bad `iris_spectrum` → `InvalidValue` naming the
//! material and the line.

use crate::error::{LoadError, LoadErrorKind};
use crate::spectrum::EmissionSpectrum;
use glam::Vec3;
use std::path::Path;

/// One `newmtl` block as written.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct RawMtl {
    /// The name after `newmtl`.
    pub name: String,
    /// Line of the `newmtl` statement (1-based).
    pub line: usize,
    /// Diffuse colour `Kd`.
    pub kd: Option<Vec3>,
    /// Specular colour `Ks`.
    pub ks: Option<Vec3>,
    /// Emissive colour `Ke`.
    pub ke: Option<Vec3>,
    /// Transmission filter `Tf` (read, deliberately not used: see `material.rs`).
    pub tf: Option<Vec3>,
    /// Specular exponent `Ns`.
    pub ns: Option<f32>,
    /// Optical density (IOR) `Ni`.
    pub ni: Option<f32>,
    /// Dissolve `d` (1 = opaque).
    pub d: Option<f32>,
    /// Transparency `Tr` (= 1 − d).
    pub tr: Option<f32>,
    /// PBR extension roughness `Pr`.
    pub pr: Option<f32>,
    /// PBR extension metallic `Pm`.
    pub pm: Option<f32>,
    /// Illumination model `illum`.
    pub illum: Option<u32>,
    /// Diffuse texture file (as written, relative to the MTL file).
    pub map_kd: Option<String>,
    /// Iris Cauchy model `(b, c)`, c in µm².
    pub cauchy: Option<(f32, f32)>,
    /// Iris `iris_glass` name as written (already checked against the known names).
    pub glass: Option<String>,
    /// Iris `iris_spectrum`: the spectral shape of `Ke`.
    pub spectrum: Option<EmissionSpectrum>,
    /// Iris `iris_priority`: nested-media priority (default 0).
    pub priority: Option<i32>,
    /// Keys seen and not used, in order of appearance, without duplicates.
    pub unsupported: Vec<String>,
}

/// A parsed MTL file.
#[derive(Debug, Default)]
pub(super) struct MtlLib {
    /// Materials in file order (a repeated name keeps both; the later one wins in `usemtl`).
    pub materials: Vec<RawMtl>,
    /// Notes for the scene's warnings.
    pub warnings: Vec<String>,
}

/// Parses MTL text read from `path`.
pub(super) fn parse_mtl(path: &Path, text: &str) -> Result<MtlLib, LoadError> {
    let mut lib = MtlLib::default();
    let mut current: Option<RawMtl> = None;
    let mut cauchy = (None, None);
    let mut stray = 0usize;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = glass_comment(raw).unwrap_or_else(|| raw.split('#').next().unwrap_or(""));
        let words: Vec<&str> = content.split_whitespace().collect();
        let Some((&key, args)) = words.split_first() else {
            continue;
        };
        if key == "newmtl" {
            if let Some(done) = current.take() {
                lib.materials.push(finish(path, done, cauchy)?);
            }
            cauchy = (None, None);
            let name = content.trim_start().strip_prefix(key).unwrap_or("").trim();
            if name.is_empty() {
                return Err(perr(path, line, "`newmtl` without a name".into()));
            }
            current = Some(RawMtl {
                name: name.to_string(),
                line,
                ..RawMtl::default()
            });
            continue;
        }
        let Some(mtl) = current.as_mut() else {
            stray += 1;
            continue;
        };
        let at = Ctx { path, line, key };
        match key {
            "Kd" => mtl.kd = at.color(args, &mut mtl.unsupported)?,
            "Ks" => mtl.ks = at.color(args, &mut mtl.unsupported)?,
            "Ke" => mtl.ke = at.color(args, &mut mtl.unsupported)?,
            "Tf" => mtl.tf = at.color(args, &mut mtl.unsupported)?,
            "Ns" => mtl.ns = Some(at.scalar(args)?),
            "Ni" => mtl.ni = Some(at.scalar(args)?),
            "d" => mtl.d = Some(at.scalar(args.strip_prefix(&["-halo"]).unwrap_or(args))?),
            "Tr" => mtl.tr = Some(at.scalar(args)?),
            "Pr" => mtl.pr = Some(at.scalar(args)?),
            "Pm" => mtl.pm = Some(at.scalar(args)?),
            "illum" => mtl.illum = Some(at.integer(args)?),
            "map_Kd" => mtl.map_kd = texture_file(args, &mut mtl.unsupported),
            "cauchy_b" => cauchy.0 = Some(at.cauchy(&mtl.name, args)?),
            "cauchy_c" => cauchy.1 = Some(at.cauchy(&mtl.name, args)?),
            "iris_glass" => mtl.glass = Some(at.glass(&mtl.name, args)?),
            "iris_spectrum" => mtl.spectrum = Some(at.spectrum(&mtl.name, args)?),
            "iris_priority" => mtl.priority = Some(at.priority(&mtl.name, args)?),
            "Ka" | "map_Ka" => {}
            other => note(&mut mtl.unsupported, other),
        }
    }
    if let Some(done) = current.take() {
        lib.materials.push(finish(path, done, cauchy)?);
    }
    if stray > 0 {
        lib.warnings.push(format!(
            "{}: {stray} statement(s) before the first `newmtl` ignored",
            path.display()
        ));
    }
    Ok(lib)
}

/// The statement inside a comment `# iris_glass NAME`, if the line is one.
fn glass_comment(raw: &str) -> Option<&str> {
    let body = raw.trim_start().strip_prefix('#')?.trim_start();
    let rest = body.strip_prefix("iris_glass")?;
    rest.starts_with(char::is_whitespace).then_some(body)
}

/// Closes a material: the Cauchy keys must come as a pair, and not with `iris_glass`.
fn finish(
    path: &Path,
    mut mtl: RawMtl,
    cauchy: (Option<f32>, Option<f32>),
) -> Result<RawMtl, LoadError> {
    mtl.cauchy = match cauchy {
        (Some(b), Some(c)) => Some((b, c)),
        (None, None) => None,
        (b, _) => {
            let (have, missing) = if b.is_some() {
                ("cauchy_b", "cauchy_c")
            } else {
                ("cauchy_c", "cauchy_b")
            };
            return Err(material_error(
                path,
                (&mtl.name, mtl.line),
                format!("`{have}` given without `{missing}` (the Cauchy model needs both)"),
            ));
        }
    };
    if mtl.glass.is_some() && mtl.cauchy.is_some() {
        return Err(material_error(
            path,
            (&mtl.name, mtl.line),
            "both `iris_glass` and `cauchy_b`/`cauchy_c` given; keep one IOR model",
        ));
    }
    Ok(mtl)
}

fn note(list: &mut Vec<String>, key: &str) {
    let key: String = key.chars().take(24).collect();
    if !list.contains(&key) && list.len() < 16 {
        list.push(key);
    }
}

fn perr(path: &Path, line: usize, detail: String) -> LoadError {
    LoadError::new(path, format!("line {line}"), LoadErrorKind::Parse, detail)
}

/// An invalid value in material `name` defined at `line` of the MTL file `path`.
fn material_error(
    path: &Path,
    (name, line): (&str, usize),
    problem: impl Into<String>,
) -> LoadError {
    LoadError::new(
        path,
        format!("material \"{name}\" (line {line})"),
        LoadErrorKind::InvalidValue,
        problem,
    )
}

/// Where a statement is, for error messages.
struct Ctx<'a> {
    path: &'a Path,
    line: usize,
    key: &'a str,
}

impl Ctx<'_> {
    /// An invalid value in `material`, at this statement's line.
    fn material_error(&self, material: &str, problem: impl Into<String>) -> LoadError {
        material_error(self.path, (material, self.line), problem)
    }

    fn number(&self, word: &str) -> Result<f32, LoadError> {
        word.parse::<f32>().map_err(|_| {
            perr(
                self.path,
                self.line,
                format!("`{}`: `{word}` is not a number", self.key),
            )
        })
    }

    /// `r`, or `r g b`; the `spectral` and `xyz` forms are noted as unsupported.
    fn color(
        &self,
        args: &[&str],
        unsupported: &mut Vec<String>,
    ) -> Result<Option<Vec3>, LoadError> {
        match args {
            [r] => Ok(Some(Vec3::splat(self.number(r)?))),
            [r, g, b] => Ok(Some(Vec3::new(
                self.number(r)?,
                self.number(g)?,
                self.number(b)?,
            ))),
            [form, ..] if *form == "spectral" || *form == "xyz" => {
                note(unsupported, &format!("{} {form}", self.key));
                Ok(None)
            }
            _ => Err(perr(
                self.path,
                self.line,
                format!(
                    "`{}` expects r [g b], found {} values",
                    self.key,
                    args.len()
                ),
            )),
        }
    }

    fn scalar(&self, args: &[&str]) -> Result<f32, LoadError> {
        match args {
            [v] => self.number(v),
            _ => Err(perr(
                self.path,
                self.line,
                format!(
                    "`{}` expects one number, found {} values",
                    self.key,
                    args.len()
                ),
            )),
        }
    }

    fn integer(&self, args: &[&str]) -> Result<u32, LoadError> {
        match args {
            [v] => v.parse::<u32>().map_err(|_| {
                perr(
                    self.path,
                    self.line,
                    format!("`{}`: `{v}` is not a non-negative integer", self.key),
                )
            }),
            _ => Err(perr(
                self.path,
                self.line,
                format!(
                    "`{}` expects one integer, found {} values",
                    self.key,
                    args.len()
                ),
            )),
        }
    }

    /// A Cauchy coefficient: a malformed value names the material.
    fn cauchy(&self, material: &str, args: &[&str]) -> Result<f32, LoadError> {
        match args {
            [v] => v.parse::<f32>().ok(),
            _ => None,
        }
        .ok_or_else(|| {
            self.material_error(
                material,
                format!(
                    "`{}` expects one number, found `{}`",
                    self.key,
                    args.join(" ")
                ),
            )
        })
    }
}

impl Ctx<'_> {
    /// An `iris_glass` name (the rest of the statement): an unknown one names the material
    /// and this line, and lists the known names.
    fn glass(&self, material: &str, args: &[&str]) -> Result<String, LoadError> {
        let name = args.join(" ");
        let problem = if args.is_empty() {
            format!(
                "`{}` expects a glass name, one of {}",
                self.key,
                crate::spectrum::ior::KNOWN_NAMES.join(", ")
            )
        } else {
            match crate::spectrum::IorModel::named(&name) {
                Ok(_) => return Ok(name),
                Err(e) => format!("`{}`: {e}", self.key),
            }
        };
        Err(self.material_error(material, problem))
    }
}

impl Ctx<'_> {
    /// An `iris_priority` value: one integer in ±1,000,000.
    fn priority(&self, material: &str, args: &[&str]) -> Result<i32, LoadError> {
        match args {
            [v] => v.parse::<i32>().ok().filter(|p| p.abs() <= 1_000_000),
            _ => None,
        }
        .ok_or_else(|| {
            self.material_error(
                material,
                format!(
                    "`{}` takes one integer in ±1000000, found `{}`",
                    self.key,
                    args.join(" ")
                ),
            )
        })
    }

    /// An `iris_spectrum` value; a bad one names the material and this line.
    fn spectrum(&self, material: &str, args: &[&str]) -> Result<EmissionSpectrum, LoadError> {
        EmissionSpectrum::parse_words(args)
            .map_err(|e| self.material_error(material, format!("`{}`: {e}", self.key)))
    }
}

/// Skips `map_Kd` options (`-s 1 1 1`, `-clamp on`, …) and returns the file name.
fn texture_file(args: &[&str], unsupported: &mut Vec<String>) -> Option<String> {
    let mut rest = args;
    while let Some((&opt, tail)) = rest.split_first() {
        let fixed = match opt {
            "-blendu" | "-blendv" | "-bm" | "-boost" | "-cc" | "-clamp" | "-imfchan"
            | "-texres" | "-type" => 1,
            "-mm" => 2,
            "-o" | "-s" | "-t" => {
                // 1 to 3 numbers.
                tail.iter()
                    .take(3)
                    .take_while(|w| w.parse::<f32>().is_ok())
                    .count()
            }
            _ => break,
        };
        note(unsupported, &format!("map_Kd {opt}"));
        rest = tail.get(fixed..).unwrap_or(&[]);
    }
    if rest.is_empty() {
        note(unsupported, "map_Kd without a file");
        return None;
    }
    // Windows exporters write backslashes.
    Some(rest.join(" ").replace('\\', "/"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<MtlLib, LoadError> {
        parse_mtl(Path::new("t.mtl"), text)
    }

    #[test]
    fn reads_values_and_grey_colours() {
        let lib = parse("newmtl a\nKd 0.5\nKs 0.1 0.2 0.3 # c\nNi 1.33\nillum 7\nd -halo 0.5\n")
            .expect("parses");
        let a = &lib.materials[0];
        assert_eq!(a.kd, Some(Vec3::splat(0.5)));
        assert_eq!(a.ks, Some(Vec3::new(0.1, 0.2, 0.3)));
        assert_eq!((a.ni, a.illum, a.d), (Some(1.33), Some(7), Some(0.5)));
    }

    #[test]
    fn bad_number_names_line() {
        let e = parse("newmtl a\n\nKd 1 x 2\n").expect_err("bad");
        assert_eq!(e.kind, LoadErrorKind::Parse);
        assert_eq!(e.element, "line 3");
        let e = parse("newmtl a\nKd 1 2\n").expect_err("two values");
        assert_eq!(e.element, "line 2");
    }

    #[test]
    fn cauchy_pair() {
        let lib = parse("newmtl g\ncauchy_b 1.5\ncauchy_c 0.0042\n").expect("parses");
        assert_eq!(lib.materials[0].cauchy, Some((1.5, 0.0042)));
        let e = parse("newmtl g\ncauchy_b 1.5\n").expect_err("lone");
        assert_eq!(e.kind, LoadErrorKind::InvalidValue);
        assert!(e.to_string().contains("\"g\""));
        let e = parse("newmtl g\ncauchy_b x\ncauchy_c 1\n").expect_err("bad");
        assert_eq!(e.kind, LoadErrorKind::InvalidValue);
    }

    #[test]
    fn iris_glass_key_and_comment() {
        let lib = parse("newmtl g\niris_glass N-BK7\nnewmtl s\n  # iris_glass fused silica\n")
            .expect("parses");
        assert_eq!(lib.materials[0].glass.as_deref(), Some("N-BK7"));
        assert_eq!(lib.materials[1].glass.as_deref(), Some("fused silica"));
        // An ordinary comment that merely mentions the key is still a comment.
        let lib = parse("newmtl g\n# iris_glassy N-BK7\n#see iris_glass docs\n").expect("parses");
        assert_eq!(lib.materials[0].glass, None);
        let e = parse("newmtl g\nKd 1\n\niris_glass unobtainium\n").expect_err("unknown");
        assert_eq!(e.kind, LoadErrorKind::InvalidValue);
        let text = e.to_string();
        assert!(
            text.contains("\"g\" (line 4)") && text.contains("N-SF11"),
            "{text}"
        );
        let e = parse("newmtl g\niris_glass\n").expect_err("no name");
        assert!(e.to_string().contains("line 2"), "{e}");
        let e =
            parse("newmtl g\niris_glass water\ncauchy_b 1.5\ncauchy_c 0.0042\n").expect_err("both");
        assert!(e.to_string().contains("both"), "{e}");
    }

    #[test]
    fn texture_options_are_skipped() {
        let lib =
            parse("newmtl t\nmap_Kd -s 2 2 1 -clamp on tex\\wood grain.png\nmap_Bump b.png\n")
                .expect("parses");
        let t = &lib.materials[0];
        assert_eq!(t.map_kd.as_deref(), Some("tex/wood grain.png"));
        assert!(t.unsupported.contains(&"map_Bump".to_string()));
        assert!(t.unsupported.contains(&"map_Kd -s".to_string()));
    }
}
