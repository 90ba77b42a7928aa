//! Scene loading: glTF (`load_gltf`, with its fixtures), OBJ/MTL, compressed geometry, bad
//! meshes, material extensions, IOR models, scene-level environments and spectral lights,
//! authored scenes, and the generated assets.

#[path = "../common/mod.rs"]
mod common;

mod authored;
mod bad_meshes;
mod gen_assets;
mod ior_models;
mod iridescence_anisotropy;
mod load_compressed;
mod load_gltf;
mod load_obj;
mod scene_env;
mod spectral_lights;
