//! The commands behind the CLI, as library functions so tests can run them without a
//! subprocess: `iris render` ([`render`], its flags: [`render_options`], its budget:
//! [`budget`], a library caller's hooks: [`render_hooks`]; `--shard`: [`shard`],
//! [`shard_id`]), `iris merge` ([`merge`]), `iris converge` ([`converge`]), `iris info`
//! ([`info`]), `iris diff` ([`diff`]), `iris gallery` ([`gallery`]), `iris turntable`
//! ([`turntable`]), `iris gem-report` ([`gem_report`]), and the printing of each
//! ([`commands`], what `main.rs` calls: one function per command). This is the top of the
//! crate: nothing below imports it.

pub mod adaptive;
pub mod budget;
pub mod checkpoint_writes;
pub mod commands;
pub mod converge;
pub mod diff;
pub mod gallery;
pub mod gem_report;
pub mod info;
pub mod judge;
pub mod live;
pub mod merge;
pub mod render;
mod render_denoise;
pub mod render_hooks;
pub mod render_options;
mod render_write;
pub mod shard;
pub mod shard_id;
pub mod summary;
pub mod turntable;

pub use crate::measure::MeasureOptions;
pub use crate::plan::SpectralMode;
pub use crate::prepare::camera_choice::{choose_camera, choose_camera_view};
pub use crate::prepare::default_preview_scene;
pub use crate::prepare::drop_in::PreviewOptions;
pub use crate::prepare::input::{check_size, default_size, load, resolve_environment, MAX_PIXELS};
pub use budget::{Budget, BudgetFlags};
pub use diff::{diff_command, DiffSummary};
pub use info::{info_command, info_command_with};
pub use render::{render_command, RenderJob, RenderSummary, RunHooks};
pub use render_options::RenderOptions;
