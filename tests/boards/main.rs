//! The board tests, one test binary: each module was a binary of its own, and most of what
//! they cost is the boards they build and run, so together they share one build of the
//! helpers, one link, and the machine's cores across every module's tests (a long test of one
//! no longer leaves a core idle while the next binary waits).
//!
//! `cargo test --release --test boards shapes::` runs one module's tests. The live board's
//! tests (tests/live.rs, tests/browser.rs) stay binaries of their own: they measure a live
//! run's pace against the wall clock (frames a second), which other tests' load beside them
//! would slow.

#[path = "../common/mod.rs"]
mod common;

mod board;
mod differential;
mod docs;
mod final_projects;
mod hostile;
mod mutants;
mod peripherals;
mod random_designs;
mod repos;
mod shapes;
mod suite;
mod syntax_variants;
