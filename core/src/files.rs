//! File output that is never half-written: write to a temporary name beside the target, then
//! rename over it.

use std::io::Write;
use std::path::Path;

/// Write `data` to `path` atomically. On error nothing is left at `path` (an existing file is
/// untouched) and the message names the path.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let p = dir.path().join("out.txt");
/// botsim_core::files::write_atomic(&p, b"hello").unwrap();
/// assert_eq!(std::fs::read(&p).unwrap(), b"hello");
/// ```
pub fn write_atomic(path: &Path, data: &[u8]) -> Result<(), String> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().ok_or_else(|| format!("{}: error: not a file name", path.display()))?;
    let tmp = dir.join(format!(".{}.tmp{}", name.to_string_lossy(), std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(data)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: error: cannot write file: {}", path.display(), kcpsm6::diag::io_reason(&e))
    })
}

/// Check, before a long run, that `path` can be written later: it is not a folder and its
/// folder takes a new file (a probe file, removed at once). An existing file is untouched:
/// outputs are written beside their name and renamed over it ([`write_atomic`]), so what
/// must be writable is the folder.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// assert!(botsim_core::files::check_writable(&dir.path().join("out.csv")).is_ok());
/// assert!(botsim_core::files::check_writable(dir.path()).is_err());
/// ```
pub fn check_writable(path: &Path) -> Result<(), String> {
    if path.is_dir() {
        return Err(format!("{}: error: cannot write file: is a directory", path.display()));
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let probe = dir.join(format!(".botsim-write-check-{}", std::process::id()));
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(|e| format!("{}: error: cannot write file: {}", path.display(), kcpsm6::diag::io_reason(&e)))
}
