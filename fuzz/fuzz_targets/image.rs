//! Image bytes → the texture decoder (PNG/JPEG/HDR as the glTF and MTL loaders call it)
//! and, for inputs starting like EXR or HDR, the environment-map loader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = iris::load::fuzz_entry::decode_image_bytes(data);
});
