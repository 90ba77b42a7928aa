//! Every `iris render` flag against the render identity (issue 48): a flag that changes
//! the image must change [`iris::app::shard_id::image_options`], one that does not must
//! leave it alone, and a flag these tables do not name fails the test (classify it here,
//! and in `image_options`).

use clap::CommandFactory;
use iris::app::shard_id::image_options;

/// Flags that change the image, each with a value other than its default.
const IMAGE: &[(&str, &str)] = &[
    ("size", "64x48"),
    ("method", "path"),
    ("max-depth", "7"),
    ("accel", "bvh"),
    ("seed", "9"),
    ("sampler", "independent"),
    ("camera", "0"),
    ("camera-look-at", "0,0,5:0,0,0:40"),
    ("turn", "1/4"),
    ("env", "none"),
    ("fog", "density=0.3"),
    ("spectral", "on"),
    ("polarization", "off"),
    ("polarizer", "90"),
    ("studio", "jeweller"),
    ("ground", "off"),
    ("photons", "1000"),
    ("radius", "0.1"),
    ("alpha", "0.5"),
    ("photon-rr", "lobe"),
    ("caustics", "light"),
    ("view", "top"),
    ("background", "transparent"),
    ("stone", "sapphire"),
    ("metal", "gold"),
    ("metal-roughness", "0.5"),
    ("adaptive", "off"),
];

/// Flags that change the image only beside another flag, with that flag.
const CONTEXT: &[(&str, &[&str])] = &[("metal-roughness", &["--metal", "gold"])];

/// Flags that do not change the image of a fixed count (the counts and the budget are the
/// identity's `total`; display, measuring and output flags act on the written file).
const NOT_IMAGE: &[(&str, &str)] = &[
    ("output", "x.exr"),
    ("spp", "8"),
    ("passes", "8"),
    ("time", "5"),
    ("target-error", "0.1"),
    ("checkpoint", "2"),
    ("threads", "1"),
    ("exposure", "1"),
    ("tonemap", "clamp"),
    ("reference", "r.exr"),
    ("report", "r.csv"),
    ("plot", "p.png"),
    ("quiet", ""),
    ("explain", ""),
    ("shard", "1/2"),
    ("denoise", "off"),
];

/// The options of `iris render s.glb --spp 4 --passes 4 ARGS…`: a fixed count, so that
/// budget flags do not switch an open budget on or off.
/// A flag in `extra` replaces the base's.
fn options(extra: &[&str]) -> String {
    let mut args = vec!["s.glb".to_string()];
    for (flag, value) in [("--spp", "4"), ("--passes", "4")] {
        if !extra.contains(&flag) {
            args.extend([flag.to_string(), value.to_string()]);
        }
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    match iris::cli::parse_render(&args) {
        Ok(o) => image_options(&o),
        Err(e) => panic!("{extra:?}: {e}"),
    }
}

fn args<'a>(flag: &'a str, value: &'a str) -> Vec<&'a str> {
    let mut a = vec![flag];
    if !value.is_empty() {
        a.push(value);
    }
    a
}

#[test]
fn every_render_flag_is_classified_for_the_identity() {
    let cli = iris::cli::Cli::command();
    let render = cli
        .get_subcommands()
        .find(|c| c.get_name() == "render")
        .expect("iris render");
    let base = options(&[]);
    let mut seen = 0;
    for arg in render.get_arguments() {
        let Some(long) = arg.get_long() else {
            continue;
        };
        if matches!(long, "help" | "version" | "verbose") {
            continue;
        }
        seen += 1;
        let flag = format!("--{long}");
        if let Some((_, v)) = IMAGE.iter().find(|(f, _)| *f == long) {
            let context: &[&str] = CONTEXT
                .iter()
                .find(|(f, _)| *f == long)
                .map_or(&[], |c| c.1);
            let without = options(context);
            let with = options(&[context, &args(&flag, v)].concat());
            assert_ne!(
                with, without,
                "{flag} {v} changes the image but not the identity"
            );
        } else if let Some((_, v)) = NOT_IMAGE.iter().find(|(f, _)| *f == long) {
            let with = options(&args(&flag, v));
            assert_eq!(with, base, "{flag} {v} does not change the image");
        } else {
            panic!(
                "{flag} is new: say whether it changes the image (IMAGE or NOT_IMAGE in \
                 tests/farm/shards/identity_flags.rs, and in shard_id::image_options)"
            );
        }
    }
    assert_eq!(seen, IMAGE.len() + NOT_IMAGE.len(), "a listed flag is gone");
}
