//! `botsim run --live`: the bot alone (BotSim 2.0 on the ISS, cycle for cycle the RTL's
//! results) paced against the wall clock, its motors from the page (or from `--driver` or
//! `--motors`), the world, the bot, its path and registers in the page.
//!
//! The firmware reads MotCtl_in once per main-loop iteration, at its start: the run goes
//! sample by sample, and motors set by a page apply from the next iteration on (the one after
//! the last sample the page has seen), as a script's next segment does. They are kept per
//! iteration, so `--record` (or the page's Save) writes a motor script that `botsim run
//! --motors FILE` replays exactly.

use std::time::{Duration, Instant};

use botsim::{Backend, IssBot, MotCtl, PS_PER_CYCLE};
use botsim_live::protocol::{BoardView, BotView, Command};
use serde_json::json;

use super::plan::Plan;
use super::Args;
use crate::cli::args::BackendKind;
use crate::cli::live::{bot_view, sample_entry, world_json, Pace, Rate};

/// The most samples a second the pages get (each is a log entry): `--timing fast` at real
/// time would be 50,000; it runs slower than real time instead.
const MAX_SAMPLES_PER_S: f64 = 2_000.0;
/// How often the pages get the state, at most.
const STATE_EVERY: Duration = Duration::from_millis(40);
/// The most board time one look at the pages' commands may be apart.
const CHUNK_PS: u64 = 20_000_000_000;

pub fn run(args: &Args) -> Result<(), String> {
    let live = &args.live;
    let unused = [
        ("--vcd", args.vcd.is_some()),
        ("--cpu-trace", args.cpu_trace.is_some()),
        ("--break", !args.breaks.is_empty()),
        ("--frames", args.frames.is_some()),
        ("--trace-csv", args.trace_csv.is_some()),
        ("--trace-json", args.trace_json.is_some()),
        ("--png", args.png.is_some()),
        ("--json", args.json),
    ];
    if let Some((name, _)) = unused.iter().find(|(_, on)| *on) {
        return Err(format!(
            "{name} and --live: the live run shows itself in the page (record it with --record, replay it with --motors)"
        ));
    }
    let mut plan = Plan::resolve(args, None)?;
    let manual = args.motors.is_none() && args.driver.is_none();
    let mut bot: Box<dyn Backend> = match plan.backend {
        BackendKind::Lockstep => {
            Box::new(botsim::sim::lockstep::Lockstep::new(&plan.image, plan.world.clone()).map_err(|e| e.to_string())?)
        }
        kind => {
            if kind == BackendKind::Rtl && !args.quiet {
                eprintln!("note: --live runs the bot on the ISS (the RTL's results, cycle for cycle, 60 x faster)");
            }
            Box::new(IssBot::new(&plan.image, plan.world.clone()).map_err(|e| e.to_string())?)
        }
    };
    bot.set_update_budget(plan.firmware.timing.update_budget());
    bot.set_motors(plan.initial);

    let driven_by = match (&args.motors, args.driver) {
        (Some(p), _) => Some(format!("the motor script {}", p.display())),
        (None, Some(_)) => Some("the line follower".to_string()),
        (None, None) => None,
    };
    let program = args.program.as_ref().map_or("the built-in firmware".to_string(), |p| p.display().to_string());
    let server = live.serve(json!({
        "design": {"top": "BotSim 2.0", "sources": program},
        "world": world_json(&plan.world),
        "mode": "bot",
        "driver": driven_by,
        "protocol": 1,
    }))?;

    botsim::interrupt::catch();
    let mut motors = Motors(vec![plan.initial]);
    let mut last: Option<BotView> = None;
    let mut samples = 0u64;
    let mut running = !live.paused;
    let mut step = false;
    let mut pace = Pace::new(live.speed.0, 0);
    let mut rate = Rate::new(0);
    // The pages' share of samples: (since, samples then).
    let mut share = (Instant::now(), 0u64);
    let mut last_state = Instant::now() - STATE_EVERY;
    let started = Instant::now();
    let time = |cycle: u64| cycle * PS_PER_CYCLE;
    let state = |running: bool, speed, rate, last: &Option<BotView>, samples, next: MotCtl, now| BoardView {
        time_ps: now,
        rate,
        running,
        speed,
        samples,
        bot: last.clone(),
        motors: Some(next.0),
        ..BoardView::default()
    };
    loop {
        if crate::cli::interrupted() {
            break;
        }
        let wait = if running { Duration::ZERO } else { Duration::from_millis(20) };
        let mut next = if wait.is_zero() { server.try_command() } else { server.command_within(wait) };
        let mut stopped = false;
        while let Some((client, command)) = next.take() {
            let now = time(bot.cycle());
            match command {
                Command::Run => {
                    (running, step) = (true, false);
                    pace.restart(now);
                }
                Command::Pause => running = false,
                Command::Step => {
                    (running, step) = (true, true);
                    pace.restart(now);
                }
                Command::Speed(f) => pace.set_speed(f, now),
                Command::Save => server.reply(client, json!({"type": "motors", "text": motors.script(samples)})),
                Command::Stop => stopped = true,
                Command::Motors(v) => match &driven_by {
                    Some(d) => server.reply(
                        client,
                        json!({"type": "error", "message": format!("{d} drives the bot: run without --driver and --motors to drive it from the page")}),
                    ),
                    None => {
                        // From the next iteration on: the one after the last sample taken.
                        let from = samples + 1;
                        motors.set_from(from, MotCtl(v));
                        bot.set_motors(MotCtl(v));
                        server.log(json!({"kind": "input", "time_ps": now, "iteration": from, "motors": v}));
                    }
                },
                Command::Switch { .. }
                | Command::Switches(_)
                | Command::Button { .. }
                | Command::Key { .. }
                | Command::Uart(_)
                | Command::Tilt(_) => server.reply(
                    client,
                    json!({"type": "error", "message": "the bot alone has no board (switches, buttons, keyboard, UART, tilt): set its motors (`motors`)"}),
                ),
            }
            next = server.try_command();
        }
        if stopped {
            break;
        }
        if running {
            let now = time(bot.cycle());
            let (target, _) = pace.target(now, CHUNK_PS);
            let allowed = share.1 as f64 + share.0.elapsed().as_secs_f64() * MAX_SAMPLES_PER_S;
            if time(bot.cycle()) < target && (samples as f64) < allowed {
                let s = bot.wait_update().map_err(|e| format!("error: sample {}: {e}", samples + 1))?;
                samples = s.sample;
                // The motors of the iteration that made this sample, and the next one's.
                let given = motors.of(samples.max(1));
                if !manual {
                    motors.set_from(samples + 1, plan.driver.next(&s));
                }
                bot.set_motors(motors.of(samples + 1));
                let view = bot_view(&s, given.0);
                server.log(sample_entry(time(s.cycle), &s, &view));
                last = Some(view);
                if step {
                    (running, step) = (false, false);
                }
            } else {
                std::thread::sleep(Duration::from_millis(1));
            }
            if share.0.elapsed() > Duration::from_secs(2) {
                share = (Instant::now(), samples);
            }
        }
        if last_state.elapsed() >= STATE_EVERY {
            let now = time(bot.cycle());
            server.state(state(running, pace.speed(), rate.at(now), &last, samples, motors.of(samples + 1), now));
            last_state = Instant::now();
        }
    }
    let now = time(bot.cycle());
    server.state(state(false, pace.speed(), 0.0, &last, samples, motors.of(samples + 1), now));
    server.close();
    if let Some(f) = &live.record {
        botsim::files::write_atomic(f, motors.script(samples).as_bytes())?;
    }
    if !args.quiet {
        let recorded = live.record.as_ref().map_or(String::new(), |f| format!("; its motors in {}", f.display()));
        let wall = started.elapsed().as_secs_f64();
        eprintln!(
            "botsim run --live: ran {samples} samples, {:.3} s of bot time in {wall:.1} s{recorded}",
            now as f64 / 1e12
        );
    }
    std::thread::sleep(Duration::from_millis(100));
    Ok(())
}

/// MotCtl_in of each main-loop iteration from 1 on (index 0: iteration 1, from reset); the
/// last holds for every later one.
struct Motors(Vec<MotCtl>);

impl Motors {
    /// The motors of iteration `i` (from 1).
    fn of(&self, i: u64) -> MotCtl {
        let i = i.max(1) as usize - 1;
        self.0.get(i).or(self.0.last()).copied().unwrap_or(MotCtl::STOP)
    }

    /// `m` from iteration `i` on (what was set for later ones goes).
    fn set_from(&mut self, i: u64, m: MotCtl) {
        let keep = i.max(1) as usize - 1;
        let hold = self.of(i);
        self.0.resize(self.0.len().max(keep), hold);
        self.0.truncate(keep);
        self.0.push(m);
    }

    /// Iterations 1 to `samples` as a motor script (`--motors`): replayed, it runs those
    /// samples with the same MotCtl_in in each.
    fn script(&self, samples: u64) -> String {
        let mut out = format!(
            "# botsim run --live: MotCtl_in per main-loop iteration, {samples} samples (botsim run --motors FILE replays them)\n"
        );
        let mut i = 1;
        while i <= samples.max(1) {
            let m = self.of(i);
            let mut n = 1;
            while i + n <= samples && self.of(i + n) == m {
                n += 1;
            }
            out.push_str(&format!("{:02X} {n}\n", m.0));
            i += n;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A change applies from its iteration on and replaces later ones; the script covers the
    /// samples, one segment per run of equal values.
    #[test]
    fn motors_per_iteration_and_their_script() {
        let mut m = Motors(vec![MotCtl(0)]);
        m.set_from(4, MotCtl(0x33));
        assert_eq!([1, 3, 4, 9].map(|i| m.of(i).0), [0, 0, 0x33, 0x33]);
        m.set_from(6, MotCtl(0x32));
        m.set_from(6, MotCtl(0x22));
        m.set_from(5, MotCtl(0x22));
        assert_eq!([4, 5, 6, 7].map(|i| m.of(i).0), [0x33, 0x22, 0x22, 0x22]);
        assert!(m.script(7).ends_with("00 3\n33 1\n22 3\n"), "{}", m.script(7));
        assert!(Motors(vec![MotCtl(0x30)]).script(0).ends_with("30 1\n"));
    }
}
