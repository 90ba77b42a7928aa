//! Image bytes → the texture decoder (PNG/JPEG/HDR as the glTF and MTL loaders call it)
//! and, for inputs starting like EXR or HDR, the environment-map loader. Any panic,
//! timeout or OOM is a bug, and so is a decoder panic the panic net caught
//! (`iris::load::panic_net`).
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
    let outcome = fuzz_entry::decode_image_bytes(data);
    if panic_net::caught_count() != caught {
        panic!("a decoder panicked (caught by the panic net): {:?}", outcome.texture);
    }
});
