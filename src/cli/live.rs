//! What `botsim board --live` and `botsim run --live` share: their options, the server
//! started with its address on the first line, the pace against the wall clock and the rate
//! measured. The runs themselves are src/cli/board/live.rs and src/cli/run/live.rs.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use botsim::{Snapshot, World};
use botsim_live::protocol::BotView;
use botsim_live::server::Server;
use serde_json::{json, Value};

/// The live options (flattened into `botsim board` and `botsim run`).
#[derive(clap::Args, Clone, Debug)]
pub struct LiveArgs {
    /// Run live: a local web server shows the board (or the bot), the VGA monitor and the
    /// world in the browser (the address is the first line printed) and takes the inputs
    /// from it, until the page's Stop or Ctrl-C
    #[arg(long)]
    pub live: bool,
    /// With --live: the port [default: 8540; 0 takes any free one]
    #[arg(long, default_value_t = 8540, requires = "live")]
    pub port: u16,
    /// With --live: the address to listen on [default: 127.0.0.1, this machine only]
    #[arg(long, default_value = "127.0.0.1", requires = "live")]
    pub listen: String,
    /// With --live: write the session's inputs to this file when it ends, a stimulus file
    /// for `botsim board --stimulus`, a motor script for `botsim run --motors`: either
    /// replays the session exactly
    #[arg(long, value_name = "FILE", requires = "live")]
    pub record: Option<PathBuf>,
    /// With --live: start at this factor of real time, or `max` (as fast as it can)
    #[arg(long, default_value = "1", value_parser = parse_speed, requires = "live")]
    pub speed: Speed,
    /// With --live: start paused
    #[arg(long, requires = "live")]
    pub paused: bool,
}

/// `--speed`: a factor of real time, or `None` for as fast as it can.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Speed(pub Option<f64>);

fn parse_speed(s: &str) -> Result<Speed, String> {
    if s.eq_ignore_ascii_case("max") {
        return Ok(Speed(None));
    }
    match s.parse::<f64>() {
        Ok(f) if f.is_finite() && f > 0.0 => Ok(Speed(Some(f))),
        _ => Err("expected a factor of real time (0.5, 1, 10) or max".into()),
    }
}

impl LiveArgs {
    /// Check the record file, listen, and print the page's address as the first line of
    /// standard output (what a user opens, what a script reads). Every page gets `hello`
    /// first.
    pub fn serve(&self, hello: Value) -> Result<Server, String> {
        if let Some(f) = &self.record {
            botsim::files::check_writable(f)?;
        }
        let addr = format!("{}:{}", self.listen, self.port);
        let addr = addr
            .parse()
            .map_err(|_| format!("--listen {}: expected an IP address (127.0.0.1, 0.0.0.0)", self.listen))?;
        let server =
            Server::start(addr, hello).map_err(|e| format!("--port {}: cannot listen on {addr}: {e}", self.port))?;
        println!("{}", server.url());
        if !server.addr().ip().is_loopback() {
            eprintln!(
                "note: --listen {}: the board is served to every machine that reaches this one, without a password",
                self.listen
            );
        }
        Ok(server)
    }
}

/// How far behind its pace a run may fall and still catch up (beyond: the pace goes on from
/// where it is), and how close to it counts as on pace.
const CATCH_UP: Duration = Duration::from_millis(500);
const ON_PACE: Duration = Duration::from_millis(30);

/// Simulated time against wall time: where a run at `speed` times real time should be now.
///
/// ```ignore
/// let mut pace = Pace::new(Some(1.0), 0);
/// let (target, on_pace) = pace.target(now_ps, chunk_ps);
/// ```
pub struct Pace {
    speed: Option<f64>,
    /// A wall instant and the simulated time (ps) it corresponds to.
    anchor: (Instant, u64),
}

impl Pace {
    pub fn new(speed: Option<f64>, now_ps: u64) -> Pace {
        Pace { speed, anchor: (Instant::now(), now_ps) }
    }

    pub fn speed(&self) -> Option<f64> {
        self.speed
    }

    /// A new speed, from `now_ps` on.
    pub fn set_speed(&mut self, speed: Option<f64>, now_ps: u64) {
        self.speed = speed;
        self.restart(now_ps);
    }

    /// Go on from `now_ps` (after a pause).
    pub fn restart(&mut self, now_ps: u64) {
        self.anchor = (Instant::now(), now_ps);
    }

    /// The simulated time to run to now (at most `chunk_ps` ahead; as fast as it can: that),
    /// and whether the run is on pace (so it may spend wall time on something else, a VGA
    /// frame). A run behind by more than [`CATCH_UP`] goes on from where it is.
    pub fn target(&mut self, now_ps: u64, chunk_ps: u64) -> (u64, bool) {
        let Some(f) = self.speed else { return (now_ps + chunk_ps, true) };
        let ps = |d: Duration| (d.as_secs_f64() * f * 1e12) as u64;
        let due = self.anchor.1 + ps(self.anchor.0.elapsed());
        if due > now_ps + ps(CATCH_UP) {
            self.anchor = (Instant::now() - CATCH_UP, now_ps);
        }
        let target = due.min(now_ps + ps(CATCH_UP)).min(now_ps + chunk_ps);
        (target, due <= now_ps + ps(ON_PACE))
    }
}

/// The rate against real time, measured over at least half a second.
pub struct Rate {
    since: (Instant, u64),
    last: f64,
}

impl Rate {
    pub fn new(now_ps: u64) -> Rate {
        Rate { since: (Instant::now(), now_ps), last: 0.0 }
    }

    /// The rate with the run at `now_ps`.
    pub fn at(&mut self, now_ps: u64) -> f64 {
        let dt = self.since.0.elapsed().as_secs_f64();
        if dt >= 0.5 {
            self.last = now_ps.saturating_sub(self.since.1) as f64 / 1e12 / dt;
            self.since = (Instant::now(), now_ps);
        }
        self.last
    }
}

/// The world for the pages' `hello`: its cells as one digit each (0 floor, 1 line, 2
/// obstruction, 3 reserved), row by row.
pub fn world_json(world: &World) -> Value {
    let cells: String = (0..128u8)
        .flat_map(|y| (0..128u8).map(move |x| (x, y)))
        .map(|(x, y)| char::from(b'0' + world.get(x, y).bits()))
        .collect();
    json!({"width": 128, "height": 128, "cells": cells})
}

/// The bot as a sample shows it, with the MotCtl_in it was given.
pub fn bot_view(s: &Snapshot, motctl: u8) -> BotView {
    BotView {
        sample: s.sample,
        x: s.regs.loc_x,
        y: s.regs.loc_y,
        heading: s.orientation().name().to_string(),
        movement: s.movement().name().to_string(),
        info: s.regs.bot_info,
        sensors: s.regs.sensors,
        lmdist: s.regs.lm_dist,
        rmdist: s.regs.rm_dist,
        motctl,
    }
}

/// A sample's entry in the pages' log.
pub fn sample_entry(time_ps: u64, s: &Snapshot, v: &BotView) -> Value {
    json!({
        "kind": "sample", "time_ps": time_ps, "sample": v.sample, "cycle": s.cycle, "x": v.x, "y": v.y,
        "info": v.info, "sensors": v.sensors, "lmdist": v.lmdist, "rmdist": v.rmdist, "motctl": v.motctl,
    })
}
