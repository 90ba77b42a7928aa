//! The `iris` binary as a user meets it: renders, errors and exit codes, interrupts, the
//! photon and convergence flags, the default budget, reports and plots, the gallery, the
//! drop-in preview (framing, background), one scene preparation, and the documentation's
//! commands, links and paths (`docs`).

#[path = "../common/mod.rs"]
mod common;

mod background;
mod cli;
mod cli_converge;
mod cli_interrupt;
mod cli_panic_net;
mod cli_photon;
mod default_budget;
mod docs;
mod drop_in;
mod error_estimate;
mod framing;
mod gallery;
mod prepare;
mod report_plot;
