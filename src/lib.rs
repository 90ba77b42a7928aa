//! # Iris
//!
//! A spectral renderer for glass, gems and caustics.
//!
//! ## Conventions (enforced by [`interaction`], the one intersection layer)
//! - World space is right-handed, +Y up, metres (glTF).
//! - Triangles wind counter-clockwise seen from outside; the geometric normal
//!   `(p1-p0)×(p2-p0)` points **out of the object** and is never flipped.
//! - A ray enters an object when `dot(direction, ng) < 0` (`front_face`), and exits otherwise.
//! - Backends ([`accel`]) take `t_min = 0` and return only `t`, triangle id and barycentrics.
//! - Every secondary ray is offset by [`interaction::SurfaceHit::spawn_ray`] /
//!   [`interaction::SurfaceHit::spawn_ray_to`] and nowhere else; no other module adds an
//!   epsilon.
//!
//! ## Pipeline
//! file → [`scene::desc::SceneDesc`] (loaders in [`load`]) → validation → the one
//! preparation ([`prepare`]: environment, camera, lights, floor written into the
//! description) → immutable [`scene::Scene`] → the plan ([`plan`], `--method auto`) → an
//! [`integrator::Integrator`] rendering through the one progressive driver and film
//! ([`render`]) → denoising of PNG previews ([`denoise`], Open Image Denoise with auxiliary
//! albedo and normals) → PNG/EXR ([`output`]). Commands live in [`app`]. The film's sums
//! are exact ([`image::fixed`]), so a render cut into shards ([`app::shard`]) merges
//! bit for bit ([`app::merge`]).
//!
//! `unsafe` appears only in `accel/embree/` and `denoise/oidn.rs`, the two C FFI layers
//! (Embree; Open Image Denoise): the crate denies `unsafe_code` in every build, and only
//! the declarations of those two modules allow it.
#![warn(missing_docs)]
#![deny(unsafe_code)]

pub mod accel;
pub mod app;
pub mod assets;
pub mod authoring;
pub mod bsdf;
pub mod camera;
pub mod cli;
pub mod denoise;
pub mod error;
pub mod fileio;
pub mod framing;
pub mod image;
pub mod integrator;
pub mod interaction;
pub mod interrupt;
pub mod light;
pub mod load;
pub mod material;
pub mod math;
pub mod measure;
pub mod medium_stack;
pub mod optics;
pub mod output;
pub mod photon;
pub mod plan;
pub mod polar;
pub mod prepare;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod shading;
pub mod spectrum;
pub mod studio;
pub mod view;
pub mod volume;

pub use error::{Error, LoadError, LoadErrorKind, Result};
