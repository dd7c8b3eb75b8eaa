//! The command line's tests, one test binary (as tests/boards is for the board): each module
//! was a binary of its own, and together they share one build of the helpers and one link,
//! and the machine's cores across every module's tests.
//!
//! `cargo test --release --test cli robust::` runs one module's tests.

#[path = "../common/mod.rs"]
mod common;

mod asm;
mod course_modules;
mod pictures;
mod readme_example;
mod robust;
mod run_debug;
mod worlds;
