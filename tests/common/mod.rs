//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod lockstep;

use std::path::PathBuf;

/// The course reference folder: $BOTSIM_REFERENCE, else ../shared/reference beside the repo.
pub fn reference_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("BOTSIM_REFERENCE")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/reference"));
    dir.join("maps").is_dir().then_some(dir)
}

/// A course map file, or None (with a note) when the reference folder is absent. CI sets
/// BOTSIM_REFERENCE, and there a missing file is an error.
pub fn reference_map(name: &str) -> Option<PathBuf> {
    match reference_dir() {
        Some(d) => {
            let p = d.join("maps").join(name);
            assert!(p.is_file(), "{} is missing", p.display());
            Some(p)
        }
        None => {
            assert!(std::env::var_os("BOTSIM_REFERENCE").is_none(), "BOTSIM_REFERENCE has no maps/ folder");
            eprintln!("note: course maps not found (set BOTSIM_REFERENCE); skipping");
            None
        }
    }
}
