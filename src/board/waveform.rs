//! The waveform of a run that kept only what it records: the signals such a run cannot show
//! become `x`.
//!
//! A run whose fast-forward compares and puts back only the variables its records observe
//! ([`super::model::FastForward::Recorded`]) leaves the rest as they were when a period was
//! skipped, and does not run a clock that drives only them (a VGA design's pixel clock). A
//! waveform it opens later shows the observed variables exactly, but the others (the VGA
//! timing, the colour pipeline) with values no board had. The build lists those signals
//! ([`crate::fastforward::observed::unshown`]); [`mark_unshown`] rewrites the waveform Verilator wrote so
//! that they read `x` from its first moment to its last, with a comment that says why.
//!
//! Verilator's VCD writer names a signal by its trace code, in base 94 from `!`, the lowest
//! digit first, each higher digit one more than its value (verilated_vcd_c.cpp,
//! `writeCode`); the top model's codes start at 1. A declaration whose width is not the
//! traced one is an error: the numbering is not what this module reads.
//!
//! ```
//! use botsim::fastforward::observed::Unshown;
//! let dir = tempfile::tempdir().unwrap();
//! let (part, vcd) = (dir.path().join("w.part"), dir.path().join("w.vcd"));
//! // Two signals: `led` (code 1, shown as `"`), `vga_r` (code 2, `#`).
//! std::fs::write(&part, "$timescale 1ps $end\n $scope module TOP $end\n  $var wire 16 \" led [15:0] $end\n  $var wire  4 # vga_r [3:0] $end\n $upscope $end\n$enddefinitions $end\n\n\n#10\nb0000000000000001 \"\nb0101 #\n#20\nb0110 #\n").unwrap();
//! let n = botsim::board::waveform::mark_unshown(&part, &vcd, &[Unshown { code: 1, width: 4 }]).unwrap();
//! let text = std::fs::read_to_string(&vcd).unwrap();
//! assert_eq!(n, 1);
//! assert!(text.contains("#10\nbx #\nb0000000000000001 \"\n#20\n"), "{text}");
//! ```

use std::collections::HashMap;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::Path;

use crate::fastforward::observed::Unshown;

/// Verilator's VCD name of the trace code `code` (its writer adds the model's base code, 1).
fn vcd_id(code: u32) -> String {
    let mut code = code + 1;
    let mut id = String::new();
    id.push(char::from(b'!' + (code % 94) as u8));
    code /= 94;
    while code > 0 {
        code -= 1;
        id.push(char::from(b'!' + (code % 94) as u8));
        code /= 94;
    }
    id
}

/// Copy the waveform `part` to `out` (written under a temporary name and then renamed) with
/// the `unshown` signals `x`: their value at the first moment is `x` and their changes are
/// left out. Returns how many declared signals became `x` (aliases of one code count once
/// each).
pub fn mark_unshown(part: &Path, out: &Path, unshown: &[Unshown]) -> Result<usize, String> {
    let ids: HashMap<Vec<u8>, u32> = unshown.iter().map(|u| (vcd_id(u.code).into_bytes(), u.width)).collect();
    let io = |e: std::io::Error, p: &Path| format!("{}: {e}", p.display());
    let mut input = BufReader::new(std::fs::File::open(part).map_err(|e| io(e, part))?);
    let tmp = out.with_file_name(format!(".{}.tmp", out.file_name().unwrap_or_default().to_string_lossy()));
    let file = std::fs::File::create(&tmp).map_err(|e| io(e, &tmp))?;
    let mut w = BufWriter::new(file);
    let result = (|| -> Result<usize, String> {
        let werr = |e: std::io::Error| io(e, &tmp);
        // The header: the declared ids that read `x`, with their widths (a 1-bit wire is a
        // scalar).
        let mut marked: Vec<(String, u32)> = Vec::new();
        let mut line = String::new();
        loop {
            line.clear();
            if input.read_line(&mut line).map_err(|e| io(e, part))? == 0 {
                return Err(format!("{}: the waveform has no `$enddefinitions`", part.display()));
            }
            let f: Vec<&str> = line.split_whitespace().collect();
            if f.first() == Some(&"$var") && f.len() >= 5 {
                if let Some(&width) = ids.get(f[3].as_bytes()) {
                    if f[2].parse::<u32>().ok() != Some(width) || f[1] != "wire" {
                        return Err(format!(
                            "the waveform's signal `{}` is {} bits, where the build's analysis traced {width} \
                             (Verilator's VCD numbering is not the one src/board/waveform.rs reads)",
                            f[4], f[2]
                        ));
                    }
                    if !marked.iter().any(|(id, _)| id == f[3]) {
                        marked.push((f[3].to_string(), width));
                    }
                }
            } else if f.first() == Some(&"$enddefinitions") {
                writeln!(
                    w,
                    "$comment botsim: {} signals are x: this run kept only what it records before the \
                     waveform, and these read the parts it did not simulate (src/board/waveform.rs) $end",
                    marked.len()
                )
                .map_err(werr)?;
                w.write_all(line.as_bytes()).map_err(werr)?;
                break;
            }
            w.write_all(line.as_bytes()).map_err(werr)?;
        }
        // The values: `x` at the first moment, then every change but theirs.
        let mut first_time = true;
        let mut buf = Vec::new();
        loop {
            buf.clear();
            if input.read_until(b'\n', &mut buf).map_err(|e| io(e, part))? == 0 {
                break;
            }
            let text = buf.strip_suffix(b"\n").unwrap_or(&buf);
            if text.first() == Some(&b'#') {
                w.write_all(&buf).map_err(werr)?;
                if std::mem::replace(&mut first_time, false) {
                    for (id, width) in &marked {
                        let x = if *width == 1 { "x" } else { "bx " };
                        writeln!(w, "{x}{id}").map_err(werr)?;
                    }
                }
                continue;
            }
            // A value change: `b0101 id`, `r1.5 id` or `0id`.
            let id = match text.iter().position(|&c| c == b' ') {
                Some(i) => &text[i + 1..],
                None => text.get(1..).unwrap_or(b""),
            };
            if !ids.contains_key(id) {
                w.write_all(&buf).map_err(werr)?;
            }
        }
        w.flush().map_err(werr)?;
        Ok(marked.len())
    })();
    drop(w);
    match result {
        Ok(n) => {
            std::fs::rename(&tmp, out).map_err(|e| io(e, out))?;
            Ok(n)
        }
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_verilators() {
        // Verilator's writeCode for codes 1, 94 and 2168 (after the base code, 1).
        assert_eq!(vcd_id(0), "\"");
        assert_eq!(vcd_id(93), "!!");
        assert_eq!(vcd_id(2167), "'7");
    }
}
