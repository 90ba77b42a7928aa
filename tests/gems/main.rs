//! Gems: the cuts and their report, fire, crystal optics, stone and metal overrides, and
//! the studio presets.

#[path = "../common/mod.rs"]
mod common;

mod gem_cuts;
mod gem_fire;
mod gem_optics_cli;
mod gem_report;
mod moissanite_doubling;
mod stones;
mod studio;
