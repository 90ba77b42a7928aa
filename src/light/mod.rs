//! Every light of the render scene, in one place:
//!
//! - [`punctual`]: point, spot and directional lights (KHR_lights_punctual; candela, lux),
//!   and the default lights of a scene without any;
//! - [`area`]: emissive triangles as lights (radiance; chosen by power, sampled by area,
//!   pdfs per solid angle at the receiver);
//! - [`env`](mod@env): the environment, radiance arriving from infinitely far away (`--env`;
//!   uniform or an equirectangular map, importance-sampled, pdfs per solid angle);
//! - [`sky`]: a clear sky and its sun from single Rayleigh and Mie scattering
//!   (`--env sky:…`), an environment map plus a directional light.
//!
//! Frame: Iris's world space (metres, right-handed, +Y up). How the integrators sample
//! these lights together (next-event estimation, MIS) is the integrators' business.

pub mod area;
pub mod env;
pub mod punctual;
pub mod sampler;
pub mod sky;

pub(crate) use punctual::range_window;
pub use punctual::{default_lights, Incidence, Light, PunctualLight};
pub use sampler::{LightChoice, LightId, LightSampler};
