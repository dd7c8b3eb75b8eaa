//! A waveform of part of a run: a VCD of the `bot` model that opens at a sample or cycle and
//! closes after one, written under a temporary name and moved to its name only when complete.
//! Dropped before [`VcdWindow::finish`] (an error ended the run), it leaves no file.
//!
//! ```
//! use botsim::sim::rtl::{Point, VcdWindow};
//! use botsim::{RtlBot, Timing};
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("s2.vcd");
//! let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
//! let mut window = VcdWindow::new(path.clone(), Some(Point::Sample(2)), Some(Point::Sample(2)));
//! for k in 0..4 {
//!     window.before_sample(&mut bot, k).unwrap();
//!     bot.wait_update().unwrap();
//!     window.after_sample(&mut bot, k).unwrap();
//! }
//! assert!(window.finish(&mut bot).unwrap());
//! assert!(std::fs::read_to_string(&path).unwrap().contains("upd_sysregs"));
//! ```

use std::path::{Path, PathBuf};

use super::RtlBot;
use crate::sim::Error;

/// Where a window opens or closes: at the start of a sample (its wait), or at a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Point {
    Sample(u64),
    Cycle(u64),
}

impl std::str::FromStr for Point {
    type Err = String;

    /// `10` (sample 10) or `2500000c` (cycle 2,500,000).
    fn from_str(s: &str) -> Result<Point, String> {
        let bad = || format!("expected a sample number or a cycle number with a 'c' suffix, found '{s}'");
        match s.strip_suffix('c') {
            Some(c) => c.parse().map(Point::Cycle).map_err(|_| bad()),
            None => s.parse().map(Point::Sample).map_err(|_| bad()),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    Before,
    Open,
    Closed,
}

/// A VCD window over a run of an [`RtlBot`]: from `from` (default: the start) to `to` (default:
/// the end). The caller tells it where the run is ([`VcdWindow::before_sample`],
/// [`VcdWindow::after_sample`], cycle boundaries) and finishes it at the end.
pub struct VcdWindow {
    path: PathBuf,
    part: PathBuf,
    from: Option<Point>,
    to: Option<Point>,
    state: State,
    finished: bool,
}

impl VcdWindow {
    pub fn new(path: PathBuf, from: Option<Point>, to: Option<Point>) -> VcdWindow {
        let part = path.with_file_name(format!(".{}.part", path.file_name().unwrap_or_default().to_string_lossy()));
        VcdWindow { path, part, from, to, state: State::Before, finished: false }
    }

    /// The file the waveform goes to.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file it is written to until it is finished (then renamed to [`VcdWindow::path`]).
    pub fn part(&self) -> &Path {
        &self.part
    }

    fn open(&mut self, bot: &mut RtlBot) -> Result<(), Error> {
        bot.open_vcd(&self.part)?;
        self.state = State::Open;
        Ok(())
    }

    fn close(&mut self, bot: &mut RtlBot) -> Result<(), Error> {
        let open = self.state == State::Open;
        self.state = State::Closed;
        if open {
            bot.close_vcd()?;
        }
        Ok(())
    }

    /// Before waiting for sample `k`: open a whole-run window or one that starts at `k`.
    pub fn before_sample(&mut self, bot: &mut RtlBot, k: u64) -> Result<(), Error> {
        match (self.state, self.from) {
            (State::Before, None) => self.open(bot),
            (State::Before, Some(Point::Sample(s))) if k >= s => {
                if k > 0 {
                    // The run stands at the first cycle of sample k-1's pulse: start after it.
                    bot.run(2)?;
                }
                self.open(bot)
            }
            _ => Ok(()),
        }
    }

    /// After sample `k`'s pulse began: close a window that ends at `k`, with the whole pulse.
    pub fn after_sample(&mut self, bot: &mut RtlBot, k: u64) -> Result<(), Error> {
        if let (State::Open, Some(Point::Sample(s))) = (self.state, self.to) {
            if k >= s {
                bot.run(3)?;
                self.close(bot)?;
            }
        }
        Ok(())
    }

    /// The next cycle at which the window opens or closes, if that is given in cycles: a wait
    /// must stop there and call [`VcdWindow::cross_boundary`].
    pub fn boundary(&self) -> Option<u64> {
        match (self.state, self.from, self.to) {
            (State::Before, Some(Point::Cycle(c)), _) => Some(c),
            (State::Open, _, Some(Point::Cycle(c))) => Some(c),
            _ => None,
        }
    }

    /// The run reached [`VcdWindow::boundary`]: open or close.
    pub fn cross_boundary(&mut self, bot: &mut RtlBot) -> Result<(), Error> {
        match self.state {
            State::Before => self.open(bot),
            _ => self.close(bot),
        }
    }

    /// The run is over (normally or by Ctrl-C): close the VCD and move it to its name. False
    /// when the window was never reached (no file).
    pub fn finish(&mut self, bot: &mut RtlBot) -> Result<bool, Error> {
        self.close(bot)?;
        if !self.part.exists() {
            self.finished = true;
            return Ok(false);
        }
        // On failure the part stays unfinished, and Drop removes it.
        std::fs::rename(&self.part, &self.path).map_err(|e| {
            Error::Io(format!("{}: error: cannot write file: {}", self.path.display(), kcpsm6::diag::io_reason(&e)))
        })?;
        self.finished = true;
        Ok(true)
    }
}

impl Drop for VcdWindow {
    /// Not finished: an error ended the run, and a half-written waveform is not left behind.
    fn drop(&mut self) {
        if !self.finished {
            let _ = std::fs::remove_file(&self.part);
        }
    }
}
