//! Loading a program from whatever file a user has: the layer above the assembler and the
//! image formats, so neither depends on the other.
//!
//! ```
//! use kcpsm6::{asm::Options, loader};
//! let dir = std::env::temp_dir().join(format!("kcpsm6-loader-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("p.psm"), "OUTPUT s0, 56\n").unwrap();
//! let image = loader::load(&dir.join("p.psm"), &Options::default()).unwrap();
//! assert_eq!(image.words[0], 0x2D056);
//! std::fs::write(dir.join("p.hex"), image.to_hex()).unwrap();
//! assert_eq!(loader::load(&dir.join("p.hex"), &Options::default()).unwrap(), image);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::path::Path;

use crate::asm::{self, Options};
use crate::diag::{io_reason, Diagnostic, Diagnostics, Loc};
use crate::image::{Format, Image};

/// A program from `.psm` (assembled with `opts`), `.hex`, `.mem` or `.v`, chosen by the
/// file's extension.
pub fn load(path: &Path, opts: &Options) -> Result<Image, Diagnostics> {
    let fmt = Format::of(path).ok_or_else(|| {
        Diagnostics::single(Diagnostic::error(
            Loc::file(path),
            "unknown program format (expected .psm, .hex, .mem or .v)",
        ))
    })?;
    if fmt == Format::Psm {
        return asm::assemble_file(path, opts).map(|p| p.image);
    }
    let bytes = std::fs::read(path).map_err(|e| {
        Diagnostics::single(Diagnostic::error(Loc::file(path), format!("cannot read file: {}", io_reason(&e))))
    })?;
    let text = String::from_utf8_lossy(&bytes);
    match fmt {
        Format::Hex => Image::parse_hex(path, &text),
        Format::Mem => Image::parse_mem(path, &text),
        _ => Image::parse_verilog(path, &text),
    }
    .map_err(Diagnostics::single)
}
