//! A GTKWave save file for a board waveform: the signals grouped (board pins, the bot's
//! registers, each KCPSM6), each in its radix, the instruction text and status as ASCII,
//! and translate filters that show BotInfo as heading and movement and each CPU's address
//! as `label+offset`.
//!
//! ```
//! use botsim_core::board::gtkw::{Format, SaveFile, View};
//! let mut s = SaveFile::new("w.vcd".as_ref());
//! // 1,024 ps per 200-pixel frame, 1,000 pixels: GTKWave's zoom -10.
//! s.view(View { start_ps: 0, end_ps: 5_120, marker_ps: Some(500) });
//! let f = s.filter("w.labels.txt".as_ref());
//! s.group("Board pins", vec![("TOP.botsim_board.led[15:0]".into(), Format::Binary, None)]);
//! s.group("SYS.APPCPU", vec![("TOP.botsim_board.user.SYS.APPCPU.address[11:0]".into(), Format::Hex, Some(f))]);
//! let text = s.text();
//! assert!(text.contains("[timestart] 0\n*-10.000000 500 -1 -1"));
//! assert!(text.contains("@800200\n-Board pins\n@28\nTOP.botsim_board.led[15:0]\n@1000200\n-Board pins\n"));
//! assert!(text.contains("^1 w.labels.txt\n@2022\nTOP.botsim_board.user.SYS.APPCPU.address[11:0]\n"));
//! ```

use std::path::{Path, PathBuf};

/// How GTKWave shows a signal (its trace flags: right-justified, in a radix).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Binary,
    Hex,
    Decimal,
    /// A vector holding text, a character per byte.
    Ascii,
}

impl Format {
    /// GTKWave's trace flags: right-justify (0x20) with hex 0x2, decimal 0x4, binary 0x8 or
    /// ASCII 0x800; a file translate filter adds 0x2000.
    fn flags(self, filtered: bool) -> u32 {
        let radix = match self {
            Format::Hex => 0x2,
            Format::Decimal => 0x4,
            Format::Binary => 0x8,
            Format::Ascii => 0x800,
        };
        0x20 | radix | if filtered { 0x2000 } else { 0 }
    }
}

/// One signal: its full name as GTKWave lists it (`TOP.a.b[7:0]`), its format, and the
/// translate filter it goes through (an index from [`SaveFile::filter`]).
pub type Signal = (String, Format, Option<usize>);

/// A save file being put together.
pub struct SaveFile {
    dump: PathBuf,
    filters: Vec<PathBuf>,
    groups: Vec<(String, Vec<Signal>)>,
    view: Option<View>,
}

/// What the waveform window shows when it opens: `start_ps` to `end_ps` across the wave
/// pane, the primary marker at `marker_ps`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct View {
    pub start_ps: u64,
    pub end_ps: u64,
    pub marker_ps: Option<u64>,
}

/// The window's size in the save file, and a width a little more than its wave pane's (the
/// window less the hierarchy and signal panes: about 940 pixels): the zoom puts the view's
/// span across this width, so the pane shows no time past the view's end (GTKWave goes back
/// to the start of the dump when the pane would reach past the dump's end).
const WINDOW: (u32, u32) = (1600, 1000);
const WAVE_PANE_PX: f64 = 1000.0;

impl View {
    /// GTKWave's zoom: a frame of 200 pixels is 2^-zoom time units (picoseconds in botsim's
    /// waveforms; GTKWave's `calczoom`).
    fn zoom(&self) -> f64 {
        const PIXELS_PER_FRAME: f64 = 200.0;
        let span = self.end_ps.saturating_sub(self.start_ps).max(1) as f64;
        -(span / WAVE_PANE_PX * PIXELS_PER_FRAME).log2()
    }
}

impl SaveFile {
    pub fn new(dump: &Path) -> SaveFile {
        SaveFile { dump: dump.to_path_buf(), filters: Vec::new(), groups: Vec::new(), view: None }
    }

    /// Open on `view` (without one GTKWave starts at time 0, a picosecond per pixel).
    pub fn view(&mut self, view: View) {
        self.view = Some(view);
    }

    /// A translate filter file (lines `VALUE TEXT`, the value in the signal's radix); its index.
    pub fn filter(&mut self, file: &Path) -> usize {
        self.filters.push(file.to_path_buf());
        self.filters.len()
    }

    pub fn group(&mut self, name: &str, signals: Vec<Signal>) {
        self.groups.push((name.to_string(), signals));
    }

    /// The save file's text.
    pub fn text(&self) -> String {
        let mut s = format!("[*] written by botsim board\n[dumpfile] \"{}\"\n", self.dump.display());
        s.push_str(&format!("[size] {} {}\n[pos] -1 -1\n", WINDOW.0, WINDOW.1));
        if let Some(v) = &self.view {
            // The zoom, the primary marker (-1: none), then the 26 named markers, unset.
            let marker = v.marker_ps.map_or("-1".to_string(), |m| m.to_string());
            s.push_str(&format!("[timestart] {}\n*{:.6} {marker}{}\n", v.start_ps, v.zoom(), " -1".repeat(26)));
        }
        s.push_str("[sst_width] 260\n[signals_width] 360\n[sst_expanded] 1\n");
        for (name, signals) in &self.groups {
            s.push_str(&format!("@800200\n-{name}\n"));
            for (signal, format, filter) in signals {
                if let Some(k) = filter {
                    s.push_str(&format!("^{k} {}\n", self.filters[k - 1].display()));
                }
                s.push_str(&format!("@{:x}\n{signal}\n", format.flags(filter.is_some())));
            }
            s.push_str(&format!("@1000200\n-{name}\n"));
        }
        s
    }
}

/// The lines of a translate filter: `value` in hex of `digits` digits, and its text.
pub fn filter_text(values: impl IntoIterator<Item = (u32, String)>, digits: usize) -> String {
    values.into_iter().map(|(v, t)| format!("{v:0digits$X} {t}\n")).collect()
}
