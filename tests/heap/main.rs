//! The tests that count heap bytes: fuzz replay's and huge declared counts' peak heap, and
//! SPPM's live heap across passes. They install the counting allocator
//! (`common::alloc::Counting`), which counts the whole process: the measured work runs on
//! rayon's threads as well as the test's, so a per-thread count would miss it. This binary
//! therefore holds only these tests, and each takes `common::alloc::SERIAL` for its whole
//! run, so no other test's allocations fall into a measurement (under `cargo nextest` each
//! test is its own process anyway).

#[path = "../common/mod.rs"]
mod common;

#[global_allocator]
static ALLOC: common::alloc::Counting = common::alloc::Counting;

mod fuzz_replay;
mod huge_counts;
mod sppm_convergence;
