//! `botsim bench`: simulation speed of each backend on this machine.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use botsim::{Firmware, IssBot, MotCtl, RtlBot, Timing, World};

/// Measure simulation speed: the RTL (Verilator, tracing compiled in but off), the RTL writing a
/// full VCD, the ISS backend, and Icarus Verilog on the same RTL when it is installed; all on
/// the built-in world driving forward, in `hw` timing (Icarus and VCD: `fast`).
#[derive(clap::Args)]
#[command(after_help = "Examples:\n  botsim bench\n  botsim bench --quick --json")]
pub struct Args {
    /// Shorter runs (less precise)
    #[arg(long)]
    quick: bool,
    /// Print the figures as JSON
    #[arg(long)]
    json: bool,
}

/// Mcycles/s of `cycles` simulated in `seconds`.
fn rate(cycles: u64, seconds: f64) -> f64 {
    cycles as f64 / seconds.max(1e-9) / 1e6
}

fn rtl(cycles: u64) -> Result<f64, String> {
    let mut bot = RtlBot::builder().motors(MotCtl::FORWARD).build().map_err(|e| e.to_string())?;
    let t = Instant::now();
    bot.run(cycles).map_err(|e| e.to_string())?;
    Ok(rate(cycles, t.elapsed().as_secs_f64()))
}

/// The bot's RTL under botsim's loop and under Verilator's minimal loop, fresh models in
/// alternating rounds: (botsim's rate, the minimal loop's, the median of the rounds' cost).
fn rtl_against_minimal(cycles: u64, rounds: usize) -> Result<(f64, f64, f64), String> {
    let (mut ours, mut minimal, mut costs) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..rounds {
        let a = rtl(cycles)?;
        let mut bot = RtlBot::builder().motors(MotCtl::FORWARD).build().map_err(|e| e.to_string())?;
        let t = Instant::now();
        bot.bench_minimal(cycles);
        let b = rate(cycles, t.elapsed().as_secs_f64());
        ours.push(a);
        minimal.push(b);
        costs.push(b / a - 1.0);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    Ok((median(&mut ours), median(&mut minimal), median(&mut costs)))
}

fn rtl_vcd(cycles: u64, dir: &Path) -> Result<f64, String> {
    let path = dir.join("bench.vcd");
    let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
    let mut bot =
        RtlBot::builder().firmware(fw).motors(MotCtl::FORWARD).vcd(&path).build().map_err(|e| e.to_string())?;
    let t = Instant::now();
    bot.run(cycles).map_err(|e| e.to_string())?;
    bot.close_vcd().map_err(|e| e.to_string())?;
    let r = rate(cycles, t.elapsed().as_secs_f64());
    let _ = std::fs::remove_file(&path);
    Ok(r)
}

fn iss(samples: u64) -> Result<f64, String> {
    let image = Firmware::default().assemble().map_err(|d| d.to_string())?;
    let mut bot = IssBot::new(&image, World::builtin()).map_err(|e| e.to_string())?;
    bot.set_motors(MotCtl::FORWARD);
    let t = Instant::now();
    for _ in 0..samples {
        bot.wait_update_within(Timing::Hw.update_budget()).map_err(|e| e.to_string())?;
    }
    Ok(rate(bot.cycle(), t.elapsed().as_secs_f64()))
}

/// Icarus through the repository's one runner (scripts/lib/icarus-bot.sh, fast firmware):
/// None outside a checkout or without Icarus.
fn icarus(samples: u32) -> Option<f64> {
    let runner = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scripts/lib/icarus-bot.sh");
    if !runner.exists() || Command::new("iverilog").arg("-V").output().is_err() {
        return None;
    }
    let out = Command::new("bash")
        .arg(&runner)
        .arg(samples.to_string())
        .env("BOTSIM", std::env::current_exe().ok()?)
        .output()
        .ok()?;
    // stderr: "icarus: CYCLES cycles in SECONDS s"
    let report = String::from_utf8_lossy(&out.stderr);
    let mut words = report.lines().last()?.split_whitespace().skip(1);
    let cycles: u64 = words.next()?.parse().ok()?;
    let seconds: f64 = words.nth(2)?.parse().ok()?;
    out.status.success().then(|| rate(cycles, seconds))
}

pub fn run(args: Args) -> Result<(), String> {
    let dir = std::env::temp_dir().join(format!("botsim-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: error: {e}", dir.display()))?;
    let scale = if args.quick { 1 } else { 5 };
    let result = (|| {
        let (rtl, minimal, cost) = rtl_against_minimal(1_000_000 * scale, 7)?;
        let vcd = rtl_vcd(60_000 * scale, &dir)?;
        let iss = iss(20 * scale)?;
        let icarus = icarus(5 * scale as u32);
        Ok::<_, String>((rtl, minimal, cost, vcd, iss, icarus))
    })();
    let _ = std::fs::remove_dir_all(&dir);
    let (rtl, minimal, cost, vcd, iss, icarus) = result?;
    let real_time = 100.0; // the board's 100 MHz
    if args.json {
        let v = serde_json::json!({
            "rtl_mcycles_per_s": rtl,
            "rtl_minimal_harness_mcycles_per_s": minimal,
            "rtl_harness_cost": cost,
            "rtl_vcd_mcycles_per_s": vcd,
            "iss_mcycles_per_s": iss,
            "icarus_mcycles_per_s": icarus,
            "rtl_vs_icarus": icarus.map(|i| rtl / i),
            "real_time_mhz": real_time,
        });
        println!("{v}");
        return Ok(());
    }
    println!("{:<34} {:>12} {:>14} {:>12}", "backend", "Mcycles/s", "x real time", "x Icarus");
    let row = |name: &str, r: f64| {
        let vs = icarus.map_or("-".to_string(), |i| format!("{:.0}", r / i));
        println!("{name:<34} {r:>12.2} {:>14.3} {vs:>12}", r / real_time);
    };
    row("RTL (Verilator, trace off)", rtl);
    row("RTL, Verilator's minimal loop", minimal);
    row("RTL writing a full VCD", vcd);
    row("ISS backend (fast path)", iss);
    if let Some(i) = icarus {
        row("Icarus Verilog 11 (same RTL)", i);
    }
    println!(
        "botsim's RTL loop costs {:+.1} % against the minimal loop (median of 7 side-by-side rounds)",
        cost * 100.0
    );
    Ok(())
}
