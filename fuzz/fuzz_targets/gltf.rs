//! glTF/GLB bytes → the real glTF loader and scene validation, from memory
//! (external URIs resolve to nothing). Any panic, timeout or OOM is a bug.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = iris::load::fuzz_entry::load_gltf_bytes(data);
});
