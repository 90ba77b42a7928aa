//! glTF/GLB bytes → the real glTF loader and scene validation, from memory
//! (external URIs resolve to nothing). Any panic, timeout or OOM is a bug.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(
    // The default panic hook, so that a decoder panic Iris catches (load::decode) is not
    // turned into an abort by libfuzzer-sys's hook; uncaught panics still crash the run.
    init: {
        let _ = std::panic::take_hook();
    },
    |data: &[u8]| {
    let _ = iris::load::fuzz_entry::load_gltf_bytes(data);
});
