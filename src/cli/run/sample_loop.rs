//! The sample loop: wait for each upd_sysregs pulse within the update budget, give the
//! snapshot to the driver, apply its MotCtl; stop early on Ctrl-C, and open or close the
//! waveform window on the way.

use std::path::Path;

use botsim::sim::rtl::VcdWindow;
use botsim::{Backend, Error, RtlBot, Snapshot};

use super::watch::Watched;
use crate::cli::interrupted;

/// What runs the bot: the RTL (which can also write a waveform), the ISS watched by a trace
/// and breakpoints, or another [`Backend`].
pub enum Engine {
    Rtl(RtlBot),
    Watched(Box<Watched>),
    Other(Box<dyn Backend>),
}

impl Engine {
    pub fn backend(&mut self) -> &mut dyn Backend {
        match self {
            Engine::Rtl(b) => b,
            Engine::Watched(b) => b.as_mut(),
            Engine::Other(b) => b.as_mut(),
        }
    }

    /// The watched ISS, if that is what runs.
    pub fn watched(&mut self) -> Option<&mut Watched> {
        match self {
            Engine::Watched(w) => Some(w),
            _ => None,
        }
    }

    /// The RTL model, for the waveform window (the plan allows a window only with it).
    fn rtl(&mut self) -> &mut RtlBot {
        match self {
            Engine::Rtl(b) => b,
            _ => unreachable!("a waveform is planned only with the RTL backend"),
        }
    }
}

/// Why the loop stopped before its last sample: Ctrl-C, or a breakpoint (the watched ISS
/// says which).
pub struct Interrupted {
    pub sample: u64,
    pub cycle: u64,
    pub by_break: bool,
}

/// Cycles between two looks at the Ctrl-C flag (~0.07 s of RTL time here).
const CHECK_EVERY: u64 = 1 << 20;

/// Run samples 0..=`samples`, calling `each(k, snapshot)` (which returns the MotCtl for the
/// next iteration and whether to stop). Returns where Ctrl-C stopped it, if it did.
pub fn run(
    engine: &mut Engine,
    mut window: Option<&mut VcdWindow>,
    samples: u64,
    mut each: impl FnMut(u64, &Snapshot) -> Result<(botsim::MotCtl, bool), String>,
) -> Result<Option<Interrupted>, String> {
    let path = window.as_ref().map(|w| w.path().to_path_buf());
    // One line per failure: a waveform write names its file, anything else its sample.
    let fail = |e: Error, k: u64| match e {
        Error::Waveform(why) => {
            let p = path.as_deref().unwrap_or(Path::new("waveform"));
            format!("{}: error: cannot write file: {why} (in sample {k})", p.display())
        }
        Error::Io(msg) => msg,
        e => format!("error: sample {k}: {e}"),
    };
    for k in 0..=samples {
        if let Some(w) = window.as_deref_mut() {
            w.before_sample(engine.rtl(), k).map_err(|e| fail(e, k))?;
        }
        let s = match next_sample(engine, window.as_deref_mut()) {
            Ok(Some(s)) => s,
            Ok(None) => return Ok(Some(Interrupted { sample: k, cycle: engine.backend().cycle(), by_break: false })),
            Err(Error::Stopped(_)) if engine.watched().is_some_and(|w| w.hit.is_some()) => {
                return Ok(Some(Interrupted { sample: k, cycle: engine.backend().cycle(), by_break: true }))
            }
            Err(e) => return Err(fail(e, k)),
        };
        let (m, stop) = each(k, &s)?;
        if let Some(w) = window.as_deref_mut() {
            w.after_sample(engine.rtl(), k).map_err(|e| fail(e, k))?;
        }
        if stop {
            break;
        }
        engine.backend().set_motors(m);
    }
    Ok(None)
}

/// Wait for the next pulse within the bot's update budget, crossing a window boundary given
/// in cycles on the way; `None` when Ctrl-C was pressed.
fn next_sample(engine: &mut Engine, mut window: Option<&mut VcdWindow>) -> Result<Option<Snapshot>, Error> {
    let budget = engine.backend().update_budget();
    let deadline = engine.backend().cycle() + budget;
    loop {
        if interrupted() {
            return Ok(None);
        }
        let bot = engine.backend();
        let now = bot.cycle();
        if now >= deadline {
            return Err(Error::no_update(budget, now, bot.cpu_at()));
        }
        let boundary = window.as_ref().and_then(|w| w.boundary());
        let stop = boundary.filter(|&c| c > now).unwrap_or(deadline).min(deadline).min(now + CHECK_EVERY);
        if boundary.map_or(true, |c| c > now) {
            match bot.wait_update_within(stop - now) {
                Ok(s) => return Ok(Some(s)),
                Err(Error::Timeout { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        if let (Some(w), Some(c)) = (window.as_deref_mut(), boundary) {
            if engine.backend().cycle() >= c {
                w.cross_boundary(engine.rtl())?;
            }
        }
    }
}
