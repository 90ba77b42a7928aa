//! What the path tracer (`--method path`) renders and how: its declaration for the method
//! registry ([`crate::integrator::Method::caps`]).

use crate::integrator::capability::{Capabilities, Photons, Support, Units};

/// What `--method path` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "path",
    purpose: "all the light, soft and exact; caustics come slowly and noisy",
    units: Units::Samples,
    photons: Photons::None,
    media: Support::Yes,
    orthographic: Support::Yes,
    polarization: Support::Yes,
    rayleigh_spectral: Support::Yes,
    lanes: Support::Yes,
    shards: Support::Yes,
    adaptive: Support::Yes,
    estimate_in_media: Support::Yes,
    progressive: Support::Yes,
    pixel_bytes: 0,
};
