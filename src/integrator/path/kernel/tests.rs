//! Tests of the SoA path kernel.
