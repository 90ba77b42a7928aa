//! Image output. STUB: being written.
