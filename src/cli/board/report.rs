//! What a run leaves: its output files and its summary (a line, or JSON).

use std::path::{Path, PathBuf};

use botsim::files::write_atomic;
use botsim::regs::Snapshot;
use botsim::render::{paths_picture, PathStyle};

use super::breaks::Stopped;
use super::prepare::Prepared;
use super::session::{at_line_end, Outcome};
use super::Args;
use crate::cli::rows::{csv_row, CSV_HEADER};
use botsim_core::frontend::pins::Role;
use botsim_core::frontend::plan::BotSite;

/// Below this fraction of its time skipped, a run says what kept it busy.
const BUSY_SAID: f64 = 0.9;

/// What kept the fast-forward from skipping more: the variable that most often kept it from
/// finding a period, else the counter whose compared values most often ended its skips.
pub struct Busy {
    /// Its path below the top, or Verilator's name for one of botsim's own.
    pub path: String,
    pub module: Option<String>,
    pub file: Option<std::path::PathBuf>,
    pub line: Option<u32>,
    pub times: u64,
    /// It ended skips (a counter), rather than keeping marks from a period.
    pub cut: bool,
}

/// What kept a run's fast-forward from skipping more, if anything did, from what the model
/// counted (`Model::fast_forward_busy`, `Model::fast_forward_cut`).
pub fn busy_of(p: &Prepared, busy: &Option<(String, u64)>, cut: &Option<(String, u64)>) -> Option<Busy> {
    match (busy, cut) {
        (Some((name, times)), _) => Some(Busy::of(p, name, *times)),
        (None, Some((name, times))) => Some(Busy { cut: true, ..Busy::of(p, name, *times) }),
        (None, None) => None,
    }
}

impl Busy {
    pub fn of(p: &Prepared, verilator_name: &str, times: u64) -> Busy {
        use botsim_core::frontend::locate::{declared, design_path};
        use botsim_core::frontend::wrapper::{board_part, top_port};
        if let Some(port) = top_port(&p.plan.pins, verilator_name) {
            // A pin of the user's top (the wire botsim's board connects to it, or the board's
            // output it drives): the port where the top declares it.
            if let Some(d) = declared(&p.design, &p.plan.top, port) {
                return Busy {
                    path: d.path,
                    module: Some(d.module),
                    file: Some(d.file),
                    line: Some(d.line),
                    times,
                    cut: false,
                };
            }
        }
        if let (None, Some(part)) = (design_path(verilator_name), board_part(verilator_name)) {
            // botsim's own part of the board, named as the user knows it.
            let inner = verilator_name.trim_start_matches("botsim_board__DOT__").replace("__DOT__", ".");
            return Busy {
                path: inner,
                module: Some(format!("{part}, botsim's model")),
                file: None,
                line: None,
                times,
                cut: false,
            };
        }
        match design_path(verilator_name).and_then(|path| declared(&p.design, &p.plan.top, &path)) {
            Some(d) => {
                Busy { path: d.path, module: Some(d.module), file: Some(d.file), line: Some(d.line), times, cut: false }
            }
            None => Busy {
                path: design_path(verilator_name).unwrap_or_else(|| verilator_name.to_string()),
                // A name of the user's design that no source declares as such, or one of
                // Verilator's own (its scheduler's, a temporary): said as what it is.
                module: design_path(verilator_name)
                    .is_none()
                    .then(|| "Verilator's own variable, not one of the design's".to_string()),
                file: None,
                line: None,
                times,
                cut: false,
            },
        }
    }

    /// Why, after its description: `still different at 12 looks for a period`, or `the next
    /// value the design compares it with ended 40 skips`.
    pub fn why(&self) -> String {
        if self.cut {
            format!("the next value the design compares it with ended {} skips", self.times)
        } else {
            format!("still different at {} looks for a period", self.times)
        }
    }

    /// The JSON of `kept_busy_by`.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "variable": self.path, "module": self.module, "file": self.file, "line": self.line, "times": self.times,
            "why": if self.cut { "skips cut short" } else { "no period" },
        })
    }

    /// `SSB.refresh` (module sevenseg, src/ssb.v:14), or `uart_in.left` (the board's
    /// USB-UART, botsim's model)
    pub fn describe(&self) -> String {
        match (&self.module, &self.file, self.line) {
            (Some(m), Some(f), Some(l)) => format!("`{}` (module {m}, {}:{l})", self.path, f.display()),
            (Some(m), None, None) => format!("`{}` ({m})", self.path),
            _ => format!("`{}`", self.path),
        }
    }
}

/// Write the outputs the arguments ask for and say how the run went.
pub fn report(a: &Args, p: &Prepared, mut o: Outcome) -> Result<Stopped, String> {
    o.rec.heard.uart.flush(o.sim_ps);
    if let Some(f) = &a.uart {
        let bytes: Vec<u8> = o.rec.heard.uart.received.iter().map(|r| r.byte).collect();
        write_atomic(f, &bytes)?;
    }
    if let (Some(f), Some(audio)) = (&a.audio, &mut o.rec.heard.audio) {
        audio.finish(o.sim_ps);
        write_atomic(f, &audio.wav())?;
    }
    let has_uart = p.plan.pins.iter().any(|(_, r)| *r == Role::UartTx);
    // The first bot's traces where the options say; each other bot's beside them, named by
    // its instance path (`trace.csv` -> `trace.top.MONSTER.csv`).
    let others: Vec<(&BotSite, &[Snapshot], &str)> = p
        .plan
        .other_bots
        .iter()
        .enumerate()
        .map(|(k, b)| match o.rec.others.get(k) {
            Some(t) => (b, &t.snapshots[..], t.json.as_str()),
            None => (b, &[][..], ""),
        })
        .collect();
    if let Some(f) = &a.trace_csv {
        let csv = |snapshots: &[Snapshot]| {
            let mut csv = format!("{CSV_HEADER}\n");
            for s in snapshots {
                csv.push_str(&csv_row(s));
            }
            csv
        };
        write_atomic(f, csv(&o.rec.snapshots).as_bytes())?;
        for (b, snapshots, _) in &others {
            write_atomic(&per_bot(f, &b.path), csv(snapshots).as_bytes())?;
        }
    }
    if let Some(f) = &a.trace_json {
        write_atomic(f, o.rec.json.as_bytes())?;
        for (b, _, json) in &others {
            write_atomic(&per_bot(f, &b.path), json.as_bytes())?;
        }
    }
    if let Some(f) = &a.pins {
        write_atomic(f, o.rec.pins_csv.as_deref().unwrap_or_default().as_bytes())?;
    }
    if let Some(f) = &a.lines {
        write_atomic(f, o.rec.lines_csv.as_deref().unwrap_or_default().as_bytes())?;
    }
    if let Some(f) = &a.display {
        write_atomic(f, o.rec.display_log.as_deref().unwrap_or_default().as_bytes())?;
    }
    if let Some(f) = &a.png {
        let trails: Vec<&[Snapshot]> =
            std::iter::once(&o.rec.snapshots[..]).chain(others.iter().map(|(_, s, _)| *s)).collect();
        let picture = paths_picture(&p.world, &trails, p.fw.threshold, &PathStyle::default());
        write_atomic(f, &picture)?;
    }
    let skipped_fraction = if o.sim_ps == 0 { 0.0 } else { o.skipped_ps as f64 / o.sim_ps as f64 };
    let busy = busy_of(p, &o.busy, &o.cut);
    let last_display = o.rec.display.lines().last().map(|l| l.text.clone()).unwrap_or_default();
    let end = o.rec.snapshots.last().map(|s| (s.regs.loc_x, s.regs.loc_y));
    // Moves the world refused (the destination was an obstruction): the samples with the event.
    let blocked: Vec<u64> =
        o.rec.snapshots.windows(2).filter(|w| w[0].move_refused(&w[1], p.fw.threshold)).map(|w| w[0].sample).collect();
    if a.finding {
        // The run that writes the waveform and the traces says it all.
    } else if a.json {
        let v = serde_json::json!({
            "top": p.plan.top,
            "simulated_seconds": o.sim_ps as f64 / 1e12,
            "stopped_by": o.stopped_by,
            "samples": o.rec.snapshots.len(),
            "end": o.rec.snapshots.last().map(|s| serde_json::json!({
                "loc_x": s.regs.loc_x, "loc_y": s.regs.loc_y, "sensors": s.regs.sensors,
                "orientation": s.orientation().name(), "movement": s.movement().name(),
                // Stopped on the line with a wall straight ahead: the end of a course.
                "at_line_end": at_line_end(s),
            })),
            "blocked_moves": blocked.len(),
            "first_blocked_sample": blocked.first(),
            // Every bot, the first (the one above) first.
            "bots": p.plan.bots().iter().enumerate().map(|(k, b)| {
                let snapshots = if k == 0 { &o.rec.snapshots[..] } else { others[k - 1].1 };
                serde_json::json!({
                    "path": b.path,
                    "module": b.team.as_ref().map_or("bot", |t| t.module.as_str()),
                    "samples": snapshots.len(),
                    "end": snapshots.last().map(|s| serde_json::json!({
                        "loc_x": s.regs.loc_x, "loc_y": s.regs.loc_y, "sensors": s.regs.sensors,
                        "orientation": s.orientation().name(), "movement": s.movement().name(),
                    })),
                })
            }).collect::<Vec<_>>(),
            "display": last_display,
            "leds": o.rec.last_led,
            "vga_frames": o.rec.frames_seen,
            "vga_frames_written": o.rec.frames_written,
            "vga_unknown_frames": o.rec.vga.unknown,
            "vcd_x_signals": o.vcd_x_signals,
            "evaluations": o.evaluations,
            "wall_seconds": o.wall_seconds,
            "build_seconds": p.built.seconds,
            "verilator": p.built.verilator,
            "cpu_traces": o.traces,
            "design_lines": o.design_lines,
            "fast_forward": {
                "skips": o.skips,
                "skipped_seconds": o.skipped_ps as f64 / 1e12,
                "skipped_fraction": skipped_fraction,
                "off_because": o.fast_forward_off,
                "kept_busy_by": busy.as_ref().map(Busy::json),
            },
            "break": o.stopped.as_ref().map(|s| serde_json::json!({"time_ps": s.time_ps, "what": s.message})),
            "uart": has_uart.then(|| {
                let u = &o.rec.heard.uart;
                serde_json::json!({
                    "baud": u.baud().map(|b| b.0),
                    "measured": u.baud().map(|b| b.1),
                    "bytes": u.received.len(),
                    "framing_errors": u.framing_errors(),
                    "text": u.text(),
                })
            }),
        });
        let mut v = v;
        if p.plan.bot_path.is_none() {
            // The board alone: nothing of a bot to say.
            for key in ["samples", "end", "blocked_moves", "first_blocked_sample", "bots"] {
                v.as_object_mut().expect("an object").remove(key);
            }
        }
        println!("{v}");
    } else if !a.quiet {
        let bot = match (&p.plan.bot_path, end) {
            (None, _) => String::new(),
            (Some(_), None) => format!(" {} samples, the bot had no sample yet,", o.rec.snapshots.len()),
            (Some(_), Some((x, y))) => format!(" {} samples, the bot ended at ({x}, {y}),", o.rec.snapshots.len()),
        };
        let frames = if o.rec.frames_seen > 0 { format!(", {} VGA frames", o.rec.frames_seen) } else { String::new() };
        println!(
            "simulated {:.3} s in {:.1} s:{bot} the display showed \"{last_display}\", LEDs {:016b}{frames}",
            o.sim_ps as f64 / 1e12,
            o.wall_seconds,
            o.rec.last_led
        );
        if o.skips > 0 {
            println!(
                "  fast-forwarded {:.3} s of it ({:.1} %) in {} skips",
                o.skipped_ps as f64 / 1e12,
                skipped_fraction * 100.0,
                o.skips
            );
        }
        if let (Some(b), true) = (&busy, o.fast_forward_off.is_none() && skipped_fraction < BUSY_SAID) {
            println!("  what kept it from skipping more: {}, {}", b.describe(), b.why());
        }
        for (b, snapshots, _) in &others {
            let end = match snapshots.last() {
                Some(s) => format!("ended at ({}, {})", s.regs.loc_x, s.regs.loc_y),
                None => "had no sample yet".into(),
            };
            println!("  the bot at `{}`: {} samples, {end}", b.path, snapshots.len());
        }
        if let Some(line) = o.rec.heard.uart_summary() {
            println!("  {line}");
        }
        for t in &o.traces {
            println!("  wrote {}", t.display());
        }
    }
    Ok(o.stopped)
}

/// Where another bot's trace goes beside the first's `file`: its instance path before the
/// extension (`trace.csv`, `top.MONSTER` -> `trace.top.MONSTER.csv`).
fn per_bot(file: &Path, path: &str) -> PathBuf {
    let stem = file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name = match file.extension() {
        Some(e) => format!("{stem}.{path}.{}", e.to_string_lossy()),
        None => format!("{stem}.{path}"),
    };
    file.with_file_name(name)
}
