// Iris patch: the crate's build script ran bindgen (which needs libclang) on every build;
// the bindings are now pre-generated in src/bindings.rs (IRIS-PATCHES.md), so all that is
// left is the link request. The original script is kept as bindgen.rs.orig.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-lib=embree4");
}
