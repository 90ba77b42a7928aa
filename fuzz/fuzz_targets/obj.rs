//! OBJ bytes, then `iris::load::fuzz_entry::OBJ_MTL_SEPARATOR`, then MTL bytes → the real
//! OBJ/MTL loader and scene validation, from memory. Any panic, timeout or OOM is a bug.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(
    // The default panic hook, so that a decoder panic Iris catches (load::decode) is not
    // turned into an abort by libfuzzer-sys's hook; uncaught panics still crash the run.
    init: {
        let _ = std::panic::take_hook();
    },
    |data: &[u8]| {
    let _ = iris::load::fuzz_entry::load_obj_mtl_bytes(data);
});
