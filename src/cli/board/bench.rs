//! `botsim board --bench`: the board's speed, measured side by side in one run.

use std::path::Path;
use std::time::Instant;

use botsim::board::build::CpuModel;
use botsim::board::iss::Host;
use botsim::board::model::{Event, FastForward, Printing, RawEvent, Stop, RECORDS};
use botsim::{World, PS_PER_CYCLE};
use botsim_core::board::display::Display;
use botsim_core::frontend::plan::Rom;

use super::prepare::{prepare, Prepared};
use super::report::Busy;
use super::session::{load, simulate, Outcome};
use super::{Args, BotArg, CpuArg};

/// `--bench`: with the ISS (the default), this run against the same run on the all-RTL board;
/// with `--cpu rtl`, the board harness against a minimal one.
pub fn run(a: &Args, p: &Prepared) -> Result<(), String> {
    if p.cpu == CpuModel::Iss {
        return against_rtl(a, p);
    }
    let seconds = a.seconds.unwrap_or(0.05);
    bench(&p.built.library, &p.world, &p.plan.roms, seconds, a.json, &|| p.main_host())
}

/// Rounds of a run against the all-RTL board.
const RUN_ROUNDS: usize = 3;

/// The run as the arguments make it (its stop, its stimulus, its records, the fast-forward),
/// timed against the same run on the all-RTL board (`--cpu rtl --bot rtl`, every edge), the
/// two alternating; the speed-up is the median of the rounds' ratios. What a run costs besides
/// its simulation (loading the model, putting the records together) is reported apart.
fn against_rtl(a: &Args, p: &Prepared) -> Result<(), String> {
    let quiet = |mut x: Args| {
        (x.quiet, x.json, x.bench) = (true, false, false);
        x
    };
    let mut rtl_args = quiet(a.clone());
    // (A design without a bot has nothing to set it for.)
    (rtl_args.cpu, rtl_args.bot) = (Some(CpuArg::Rtl), p.plan.has_own_bot().then_some(BotArg::Rtl));
    let rtl = prepare(&rtl_args)?;
    let run_args = quiet(a.clone());
    let (mut fast, mut slow, mut ratios, mut overhead) = (vec![], vec![], vec![], vec![]);
    let (mut frames_fast, mut frames_slow) = (vec![], vec![]);
    let mut last = None;
    for _ in 0..RUN_ROUNDS {
        let t = Instant::now();
        let o = simulate(&run_args, p)?;
        overhead.push(t.elapsed().as_secs_f64() - o.wall_seconds);
        let r = simulate(&rtl_args, &rtl)?;
        let rate = |o: &Outcome| o.sim_ps as f64 / 1e4 / o.wall_seconds.max(1e-9) / 1e6;
        let frame_rate = |o: &Outcome| o.rec.frames_seen as f64 / o.wall_seconds.max(1e-9);
        let (f, s) = (rate(&o), rate(&r));
        fast.push(f);
        slow.push(s);
        ratios.push(f / s);
        frames_fast.push(frame_rate(&o));
        frames_slow.push(frame_rate(&r));
        last = Some(o);
    }
    let o = last.expect("at least one round");
    let (f, s, x, ov) = (median(&mut fast), median(&mut slow), median(&mut ratios), median(&mut overhead));
    // With --frames: VGA frames simulated (and written) a second of wall time, each board's.
    let frames = (o.rec.frames_seen > 0).then(|| (median(&mut frames_fast), median(&mut frames_slow)));
    let skipped = if o.sim_ps == 0 { 0.0 } else { o.skipped_ps as f64 / o.sim_ps as f64 };
    let busy = super::report::busy_of(p, &o.busy, &o.cut);
    if a.json {
        println!(
            "{}",
            serde_json::json!({
                "mcycles_per_s": f, "real_time": f / 100.0, "rtl_mcycles_per_s": s, "speedup": x,
                "rounds": RUN_ROUNDS, "simulated_seconds": o.sim_ps as f64 / 1e12,
                "skips": o.skips, "skipped_fraction": skipped, "evaluations": o.evaluations,
                "overhead_seconds": ov, "off_because": o.fast_forward_off,
                "kept_busy_by": busy.as_ref().map(Busy::json),
                "vga_frames": o.rec.frames_seen,
                "frames_per_s": frames.map(|f| f.0), "rtl_frames_per_s": frames.map(|f| f.1),
            })
        );
        return Ok(());
    }
    println!(
        "botsim board --bench: this run, {:.3} s of board time, {RUN_ROUNDS} rounds side by side with the same run on the all-RTL board",
        o.sim_ps as f64 / 1e12
    );
    println!(
        "  this run       {f:9.2} Mcycles/s  {:7.3} x real time   skipped {:.1} % of it in {} skips",
        f / 100.0,
        skipped * 100.0,
        o.skips
    );
    println!("  all-RTL board  {s:9.2} Mcycles/s  {:7.3} x real time", s / 100.0);
    if let Some((ff, fs)) = frames {
        println!(
            "  VGA frames     {ff:9.2} a second simulated and written by this run, {fs:.2} by the all-RTL board ({} in the run; a monitor shows 60)",
            o.rec.frames_seen
        );
    }
    println!("  {x:.2} x the all-RTL board (the median of the rounds' ratios); besides its simulation, a run took {ov:.3} s (loading the model, the records)");
    if let Some(why) = &o.fast_forward_off {
        println!("  no fast-forward: {why}");
    } else if let Some(b) = busy {
        println!("  what kept it from skipping more: {}, {}", b.describe(), b.why());
    }
    Ok(())
}

/// Rounds of `--bench`.
const ROUNDS: usize = 7;

/// The board harness on a fresh model of `library`, the reset released from the start, for
/// `cycles` of 100 MHz; its events decoded as a run decodes them. Mcycles/s.
fn board_rate(
    library: &Path,
    world: &World,
    roms: &[Rom],
    host: Option<Box<Host>>,
    cycles: u64,
    fast_forward: bool,
) -> Result<f64, String> {
    let mut m = load(library, world, roms, host, &Printing::SILENT)?;
    m.set_inputs(false, 0, 0);
    m.fast_forward(if fast_forward { FastForward::Recorded } else { FastForward::Off });
    let mut buf = vec![RawEvent::default(); RECORDS];
    let mut display = Display::default();
    let t = Instant::now();
    loop {
        let (stop, n) = m.run(cycles * PS_PER_CYCLE, u64::MAX, &mut buf);
        let events: Vec<Event> = buf[..n].iter().filter_map(Event::of).collect();
        for (i, e) in events.iter().enumerate() {
            match *e {
                Event::Display { time_ps, an, seg, dp } => display.pins(time_ps, an, seg, dp),
                Event::Repeat { events: per, period_ps, count, .. } => {
                    let pins: Vec<_> = events[i - per..i]
                        .iter()
                        .filter_map(|p| match *p {
                            Event::Display { time_ps, an, seg, dp } => Some((time_ps, an, seg, dp)),
                            _ => None,
                        })
                        .collect();
                    display.repeat(&pins, period_ps, count);
                }
                _ => {}
            }
        }
        if stop != Stop::BufferFull {
            break;
        }
    }
    Ok(cycles as f64 / t.elapsed().as_secs_f64() / 1e6)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `--bench`: both harnesses on fresh models of the same library, the reset released from
/// the start, alternating. The cost is the median of the rounds' ratios (each round
/// measures both side by side).
fn bench(
    library: &Path,
    world: &World,
    roms: &[Rom],
    seconds: f64,
    json: bool,
    host: &dyn Fn() -> Result<Option<Box<Host>>, String>,
) -> Result<(), String> {
    let cycles = (seconds * 1e8) as u64;
    let (mut board_rates, mut minimal_rates) = (Vec::new(), Vec::new());
    for _ in 0..ROUNDS {
        board_rates.push(board_rate(library, world, roms, host()?, cycles, false)?);
        let mut m = load(library, world, roms, host()?, &Printing::SILENT)?;
        m.set_inputs(false, 0, 0);
        let t = Instant::now();
        m.bench_minimal(cycles);
        minimal_rates.push(cycles as f64 / t.elapsed().as_secs_f64() / 1e6);
    }
    let mut costs: Vec<f64> = minimal_rates.iter().zip(&board_rates).map(|(m, b)| m / b - 1.0).collect();
    let cost = median(&mut costs);
    let best = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    // Noise on a shared machine only slows a run down: the best rates are the least disturbed.
    let best_cost = best(&minimal_rates) / best(&board_rates) - 1.0;
    let (b, m) = (median(&mut board_rates), median(&mut minimal_rates));
    if json {
        println!(
            "{}",
            serde_json::json!({"board_mcycles_per_s": b, "minimal_mcycles_per_s": m, "board_cost": cost, "board_cost_best": best_cost, "cycles": cycles, "rounds": ROUNDS})
        );
    } else {
        println!(
            "board harness {b:.2} Mcycles/s, minimal harness {m:.2} Mcycles/s (medians): the board harness costs {:+.1} % (median of {ROUNDS} side-by-side rounds of {cycles} cycles of 100 MHz; best against best {:+.1} %)",
            cost * 100.0,
            best_cost * 100.0
        );
    }
    Ok(())
}
