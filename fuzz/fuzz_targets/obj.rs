//! OBJ bytes, then `iris::load::fuzz_entry::OBJ_MTL_SEPARATOR`, then MTL bytes → the real
//! OBJ/MTL loader and scene validation, from memory. Any panic, timeout or OOM is a bug,
//! and so is a decoder panic the loader's panic net caught (`iris::load::panic_net`).
#![no_main]
use iris::load::{fuzz_entry, panic_net};
use libfuzzer_sys::fuzz_target;

fuzz_target!(
    // The error of a caught panic names its message and location.
    init: {
        panic_net::show_caught_panics(true);
    },
    |data: &[u8]| {
    let caught = panic_net::caught_count();
    let result = fuzz_entry::load_obj_mtl_bytes(data);
    if panic_net::caught_count() != caught {
        panic!("a decoder panicked (caught by the panic net): {:?}", result.err());
    }
});
