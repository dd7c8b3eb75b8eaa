//! `botsim board --bench`: the board's speed, measured side by side in one run.

use std::path::Path;
use std::time::Instant;

use botsim::board::build::{build, BotKind, CpuModel};
use botsim::board::iss::Host;
use botsim::board::model::{Event, FastForward, Printing, RawEvent, Stop};
use botsim::World;
use botsim_core::board::display::Display;
use botsim_core::board::plan::Rom;

use super::prepare::Prepared;
use super::session::load;
use super::Args;

/// `--bench`: with the ISS (the default), the ISS board against the all-RTL board of the same
/// design; with `--cpu rtl`, the board harness against a minimal one.
pub fn run(a: &Args, p: &Prepared) -> Result<(), String> {
    let seconds = a.seconds.unwrap_or(0.05);
    if p.cpu == CpuModel::Iss {
        let rtl = build(&p.plan, &p.params, CpuModel::Rtl, BotKind::Rtl, false, a.quiet || a.json)
            .map_err(|e| e.to_string())?;
        let ff = p.main_bot == BotKind::Model && !a.no_fast_forward;
        return bench_iss([&rtl.library, &p.built.library], &p.world, &p.plan.roms, seconds, a.json, ff, &|| {
            p.main_host()
        });
    }
    bench(&p.built.library, &p.world, &p.plan.roms, seconds, a.json, &|| p.main_host())
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
    let mut buf = vec![RawEvent::default(); 4096];
    let mut display = Display::default();
    let t = Instant::now();
    loop {
        let (stop, n) = m.run(cycles * 10_000, u64::MAX, &mut buf);
        for e in buf[..n].iter().filter_map(Event::of) {
            if let Event::Display { time_ps, an, seg, dp } = e {
                display.pins(time_ps, an, seg, dp);
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

/// `--bench --cpu iss`: the ISS board against the all-RTL board of the same design (and,
/// with `fast_forward`, the ISS board fast-forwarding), alternating rounds; each speed-up is
/// the median of the rounds' ratios.
fn bench_iss(
    [rtl, iss]: [&Path; 2],
    world: &World,
    roms: &[Rom],
    seconds: f64,
    json: bool,
    fast_forward: bool,
    host: &dyn Fn() -> Result<Option<Box<Host>>, String>,
) -> Result<(), String> {
    let cycles = (seconds * 1e8) as u64;
    let (mut r, mut i, mut f, mut ratios, mut ff_ratios) = (vec![], vec![], vec![], vec![], vec![]);
    for _ in 0..ROUNDS {
        let a = board_rate(rtl, world, roms, Some(Host::new(Vec::new(), false)), cycles, false)?;
        let b = board_rate(iss, world, roms, host()?, cycles, false)?;
        r.push(a);
        i.push(b);
        ratios.push(b / a);
        if fast_forward {
            let c = board_rate(iss, world, roms, host()?, cycles, true)?;
            f.push(c);
            ff_ratios.push(c / a);
        }
    }
    let (r, i, x) = (median(&mut r), median(&mut i), median(&mut ratios));
    let (f, fx) = (fast_forward.then(|| median(&mut f)), fast_forward.then(|| median(&mut ff_ratios)));
    if json {
        println!(
            "{}",
            serde_json::json!({"iss_board_mcycles_per_s": i, "rtl_board_mcycles_per_s": r, "speedup": x,
                "fast_forward_mcycles_per_s": f, "fast_forward_speedup": fx, "cycles": cycles, "rounds": ROUNDS})
        );
    } else {
        println!(
            "ISS board {i:.2} Mcycles/s, all-RTL board {r:.2} Mcycles/s (medians): {x:.2} x (median of {ROUNDS} side-by-side rounds of {cycles} cycles of 100 MHz; {:.3} x the board's real time)",
            i / 100.0
        );
        if let (Some(f), Some(fx)) = (f, fx) {
            println!(
                "with the fast-forward {f:.2} Mcycles/s of board time: {fx:.2} x the all-RTL board ({:.3} x the board's real time)",
                f / 100.0
            );
        }
    }
    Ok(())
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
