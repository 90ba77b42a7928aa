//! The generator's refusal of a value it cannot write: a usage error naming the element,
//! `scene generator: ELEMENT: WHAT` ([`crate::error::Error::Usage`]).

use crate::error::Error;

/// The usage error for `element` (e.g. `mesh 2 "Table"`) and what is wrong with it.
pub(super) fn bad(element: &str, what: impl std::fmt::Display) -> Error {
    Error::Usage(format!("scene generator: {element}: {what}"))
}
