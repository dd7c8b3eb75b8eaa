//! `botsim run --cpu-trace` and `--break`: the bot on the ISS, one instruction at a time, each
//! one given to the source-level tracer (kcpsm6::trace, as `botsim board --cpu-trace` writes
//! it) and checked against the breakpoints (botsim_core::debug, as `botsim board --break`).

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use botsim::files::write_atomic;
use botsim::kcpsm6::iss::Retired;
use botsim::kcpsm6::source::SourceMap;
use botsim::kcpsm6::trace::Tracer;
use botsim::sim::rtl::Point;
use botsim::sim::{Backend, CpuAt, Error};
use botsim::{IssBot, MotCtl, Snapshot, PS_PER_CYCLE};
use botsim_core::debug::{describe_pc, Breaks};

/// A breakpoint that stopped the run.
#[derive(Clone, Debug)]
pub struct Hit {
    pub what: String,
    pub pc: u16,
    /// The instruction's D cycle, and the sample whose iteration it is in.
    pub cycle: u64,
    pub sample: u64,
}

/// The trace being written: under a temporary name until [`Watched::finish`].
struct Trace {
    tracer: Tracer,
    out: BufWriter<std::fs::File>,
    tmp: PathBuf,
    file: PathBuf,
    from: Option<Point>,
    to: Option<Point>,
    error: Option<std::io::Error>,
}

impl Trace {
    /// Whether the instruction of `cycle` in the iteration of `sample` is in the window.
    fn covers(&self, sample: u64, cycle: u64) -> bool {
        let after = |p: Option<Point>, or: bool| match p {
            None => or,
            Some(Point::Sample(s)) => sample >= s,
            Some(Point::Cycle(c)) => cycle >= c,
        };
        let before = match self.to {
            None => true,
            Some(Point::Sample(s)) => sample <= s,
            Some(Point::Cycle(c)) => cycle < c,
        };
        after(self.from, true) && before
    }
}

/// The bot on the ISS, watched.
pub struct Watched {
    bot: IssBot,
    trace: Option<Trace>,
    breaks: Breaks,
    map: Option<SourceMap>,
    pub hit: Option<Hit>,
}

impl Watched {
    pub fn new(bot: IssBot, breaks: Breaks, map: Option<SourceMap>) -> Watched {
        Watched { bot, trace: None, breaks, map, hit: None }
    }

    /// Trace into `file` the instructions from `from` to `to` (samples or cycles); the profile
    /// counts them all.
    pub fn trace(&mut self, file: &Path, from: Option<Point>, to: Option<Point>) -> Result<(), String> {
        let name = file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let tmp = file.with_file_name(format!(".{name}.part"));
        let f = std::fs::File::create(&tmp).map_err(|e| format!("{}: error: cannot write: {e}", tmp.display()))?;
        self.trace = Some(Trace {
            tracer: Tracer::new(self.map.clone().unwrap_or_default(), 0, u64::MAX),
            out: BufWriter::with_capacity(1 << 20, f),
            tmp,
            file: file.to_path_buf(),
            from,
            to,
            error: None,
        });
        Ok(())
    }

    /// The line that says where a breakpoint stopped the run.
    pub fn stop_message(&self) -> Option<String> {
        let h = self.hit.as_ref()?;
        Some(format!(
            "stopped by --break {}: {} in cycle {} ({:.6} ms), in sample {}'s iteration",
            h.what,
            describe_pc(self.map.as_ref(), h.pc),
            h.cycle,
            (h.cycle * PS_PER_CYCLE) as f64 / 1e9,
            h.sample
        ))
    }

    /// Close the trace: it takes its name, and the profile is written beside it
    /// (`<name>.profile.txt`); the files written.
    pub fn finish(&mut self) -> Result<Vec<PathBuf>, String> {
        let Some(mut t) = self.trace.take() else { return Ok(Vec::new()) };
        let flushed = t.out.flush();
        if let Some(e) = t.error.take().or(flushed.err()) {
            let _ = std::fs::remove_file(&t.tmp);
            return Err(format!("{}: error: cannot write: {e}", t.file.display()));
        }
        std::fs::rename(&t.tmp, &t.file).map_err(|e| format!("{}: error: cannot write: {e}", t.file.display()))?;
        let stem = t.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let profile = t.file.with_file_name(format!("{stem}.profile.txt"));
        write_atomic(&profile, t.tracer.profile().as_bytes())?;
        Ok(vec![t.file.clone(), profile])
    }
}

impl Backend for Watched {
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        let sample = self.bot.samples();
        let (trace, breaks, hit) = (&mut self.trace, &self.breaks, &mut self.hit);
        let watch = |r: &Retired, end: u64| {
            if let Some(t) = trace.as_mut() {
                let result = if t.covers(sample, r.cycle) {
                    t.tracer.retired(r, end, Some(end * PS_PER_CYCLE), &mut t.out)
                } else {
                    t.tracer.retired(r, end, Some(end * PS_PER_CYCLE), &mut std::io::sink())
                };
                if let Err(e) = result {
                    t.error.get_or_insert(e);
                }
            }
            match breaks.hit(r) {
                Some(what) => {
                    *hit = Some(Hit { what: what.to_string(), pc: r.pc, cycle: r.cycle, sample });
                    true
                }
                None => false,
            }
        };
        match self.bot.wait_update_watched(budget, watch)? {
            Some(s) => Ok(s),
            None => Err(Error::Stopped("a breakpoint".into())),
        }
    }
    fn update_budget(&self) -> u64 {
        self.bot.update_budget()
    }
    fn set_update_budget(&mut self, cycles: u64) {
        self.bot.set_update_budget(cycles)
    }
    fn set_motors(&mut self, m: MotCtl) {
        self.bot.set_motors(m)
    }
    fn cycle(&self) -> u64 {
        self.bot.cycle()
    }
    fn cpu_at(&self) -> CpuAt {
        self.bot.cpu_at()
    }
}
