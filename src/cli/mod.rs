//! The command line's flags, by command: [`render_args`] (`iris render`, and the overrides
//! shared with converge and info), [`other_args`] (merge, turntable, gallery, gem,
//! converge), [`parse`] (value parsers with their bounds).

pub(crate) mod other_args;
pub(crate) mod parse;
pub(crate) mod render_args;
