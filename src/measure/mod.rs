//! Measuring renders: how far an image is from a reference and how that distance falls with
//! time. Used by `iris render --reference/--report/--plot/--target-error` and by
//! `iris converge`; it sees the renderer only through the checkpoints a render shows
//! ([`crate::render::Progress`]).
//!
//! - The distances themselves (RMSE, relative MSE and MAE against a reference, and the
//!   half-buffer estimate without one) are image arithmetic: [`crate::image::metrics`].
//! - [`recorder`]: one [`ReportRow`](report::ReportRow) per [`crate::render::Progress`] of a
//!   progressive render, the `--target-error` stop, the `--reference` file checks.
//! - [`levels`]: which run reached each error level first (`iris converge`).
//! - [`report`]: the CSV report; [`plot`]: the error-against-time plot (PNG).
//!
//! Units: wall seconds; "relative error" is the relative RMSE `sqrt(rel_mse)`
//! ([`relative_rmse`]). Files are written atomically (temporary file + rename).

pub mod levels;
mod options;
pub mod plot;
pub mod recorder;
pub mod report;

pub use levels::{levels_table, LEVELS};
pub use options::{check_plot_extension, file_name, MeasureOptions};
pub use recorder::{
    check_reference_size, denoised_points, points, read_reference_file, relative_rmse, Recorder,
};
