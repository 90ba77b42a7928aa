//! OBJ bytes, then `iris::load::fuzz_entry::OBJ_MTL_SEPARATOR`, then MTL bytes → the real
//! OBJ/MTL loader and scene validation, from memory. Any panic, timeout or OOM is a bug.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = iris::load::fuzz_entry::load_obj_mtl_bytes(data);
});
