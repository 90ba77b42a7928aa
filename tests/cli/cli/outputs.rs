//! Outputs are checked before any work (issue 48 item 2): `-o` (and `--report`, `--plot`,
//! `iris merge -o`) into a missing directory, onto a directory, a device, a read-only file
//! or under a regular file fails at once with an error naming the path, and two outputs
//! naming one file, or an output naming an input, are refused.
//!
//! The renders ask for 10⁶ samples per pixel: a check that came after the render would
//! not finish within [`super::files::HANG`], so an exit with the error proves that nothing
//! was rendered.

use super::files::guarded;
use super::{asset, entries};
use std::path::Path;

/// `iris render` of the prism at 32×24 with 10⁶ samples, plus `extra`.
fn render_args<'a>(scene: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "render", scene, "--size", "32x24", "--method", "path", "--spp", "1000000", "-q",
    ];
    args.extend_from_slice(extra);
    args
}

/// Runs `args` in `dir`, asserts exit code 1 with each of `says` in the message and `dir`
/// unchanged.
fn refused(dir: &Path, args: &[&str], says: &[&str]) {
    let before = entries(dir);
    let (code, err) = guarded(args, dir);
    assert_eq!(code, Some(1), "{args:?}: {err}");
    for s in says {
        assert!(err.contains(s), "{args:?}: {err:?} does not say {s:?}");
    }
    assert_eq!(entries(dir), before, "{args:?} left a file");
}

#[test]
fn unwritable_outputs_fail_before_the_render() {
    let dir = crate::common::scratch_dir("cli_unwritable_outputs");
    let scene = asset("fig4_4_1_prism.glb");
    std::fs::create_dir(dir.join("folder.png")).unwrap();
    std::fs::write(dir.join("file.txt"), b"").unwrap();
    std::fs::write(dir.join("locked.png"), b"old").unwrap();
    let mut perms = std::fs::metadata(dir.join("locked.png"))
        .unwrap()
        .permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(dir.join("locked.png"), perms).unwrap();
    std::os::unix::fs::symlink("/dev/null", dir.join("null.png")).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["-o", "missing/out.png"],
            "missing/out.png: cannot write output: the directory missing does not exist",
        ),
        (
            &["-o", "folder.png"],
            "folder.png: cannot write output: it is a directory",
        ),
        (
            &["-o", "file.txt/out.png"],
            "file.txt/out.png: cannot write output: file.txt is a regular file, not a directory",
        ),
        (
            &["-o", "locked.png"],
            "locked.png: cannot write output: the file is read-only",
        ),
        (
            &["-o", "null.png"],
            "null.png: cannot write output: it is a symbolic link to /dev/null, a character \
             device",
        ),
        (
            &["-o", "out.png", "--report", "missing/r.csv"],
            "missing/r.csv: cannot write output: the directory missing does not exist",
        ),
        (
            &["-o", "out.png", "--plot", "folder.png"],
            "folder.png: cannot write output: it is a directory",
        ),
    ];
    for (extra, says) in cases {
        refused(&dir, &render_args(&scene, extra), &[says]);
    }
    assert_eq!(std::fs::read(dir.join("locked.png")).unwrap(), b"old");
    assert!(Path::new("/dev/null").exists());
}

#[test]
fn a_directory_without_write_permission_is_refused() {
    use std::os::unix::fs::PermissionsExt;
    let dir = crate::common::scratch_dir("cli_readonly_dir");
    let locked = dir.join("locked");
    std::fs::create_dir(&locked).unwrap();
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
    // Root (and CAP_DAC_OVERRIDE) writes through permission bits: then the case cannot
    // happen and is skipped.
    if std::fs::write(locked.join("probe"), b"").is_ok() {
        eprintln!("SKIPPED: this user writes into a read-only directory (root?)");
        let _ = std::fs::remove_file(locked.join("probe"));
        return;
    }
    let scene = asset("fig4_4_1_prism.glb");
    refused(
        &dir,
        &render_args(&scene, &["-o", "locked/out.png"]),
        &["locked/out.png: cannot write output: cannot create a file in locked: "],
    );
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o755)).unwrap();
}

#[test]
fn files_named_twice_are_refused() {
    let dir = crate::common::scratch_dir("cli_named_twice");
    let scene = asset("fig4_4_1_prism.glb");
    let img = iris::image::ImageRgb {
        width: 32,
        height: 24,
        data: vec![glam::Vec3::splat(0.5); 32 * 24],
    };
    iris::output::write_image(&dir.join("ref.exr"), &img, &Default::default()).unwrap();
    std::fs::copy(dir.join("ref.exr"), dir.join("part.exr")).unwrap();
    refused(
        &dir,
        &render_args(&scene, &["-o", "a.png", "--plot", "./a.png"]),
        &["-o a.png and --plot ./a.png name the same file"],
    );
    refused(
        &dir,
        &render_args(&scene, &["-o", "ref.exr", "--reference", "ref.exr"]),
        &["-o ref.exr is the --reference ref.exr: writing it would replace a file"],
    );
    refused(
        &dir,
        &["merge", "part.exr", "-o", "part.exr"],
        &["-o part.exr is the part part.exr"],
    );
    refused(
        &dir,
        &["merge", "part.exr", "-o", "m.exr", "--report", "m.exr"],
        &["-o m.exr and --report m.exr name the same file"],
    );
}
