//! Which files Verilator read for a design (its `V<prefix>__verFiles.dat`) are the design's
//! own sources, for `cargo:rerun-if-changed`: all but the Verilator runtime's headers and the
//! files generated into OUT_DIR. Kept apart from build.rs so that a test can include it.

use std::path::{Path, PathBuf};

/// The sources listed in a `__verFiles.dat` (its `S` lines, paths quoted), except those under
/// `verilator_root` or `out_dir`. Nothing else is excluded: a checkout under /usr, or in a
/// folder whose name contains "verilator", still tracks its RTL.
pub fn design_sources(ver_files: &str, verilator_root: &Path, out_dir: &Path) -> Vec<PathBuf> {
    ver_files
        .lines()
        .filter_map(|line| {
            let mut parts = line.split_whitespace();
            (parts.next() == Some("S")).then(|| parts.last()).flatten()
        })
        .map(|p| PathBuf::from(p.trim_matches('"')))
        .filter(|p| !p.starts_with(verilator_root) && !p.starts_with(out_dir))
        .collect()
}
