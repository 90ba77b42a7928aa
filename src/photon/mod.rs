//! Photons: light paths traced from the emitters, for photon mapping (`--method photon`,
//! Jensen 1996/2001) and stochastic progressive photon mapping (`--method sppm`, Hachisuka
//! & Jensen 2009 with Knaus & Zwicker 2011's radius sequence).
//!
//! - [`emit`]: where photons start, from every light type, chosen by power, optionally
//!   aimed at the caustic makers; [`flux`]: the lights' flux and usual sampling shapes.
//! - [`aim`]: the caustic makers' bounding spheres and the aimed densities.
//! - [`numbers`]: the photons' emission numbers (digit-permuted Halton over the index).
//! - [`store`]: the compact stored photon (32 bytes, octahedral direction, flags).
//! - [`kdtree`]: the photon map, a kd-tree with k-nearest and radius queries.
//! - [`grid`]: the hash grid for fixed-radius queries, rebuilt every SPPM pass.
//! - [`trace`]: photon paths through the shared per-hit step in importance mode;
//!   [`polarized`]: the same carrying a Stokes vector, through birefringent crystals.
//! - [`probe`]: fixed-seed probes for the render plan (caustic paths, light kept by a bounce).
//!
//! Units: photon power is flux in the lights' units (cd·sr = lm for punctual lights, nit·m²·sr
//! for emitters), so that the sum over all photons emitted, divided by their number, is the
//! scene's emitted power. World space, metres.

pub mod aim;
pub mod emit;
pub mod flux;
pub mod grid;
pub mod kdtree;
pub mod numbers;
pub mod polarized;
pub mod probe;
pub mod store;
pub mod trace;
