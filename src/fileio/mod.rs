//! The file system at Iris's edges: every file Iris reads is opened through [`input`]
//! (regular files only, a size bound per kind of file, checked before reading and while
//! reading), and every output path is checked through [`output`] before the work that
//! makes it. Errors name the path and what is wrong with it.

pub mod input;
pub mod output;

pub use input::{Input, ReadError};
