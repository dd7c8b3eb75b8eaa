//! Program images: 4096 18-bit words, read from and written to the formats people bring.
//!
//! | format | read | write |
//! |---|---|---|
//! | `.psm` | assembled ([`crate::asm`], through [`crate::loader`]) | ([`crate::disasm`]) |
//! | `.hex` | 4096 lines of 5 hex digits (KCPSM6, CR LF or LF) | exactly as KCPSM6 (CR LF) |
//! | `.mem` | `@address` lines and hex words (opbasm, `$readmemh`) | `@00000000` + 4096 words, LF |
//! | `.v` | Xilinx-template ROM (INIT_xx / INITP_xx) or our behavioural ROM | [`crate::output::verilog_rom`] |
//!
//! ```
//! use kcpsm6::image::Image;
//! let mut img = Image::zeroed();
//! img.words[0] = 0x2D056;
//! let hex = img.to_hex();
//! assert_eq!(hex.len(), 28_672);
//! assert_eq!(Image::parse_hex(std::path::Path::new("x.hex"), &hex).unwrap(), img);
//! ```

use std::path::Path;

use crate::diag::{Diagnostic, Loc};
use crate::isa::{ROM_WORDS, WORD_MASK};

/// A full 4K program memory.
#[derive(Clone, PartialEq, Eq)]
pub struct Image {
    pub words: Box<[u32; ROM_WORDS]>,
}

impl std::fmt::Debug for Image {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let used = self.words.iter().rposition(|&w| w != 0).map_or(0, |i| i + 1);
        write!(f, "Image({:05X?}", &self.words[..used.min(16)])?;
        if used > 16 {
            write!(f, " ... {used} words")?;
        }
        write!(f, ")")
    }
}

/// The program formats, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Psm,
    Hex,
    Mem,
    Verilog,
}

impl Format {
    /// The format for a path's extension (case-insensitive).
    pub fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "psm" => Some(Format::Psm),
            "hex" => Some(Format::Hex),
            "mem" => Some(Format::Mem),
            "v" => Some(Format::Verilog),
            _ => None,
        }
    }
}

impl Image {
    pub fn zeroed() -> Image {
        Image { words: Box::new([0; ROM_WORDS]) }
    }

    /// An image holding `words` from address 0 (at most 4096, each masked to 18 bits).
    pub fn from_words(words: &[u32]) -> Image {
        let mut img = Image::zeroed();
        for (d, s) in img.words.iter_mut().zip(words) {
            *d = s & WORD_MASK;
        }
        img
    }

    /// KCPSM6 `.hex`: 4096 lines of 5 hex digits (CR LF as written; LF accepted).
    pub fn parse_hex(path: &Path, text: &str) -> Result<Image, Diagnostic> {
        let mut img = Image::zeroed();
        let mut n = 0;
        for (i, line) in text.lines().enumerate() {
            let t = line.trim_end_matches('\r').trim();
            if t.is_empty() {
                continue;
            }
            let loc = Loc::new(path, i + 1, line.find(|c: char| !c.is_whitespace()).map_or(1, |c| c + 1));
            let w = parse_word(t).map_err(|m| Diagnostic::error(loc.clone(), m))?;
            if n == ROM_WORDS {
                return Err(Diagnostic::error(loc, "more than 4096 words (a KCPSM6 .hex has one per address 000-FFF)"));
            }
            img.words[n] = w;
            n += 1;
        }
        if n != ROM_WORDS {
            return Err(Diagnostic::error(
                Loc::file(path),
                format!("has {n} words; a KCPSM6 .hex has exactly 4096 (one per address 000-FFF)"),
            ));
        }
        Ok(img)
    }

    /// `.mem` as `$readmemh` reads it ([`crate::readmemh`]): `@address` lines, hex words,
    /// comments.
    pub fn parse_mem(path: &Path, text: &str) -> Result<Image, Diagnostic> {
        use crate::readmemh::{entries, Error};
        let items = entries(text, ROM_WORDS).map_err(|e| match e {
            Error::BadAddress { token, line, col } => {
                Diagnostic::error(Loc::new(path, line, col), format!("'{token}' is not an address 000-FFF"))
            }
            Error::PastEnd { line, col } => Diagnostic::error(Loc::new(path, line, col), "word past address FFF"),
            Error::UnclosedComment { line, col } => {
                Diagnostic::error(Loc::new(path, line, col), "'/*' comment without its '*/'")
            }
        })?;
        if items.is_empty() {
            return Err(Diagnostic::error(Loc::file(path), "no program words found"));
        }
        let mut img = Image::zeroed();
        for e in items {
            img.words[e.address] =
                parse_word(&e.value).map_err(|m| Diagnostic::error(Loc::new(path, e.line, e.col), m))?;
        }
        Ok(img)
    }

    /// A ROM `.v`: a Xilinx template filled by KCPSM6 (INIT_xx/INITP_xx strings, 18-bit or
    /// 9-bit split BRAMs) or a behavioural ROM written by this toolchain.
    pub fn parse_verilog(path: &Path, text: &str) -> Result<Image, Diagnostic> {
        if let Some(img) = parse_init_strings(text) {
            return img.map_err(|(line, m)| Diagnostic::error(Loc::new(path, line, 0), m));
        }
        if let Some(img) = parse_behavioural(path, text) {
            return img;
        }
        Err(Diagnostic::error(
            Loc::file(path),
            "no program found: expected INIT_xx/INITP_xx strings (a Xilinx ROM template) or rom[...] = 18'h... lines",
        ))
    }

    /// KCPSM6 `.hex` text (28,672 bytes).
    pub fn to_hex(&self) -> String {
        let mut s = String::with_capacity(ROM_WORDS * 7);
        for w in self.words.iter() {
            s.push_str(&format!("{w:05X}\r\n"));
        }
        s
    }

    /// opbasm-style `.mem` text (24,586 bytes).
    pub fn to_mem(&self) -> String {
        let mut s = String::with_capacity(10 + ROM_WORDS * 6);
        s.push_str("@00000000\n");
        for w in self.words.iter() {
            s.push_str(&format!("{w:05X}\n"));
        }
        s
    }

    /// INIT_nn strings for an 18-bit BRAM: `(INIT_nn values, INITP_nn values)` as 64 hex digits.
    pub fn init_strings(&self, words: usize) -> (Vec<String>, Vec<String>) {
        let init = (0..words / 16)
            .map(|n| (0..16).rev().map(|j| format!("{:04X}", self.words[16 * n + j] & 0xFFFF)).collect())
            .collect();
        let initp = (0..words / 128)
            .map(|n| {
                (0..64)
                    .rev()
                    .map(|k| {
                        let lo = self.words[128 * n + 2 * k] >> 16 & 3;
                        let hi = self.words[128 * n + 2 * k + 1] >> 16 & 3;
                        format!("{:X}", hi << 2 | lo)
                    })
                    .collect()
            })
            .collect();
        (init, initp)
    }
}

/// One hex word of up to 5 digits, at most 3FFFF.
fn parse_word(t: &str) -> Result<u32, String> {
    if t.is_empty() || t.len() > 5 || !t.chars().all(|c| c.is_ascii_hexdigit()) {
        return Err(format!("'{t}' is not an instruction word (up to 5 hex digits)"));
    }
    let w = u32::from_str_radix(t, 16).unwrap_or(u32::MAX);
    if w > WORD_MASK {
        return Err(format!("'{t}' is larger than the 18-bit maximum 3FFFF"));
    }
    Ok(w)
}

/// One `INIT_nn` / `INITP_nn` value found in a template, with its BRAM's data width.
struct InitString {
    parity: bool,
    index: usize,
    /// 32 bytes, least significant first.
    bytes: [u8; 32],
    width: u32,
    block: usize,
    line: usize,
}

/// Find the INIT strings and group them by BRAM instance. `None` when there are none.
fn parse_init_strings(text: &str) -> Option<Result<Image, (usize, String)>> {
    let strings = scan_init_strings(text);
    if strings.is_empty() {
        return None;
    }
    let mut img = Image::zeroed();
    let eighteen: Vec<&InitString> = strings.iter().filter(|s| s.width != 9).collect();
    if !eighteen.is_empty() {
        let mut seen_init = [false; 128];
        let mut seen_initp = [false; 16];
        for s in eighteen {
            if s.parity {
                if s.index >= 16 || std::mem::replace(&mut seen_initp[s.index], true) {
                    continue;
                }
                for j in 0..128 {
                    let bits = (s.bytes[j / 4] >> (2 * (j % 4)) & 3) as u32;
                    img.words[128 * s.index + j] |= bits << 16;
                }
            } else {
                if s.index >= 128 || std::mem::replace(&mut seen_init[s.index], true) {
                    continue;
                }
                for j in 0..16 {
                    let low = s.bytes[2 * j] as u32 | (s.bytes[2 * j + 1] as u32) << 8;
                    img.words[16 * s.index + j] |= low;
                }
            }
        }
        return Some(Ok(img));
    }
    // 9-bit split: the first BRAM holds bits [8:0], the second bits [17:9].
    let mut blocks: Vec<usize> = strings.iter().map(|s| s.block).collect();
    blocks.dedup();
    if blocks.len() < 2 {
        let line = strings[0].line;
        return Some(Err((line, "9-bit ROM template with only one BRAM: need the [8:0] and [17:9] halves".into())));
    }
    for (half, &block) in blocks.iter().take(2).enumerate() {
        let shift = 9 * half as u32;
        for s in strings.iter().filter(|s| s.block == block) {
            if s.parity {
                for j in 0..256.min(ROM_WORDS - 256 * s.index.min(15)) {
                    let bit = (s.bytes[j / 8] >> (j % 8) & 1) as u32;
                    if let Some(w) = img.words.get_mut(256 * s.index + j) {
                        *w |= bit << (8 + shift);
                    }
                }
            } else {
                for j in 0..32 {
                    if let Some(w) = img.words.get_mut(32 * s.index + j) {
                        *w |= (s.bytes[j] as u32) << shift;
                    }
                }
            }
        }
    }
    Some(Ok(img))
}

/// The INIT strings of a template in text order, read token by token (comments blanked), so
/// an attribute written over several lines, with comments between its parts or none of the
/// usual spaces (`.INIT_00 (\n 256'h...)`, `.INIT_00(256'h...)`) reads as the usual form.
fn scan_init_strings(text: &str) -> Vec<InitString> {
    let code = blank_comments(text);
    let b = code.as_bytes();
    let mut out = Vec::new();
    let mut block = 0;
    let mut width = 18;
    let line_of = |at: usize| code[..at].bytes().filter(|&c| c == b'\n').count() + 1;
    // The first token after `at` past white space, `(`, `=` and `.`.
    let value_after = |mut at: usize| {
        while at < b.len() && (b[at].is_ascii_whitespace() || b"(=.".contains(&b[at])) {
            at += 1;
        }
        let end = (at..b.len())
            .find(|&k| !(b[k].is_ascii_alphanumeric() || b[k] == b'_' || b[k] == b'\''))
            .unwrap_or(b.len());
        &code[at..end]
    };
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b'"' {
            i = code[i + 1..].find('"').map_or(b.len(), |k| i + k + 2);
            continue;
        }
        if !(c.is_ascii_alphanumeric() || c == b'_' || c == b'$') {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'$' || b[i] == b'\'') {
            i += 1;
        }
        if c.is_ascii_digit() {
            continue; // a number (`256'h...`): its letters are no names
        }
        let word = &code[start..i];
        if ["RAMB18E1", "RAMB36E1", "RAMB16BWER", "RAMB18", "RAMB36", "RAMB16"].contains(&word) {
            block += 1;
            width = 18;
        } else if word == "READ_WIDTH_A" || word == "DATA_WIDTH_A" {
            let digits: String = value_after(i).chars().take_while(|c| c.is_ascii_digit()).collect();
            if let Ok(w) = digits.parse() {
                width = w;
                for s in out.iter_mut().filter(|s: &&mut InitString| s.block == block) {
                    s.width = w;
                }
            }
        } else if let Some((parity, hex)) =
            word.strip_prefix("INITP_").map(|h| (true, h)).or_else(|| word.strip_prefix("INIT_").map(|h| (false, h)))
        {
            let Some(index) = (hex.len() == 2).then(|| usize::from_str_radix(hex, 16).ok()).flatten() else { continue };
            let mut at = i;
            while at < b.len() && b[at].is_ascii_whitespace() {
                at += 1;
            }
            if !(at < b.len() && (b[at] == b'(' || b[at] == b'=')) {
                continue;
            }
            let value = value_after(at);
            let Some(digits) = value.strip_prefix("256'h").or_else(|| value.strip_prefix("256'H")) else { continue };
            if digits.len() != 64 || !digits.bytes().all(|c| c.is_ascii_hexdigit()) {
                continue;
            }
            let mut bytes = [0u8; 32];
            for (k, byte) in bytes.iter_mut().enumerate() {
                let pos = 62 - 2 * k;
                *byte = u8::from_str_radix(&digits[pos..pos + 2], 16).unwrap_or(0);
            }
            out.push(InitString { parity, index, bytes, width, block, line: line_of(start) });
        }
    }
    out
}

/// `text` with its comments replaced by spaces (line breaks kept, so lines and offsets stay).
fn blank_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        let line = rest.find("//");
        let block = rest.find("/*");
        let quote = rest.find('"');
        let first = [line, block, quote].into_iter().flatten().min();
        let Some(at) = first else {
            out.push_str(rest);
            break;
        };
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        let end = if Some(at) == quote {
            // A string is kept whole: a `//` inside it is no comment.
            let end = rest[1..].find('"').map_or(rest.len(), |k| k + 2);
            out.push_str(&rest[..end]);
            rest = &rest[end..];
            continue;
        } else if Some(at) == line {
            rest.find('\n').unwrap_or(rest.len())
        } else {
            rest[2..].find("*/").map_or(rest.len(), |k| k + 4)
        };
        out.extend(rest[..end].chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
        rest = &rest[end..];
    }
    out
}

/// Our behavioural ROM: lines `rom[10'hAAA] = 18'hWWWWW;` (and an optional fill value).
fn parse_behavioural(path: &Path, text: &str) -> Option<Result<Image, Diagnostic>> {
    // Read token by token (comments blanked): `rom[10'h01A] = 18'h2D515;` and `fill = 18'h0;`
    // however they are spaced or broken over lines.
    let code = blank_comments(text);
    let b = code.as_bytes();
    let mut img = Image::zeroed();
    let mut any = false;
    let line_of = |at: usize| code[..at].bytes().filter(|&c| c == b'\n').count() + 1;
    let skip_ws = |mut at: usize| {
        while at < b.len() && b[at].is_ascii_whitespace() {
            at += 1;
        }
        at
    };
    // A sized hex literal at `at` (`18'h2D515`): its width, digits and end.
    let literal = |at: usize| -> Option<(&str, &str, usize)> {
        let w_end = (at..b.len()).find(|&k| !b[k].is_ascii_digit())?;
        let rest = code[w_end..].strip_prefix("'h").or_else(|| code[w_end..].strip_prefix("'H"))?;
        let d_start = b.len() - rest.len();
        let d_end = (d_start..b.len()).find(|&k| !(b[k].is_ascii_hexdigit() || b[k] == b'_')).unwrap_or(b.len());
        Some((&code[at..w_end], &code[d_start..d_end], d_end))
    };
    let name_at = |at: usize, name: &str| {
        b[at..].starts_with(name.as_bytes())
            && (at == 0 || !(b[at - 1].is_ascii_alphanumeric() || b[at - 1] == b'_'))
            && !b.get(at + name.len()).is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
    };
    // `= 18'hWWWWW ;` at `at`: the word.
    let assigned = |at: usize| -> Option<Result<u32, String>> {
        let at = skip_ws(at);
        (b.get(at) == Some(&b'=')).then_some(())?;
        let (width, digits, end) = literal(skip_ws(at + 1))?;
        (width == "18" && b.get(skip_ws(end)) == Some(&b';')).then_some(())?;
        Some(parse_word(&digits.replace('_', "")))
    };
    let mut i = 0;
    while i < b.len() {
        if name_at(i, "fill") {
            if let Some(w) = assigned(i + 4) {
                match w {
                    Ok(w) => img.words.iter_mut().for_each(|x| *x = w),
                    Err(m) => return Some(Err(Diagnostic::error(Loc::new(path, line_of(i), 1), m))),
                }
            }
            i += 4;
        } else if name_at(i, "rom") && b.get(skip_ws(i + 3)) == Some(&b'[') {
            let at = skip_ws(skip_ws(i + 3) + 1);
            // `rom[i] = fill` in the template's loop and the declaration `rom [0:WORDS-1]`:
            // not words of the program.
            if literal(at).is_some() {
                let parsed = literal(at).and_then(|(width, a, end)| {
                    width.parse::<u8>().ok()?;
                    let close = skip_ws(end);
                    (b.get(close) == Some(&b']')).then_some(())?;
                    Some((usize::from_str_radix(&a.replace('_', ""), 16).ok()?, assigned(close + 1)?))
                });
                let line = line_of(i);
                match parsed {
                    Some((a, Ok(w))) if a < ROM_WORDS => {
                        img.words[a] = w;
                        any = true;
                    }
                    Some((_, Err(m))) => return Some(Err(Diagnostic::error(Loc::new(path, line, 1), m))),
                    _ => {
                        let statement =
                            code[i..].split(';').next().unwrap_or("").split_whitespace().collect::<Vec<_>>().join(" ");
                        return Some(Err(Diagnostic::error(
                            Loc::new(path, line, 1),
                            format!("cannot read ROM line '{statement};'"),
                        )));
                    }
                }
            }
            i += 3;
        } else {
            i += 1;
        }
    }
    any.then_some(Ok(img))
}
