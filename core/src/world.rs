//! The bot's world: 128 x 128 cells of 2 bits (spec/botsim.md §9-§10), its file formats and
//! the built-in course.
//!
//! | format | reads | writes |
//! |---|---|---|
//! | `.txt` | the course format: header lines, then `RRR|<128 digits 0-3>` rows | the same |
//! | `.coe` | Xilinx COE, radix 16, with or without the final `;` | as the course files |
//! | `.mem` | `$readmemh`: one value per cell, row-major, `@addr` and `//` allowed | 16384 lines |
//! | `.png` | 128 x 128, the four colours of [`Cell::colour`] | the same |
//!
//! ```
//! use botsim_core::world::{Cell, World};
//! let w = World::builtin();
//! assert_eq!(w.get(64, 64), Cell::Line); // the start cell, the line runs East
//! assert_eq!(w.get(0, 0), Cell::Obstruction);
//! let again = World::parse_txt(std::path::Path::new("w.txt"), &w.to_txt()).unwrap();
//! assert_eq!(again, w);
//! ```

use std::path::Path;

use kcpsm6::diag::{Diagnostic, Loc};

pub const SIZE: usize = 128;
pub const CELLS: usize = SIZE * SIZE;

/// One map cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Cell {
    #[default]
    Floor = 0,
    Line = 1,
    Obstruction = 2,
    Reserved = 3,
}

impl Cell {
    pub const ALL: [Cell; 4] = [Cell::Floor, Cell::Line, Cell::Obstruction, Cell::Reserved];

    pub fn from_bits(v: u8) -> Cell {
        Cell::ALL[(v & 3) as usize]
    }

    pub fn bits(self) -> u8 {
        self as u8
    }

    /// The colour of this cell in PNG files (RGB).
    pub fn colour(self) -> [u8; 3] {
        match self {
            Cell::Floor => [255, 255, 255],
            Cell::Line => [0, 0, 0],
            Cell::Obstruction => [178, 34, 34],
            Cell::Reserved => [30, 144, 255],
        }
    }

    pub fn name(self) -> &'static str {
        ["floor", "line", "obstruction", "reserved"][self as usize]
    }
}

/// A 128 x 128 world, row-major (address = row * 128 + column).
#[derive(Clone, PartialEq, Eq)]
pub struct World {
    cells: Vec<Cell>,
}

impl std::fmt::Debug for World {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let c = self.counts();
        write!(f, "World(floor {}, line {}, obstruction {}, reserved {})", c[0], c[1], c[2], c[3])
    }
}

impl Default for World {
    fn default() -> World {
        World::empty()
    }
}

/// The world file formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WorldFormat {
    Txt,
    Coe,
    Mem,
    Png,
}

impl WorldFormat {
    pub fn of(path: &Path) -> Option<WorldFormat> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "txt" => Some(WorldFormat::Txt),
            "coe" => Some(WorldFormat::Coe),
            "mem" => Some(WorldFormat::Mem),
            "png" => Some(WorldFormat::Png),
            _ => None,
        }
    }
}

fn err(path: &Path, line: usize, col: usize, msg: impl Into<String>) -> Diagnostic {
    Diagnostic::error(Loc::new(path, line, col), msg)
}

impl World {
    /// All floor.
    pub fn empty() -> World {
        World { cells: vec![Cell::Floor; CELLS] }
    }

    /// The cell at column `x`, row `y`, modulo 128 (as the map hardware addresses it).
    pub fn get(&self, x: u8, y: u8) -> Cell {
        self.cells[(y as usize & 127) * SIZE + (x as usize & 127)]
    }

    pub fn set(&mut self, x: u8, y: u8, c: Cell) {
        self.cells[(y as usize & 127) * SIZE + (x as usize & 127)] = c;
    }

    /// Fill the rectangle of columns `x0..=x1`, rows `y0..=y1`.
    pub fn fill(&mut self, (x0, y0): Xy, (x1, y1): Xy, c: Cell) {
        for y in y0.min(y1)..=y0.max(y1) {
            for x in x0.min(x1)..=x0.max(x1) {
                self.set(x, y, c);
            }
        }
    }

    /// A world from cell values in address order (at most 16384; the rest floor).
    pub fn from_cells(cells: &[Cell]) -> World {
        let mut w = World::empty();
        for (d, s) in w.cells.iter_mut().zip(cells) {
            *d = *s;
        }
        w
    }

    /// The 2-bit values in address order.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        self.cells.iter().copied()
    }

    /// The values as bytes in address order (for loading the RTL map).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.cells.iter().map(|c| c.bits()).collect()
    }

    /// Cells of each value: [floor, line, obstruction, reserved].
    pub fn counts(&self) -> [usize; 4] {
        let mut n = [0; 4];
        for c in &self.cells {
            n[*c as usize] += 1;
        }
        n
    }

    /// Load a world file, the format chosen by extension.
    pub fn load(path: &Path) -> Result<World, Diagnostic> {
        let fmt = WorldFormat::of(path)
            .ok_or_else(|| err(path, 0, 0, "unknown world format (expected .txt, .coe, .mem or .png)"))?;
        let bytes = std::fs::read(path)
            .map_err(|e| err(path, 0, 0, format!("cannot read file: {}", kcpsm6::diag::io_reason(&e))))?;
        match fmt {
            WorldFormat::Png => World::from_png(path, &bytes),
            _ => {
                let text = std::str::from_utf8(&bytes).map_err(|e| {
                    err(path, 0, 0, format!("not a text file (invalid UTF-8 at byte {})", e.valid_up_to()))
                })?;
                match fmt {
                    WorldFormat::Txt => World::parse_txt(path, text),
                    WorldFormat::Coe => World::parse_coe(path, text),
                    _ => World::parse_mem(path, text),
                }
            }
        }
    }

    /// Write a world file, the format chosen by extension.
    pub fn to_format(&self, fmt: WorldFormat) -> Vec<u8> {
        match fmt {
            WorldFormat::Txt => self.to_txt().into_bytes(),
            WorldFormat::Coe => self.to_coe().into_bytes(),
            WorldFormat::Mem => self.to_mem().into_bytes(),
            WorldFormat::Png => self.to_png(),
        }
    }

    /// The course `.txt` format (spec §10.1): rows `RRR|` + 128 digits; header lines and
    /// trailing blanks are ignored; each row 000-07F exactly once.
    pub fn parse_txt(path: &Path, text: &str) -> Result<World, Diagnostic> {
        let mut w = World::empty();
        let mut seen = [0usize; SIZE];
        for (i, line) in text.lines().enumerate() {
            let line = line.trim_end();
            let Some((label, digits)) = line.split_once('|') else { continue };
            if label.len() != 3 || !label.chars().all(|c| c.is_ascii_hexdigit()) {
                continue;
            }
            let row = usize::from_str_radix(label, 16).unwrap_or(usize::MAX);
            if row >= SIZE {
                return Err(err(path, i + 1, 1, format!("row label '{label}' is above 07F")));
            }
            if seen[row] != 0 {
                return Err(err(path, i + 1, 1, format!("row {label} again (first at line {})", seen[row])));
            }
            seen[row] = i + 1;
            let n = digits.chars().count();
            if n != SIZE {
                return Err(err(path, i + 1, 5, format!("row {label} has {n} cells; a row has 128")));
            }
            for (x, ch) in digits.chars().enumerate() {
                match ch.to_digit(10) {
                    Some(v) if v <= 3 => w.cells[row * SIZE + x] = Cell::from_bits(v as u8),
                    _ => {
                        return Err(err(path, i + 1, 5 + x, format!("'{ch}' is not a cell value 0-3")));
                    }
                }
            }
        }
        if let Some(missing) = seen.iter().position(|&s| s == 0) {
            let count = seen.iter().filter(|&&s| s == 0).count();
            return Err(err(path, 0, 0, format!("row {missing:03X} is missing ({count} of 128 rows missing)")));
        }
        Ok(w)
    }

    /// The course `.txt` format: column index headers, a dashed line, 128 rows.
    pub fn to_txt(&self) -> String {
        let mut s = String::new();
        for div in [100, 10, 1] {
            s.push_str("    ");
            s.extend((0..SIZE).map(|x| char::from(b'0' + (x / div % 10) as u8)));
            s.push('\n');
        }
        s.push('\n');
        for shift in [4, 0] {
            s.push_str("    ");
            s.extend(
                (0..SIZE).map(|x| char::from_digit((x >> shift & 15) as u32, 16).unwrap_or('0').to_ascii_uppercase()),
            );
            s.push('\n');
        }
        s.push_str(&"-".repeat(131));
        s.push('\n');
        for y in 0..SIZE {
            s.push_str(&format!("{y:03X}|"));
            s.extend(self.cells[y * SIZE..(y + 1) * SIZE].iter().map(|c| char::from(b'0' + c.bits())));
            s.push('\n');
        }
        s
    }

    /// Xilinx `.coe` (spec §10.2): keywords in any case, radix 16 (or 2/10), the vector
    /// comma- or blank-separated, ending in `;` or (as the course files) in a final `,`.
    pub fn parse_coe(path: &Path, text: &str) -> Result<World, Diagnostic> {
        let lower = text.to_ascii_lowercase();
        let radix_at = lower
            .find("memory_initialization_radix")
            .ok_or_else(|| err(path, 1, 1, "missing MEMORY_INITIALIZATION_RADIX"))?;
        let vector_at = lower
            .find("memory_initialization_vector")
            .ok_or_else(|| err(path, 1, 1, "missing MEMORY_INITIALIZATION_VECTOR"))?;
        let line_of = |pos: usize| text[..pos].matches('\n').count() + 1;
        let radix_text: String = lower[radix_at..]
            .split_once('=')
            .map(|(_, r)| r.chars().skip_while(|c| c.is_whitespace()).take_while(|c| c.is_ascii_digit()).collect())
            .unwrap_or_default();
        let radix = match radix_text.as_str() {
            "16" => 16,
            "10" => 10,
            "2" => 2,
            other => {
                return Err(err(path, line_of(radix_at), 1, format!("radix '{other}' is not 2, 10 or 16")));
            }
        };
        let body_start = text[vector_at..]
            .find('=')
            .map(|i| vector_at + i + 1)
            .ok_or_else(|| err(path, line_of(vector_at), 1, "MEMORY_INITIALIZATION_VECTOR needs '='"))?;
        let mut w = World::empty();
        let mut n = 0;
        let mut line = line_of(body_start);
        let mut col = 1;
        let mut tok = String::new();
        let mut tok_pos = (line, col);
        let mut ended = false;
        let mut flush = |tok: &mut String, pos: (usize, usize), n: &mut usize| -> Result<(), Diagnostic> {
            if tok.is_empty() {
                return Ok(());
            }
            // The radix first: a '2' in a radix-2 file is a digit it cannot have.
            let v = u32::from_str_radix(tok, radix).map_err(|_| {
                err(
                    path,
                    pos.0,
                    pos.1,
                    format!("'{tok}' is not a radix-{radix} number (the file's memory_initialization_radix)"),
                )
            })?;
            if v > 3 {
                return Err(err(path, pos.0, pos.1, format!("'{tok}' is not a cell value 0-3")));
            }
            if *n == CELLS {
                return Err(err(path, pos.0, pos.1, "more than 16384 values"));
            }
            w.cells[*n] = Cell::from_bits(v as u8);
            *n += 1;
            tok.clear();
            Ok(())
        };
        for ch in text[body_start..].chars() {
            if ended {
                if !ch.is_whitespace() {
                    return Err(err(path, line, col, "text after the final ';'"));
                }
            } else if ch == ',' || ch.is_whitespace() || ch == ';' {
                flush(&mut tok, tok_pos, &mut n)?;
                ended = ch == ';';
            } else {
                if tok.is_empty() {
                    tok_pos = (line, col);
                }
                tok.push(ch);
            }
            if ch == '\n' {
                line += 1;
                col = 1;
            } else {
                col += 1;
            }
        }
        flush(&mut tok, tok_pos, &mut n)?;
        if n != CELLS {
            return Err(err(path, 0, 0, format!("has {n} values; a world has 16384")));
        }
        Ok(w)
    }

    /// `.coe` exactly as the course files are written (spec §10.2).
    pub fn to_coe(&self) -> String {
        let mut s = String::from("MEMORY_INITIALIZATION_RADIX=16;\nMEMORY_INITIALIZATION_VECTOR=\n\n");
        for (i, chunk) in self.cells.chunks(32).enumerate() {
            if i > 0 {
                s.push('\n');
            }
            for c in chunk {
                s.push(char::from(b'0' + c.bits()));
                s.push(',');
            }
        }
        s
    }

    /// `$readmemh` text ([`kcpsm6::readmemh`]): hex values, `@address` lines and comments.
    pub fn parse_mem(path: &Path, text: &str) -> Result<World, Diagnostic> {
        use kcpsm6::readmemh::{entries, Error};
        let items = entries(text, CELLS).map_err(|e| match e {
            Error::BadAddress { token, line, col } => {
                err(path, line, col, format!("'{token}' is not an address 0000-3FFF"))
            }
            Error::PastEnd { line, col } => err(path, line, col, "value past the last cell (address 3FFF)"),
            Error::UnclosedComment { line, col } => err(path, line, col, "'/*' comment without its '*/'"),
        })?;
        if items.is_empty() {
            return Err(err(path, 0, 0, "no cell values found"));
        }
        let mut w = World::empty();
        for e in items {
            let v = u8::from_str_radix(&e.value, 16)
                .ok()
                .filter(|&v| v <= 3)
                .ok_or_else(|| err(path, e.line, e.col, format!("'{}' is not a cell value 0-3", e.value)))?;
            w.cells[e.address] = Cell::from_bits(v);
        }
        Ok(w)
    }

    /// `.mem`: 16384 lines of one hex digit.
    pub fn to_mem(&self) -> String {
        let mut s = String::with_capacity(CELLS * 2);
        for c in &self.cells {
            s.push(char::from(b'0' + c.bits()));
            s.push('\n');
        }
        s
    }

    /// A 128 x 128 PNG whose pixels are the four cell colours ([`Cell::colour`]).
    pub fn from_png(path: &Path, bytes: &[u8]) -> Result<World, Diagnostic> {
        let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info().map_err(|e| err(path, 0, 0, format!("not a readable PNG: {e}")))?;
        let (w, h) = (reader.info().width, reader.info().height);
        if (w, h) != (SIZE as u32, SIZE as u32) {
            return Err(err(path, 0, 0, format!("image is {w} x {h} pixels; a world is 128 x 128")));
        }
        let mut buf = vec![0; reader.output_buffer_size().unwrap_or(SIZE * SIZE * 4)];
        let info = reader.next_frame(&mut buf).map_err(|e| err(path, 0, 0, format!("not a readable PNG: {e}")))?;
        let channels = info.color_type.samples();
        let mut world = World::empty();
        for y in 0..SIZE {
            for x in 0..SIZE {
                let p = &buf[y * info.line_size + x * channels..][..channels];
                let rgb = match channels {
                    1 | 2 => [p[0], p[0], p[0]],
                    _ => [p[0], p[1], p[2]],
                };
                let cell = Cell::ALL.into_iter().find(|c| c.colour() == rgb).ok_or_else(|| {
                    err(
                        path,
                        0,
                        0,
                        format!(
                            "pixel ({x}, {y}) has colour #{:02X}{:02X}{:02X}; use white (floor), black (line), #B22222 (obstruction) or #1E90FF (reserved)",
                            rgb[0], rgb[1], rgb[2]
                        ),
                    )
                })?;
                world.cells[y * SIZE + x] = cell;
            }
        }
        Ok(world)
    }

    /// A 128 x 128 RGB PNG, one pixel per cell.
    pub fn to_png(&self) -> Vec<u8> {
        let mut rgb = Vec::with_capacity(CELLS * 3);
        for c in &self.cells {
            rgb.extend_from_slice(&c.colour());
        }
        crate::picture::encode_rgb(SIZE as u32, SIZE as u32, &rgb)
    }

    /// The built-in world: border walls, a black-line course from the start cell (64, 64)
    /// heading East with right and left turns (90 and 45 degrees), wall blocks beside it, and
    /// a wall at the end of the line (like the course's Part 1 track, whose bot ends blocked).
    pub fn builtin() -> World {
        let mut w = World::empty();
        let wall = Cell::Obstruction;
        w.fill((0, 0), (127, 1), wall);
        w.fill((0, 126), (127, 127), wall);
        w.fill((0, 0), (1, 127), wall);
        w.fill((126, 0), (127, 127), wall);
        for pair in COURSE.windows(2) {
            let ((x0, y0), (x1, y1)) = (pair[0], pair[1]);
            let (dx, dy) = ((x1 as i16 - x0 as i16).signum(), (y1 as i16 - y0 as i16).signum());
            let (mut x, mut y) = (x0 as i16, y0 as i16);
            loop {
                w.set(x as u8, y as u8, Cell::Line);
                if (x, y) == (x1 as i16, y1 as i16) {
                    break;
                }
                x += dx;
                y += dy;
            }
        }
        for &(a, b) in BLOCKS {
            w.fill(a, b, wall);
        }
        w
    }
}

/// The built-in course: waypoints joined by horizontal, vertical or diagonal lines.
/// E, right to S, left to E, right to SE, right to S, right to W, right to NW, left to W,
/// right to N, left to NW, right to N, and the end of the line below a wall.
pub const COURSE: &[Xy] = &[
    (64, 64),
    (84, 64),
    (84, 76),
    (96, 76),
    (104, 84),
    (104, 100),
    (76, 100),
    (68, 92),
    (44, 92),
    (44, 72),
    (36, 64),
    (36, 48),
];

/// A cell as (column, row).
pub type Xy = (u8, u8);

/// Wall blocks (corner, corner): beside the course, and across its end.
pub const BLOCKS: &[(Xy, Xy)] = &[
    ((88, 58), (91, 61)),   // north-east of the first straight
    ((70, 68), (74, 70)),   // south of the first straight
    ((108, 88), (110, 95)), // east of the long southward run
    ((56, 103), (62, 105)), // south of the westward run
    ((38, 80), (40, 84)),   // west of the northward run
    ((34, 46), (38, 47)),   // the end: a wall right after the last line cell
];
