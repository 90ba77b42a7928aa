//! Gives the extension module the RUNPATH of the Embree and Open Image Denoise libraries
//! that the `iris` crate's build script located (its `rpath` metadata, `links =
//! "iris_native"`), so `import iris` finds them as the `iris` binary does.

fn main() {
    println!("cargo:rerun-if-env-changed=DEP_IRIS_NATIVE_RPATH");
    if let Ok(dirs) = std::env::var("DEP_IRIS_NATIVE_RPATH") {
        for dir in dirs.split(':').filter(|d| !d.is_empty()) {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
        }
    }
}
