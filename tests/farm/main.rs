//! Work cut for a render farm: shards and their merge (bit-identical to one render),
//! the merge's refusals, and turntables.

#[path = "../common/mod.rs"]
mod common;

mod merge_errors;
mod shards;
mod turntable;
