//! Polarized light: Stokes vectors and Mueller matrices ([`stokes`]), the Mueller matrices of
//! smooth interfaces ([`fresnel`]), the two modes of light in a birefringent crystal
//! ([`crystal`]), where a path meets a crystal's surface ([`interface`]) and how it picks a
//! mode there ([`modes`]). Pure functions and small value types; the transport that uses
//! them is [`crate::integrator`]'s polarized path tracer and the polarized photons of
//! [`crate::photon::polarized`].

pub mod crystal;
pub mod fresnel;
pub mod interface;
pub mod modes;
pub mod stokes;

pub use stokes::{Analyzer, Mueller, Stokes};
