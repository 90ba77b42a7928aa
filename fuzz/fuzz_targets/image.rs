//! Image bytes → the texture decoder (PNG/JPEG/HDR as the glTF and MTL loaders call it)
//! and, for inputs starting like EXR or HDR, the environment-map loader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(
    // The default panic hook, so that a decoder panic Iris catches (load::decode) is not
    // turned into an abort by libfuzzer-sys's hook; uncaught panics still crash the run.
    init: {
        let _ = std::panic::take_hook();
    },
    |data: &[u8]| {
    let _ = iris::load::fuzz_entry::decode_image_bytes(data);
});
