//! What a run writes: the traces, the pictures, the summary.

use std::fmt::Write as _;
use std::path::PathBuf;

use botsim::files::write_atomic;
use botsim::render::{path_picture, PathStyle};
use botsim::Snapshot;

use super::plan::Plan;
use crate::cli::rows::{csv_row, CSV_HEADER};

/// What the sample loop collected.
#[derive(Default)]
pub struct Taken {
    pub snapshots: Vec<Snapshot>,
    /// The JSON lines, built as the MotCtl of each is known.
    pub json: String,
    pub frames_written: u64,
}

/// Write the trace files and pictures of a finished (or interrupted) run; the files written.
pub fn write(plan: &Plan, taken: &Taken, end_frame: Option<&[u8]>) -> Result<Vec<PathBuf>, String> {
    let mut written = vec![];
    if let Some(p) = &plan.trace_csv {
        let mut csv = format!("{CSV_HEADER}\n");
        for s in &taken.snapshots {
            csv.push_str(&csv_row(s));
        }
        write_atomic(p, csv.as_bytes())?;
        written.push(p.clone());
    }
    if let Some(p) = &plan.trace_json {
        write_atomic(p, taken.json.as_bytes())?;
        written.push(p.clone());
    }
    if let (Some(p), Some(png)) = (&plan.end_frame, end_frame) {
        write_atomic(p, png)?;
        written.push(p.clone());
    }
    if let Some(f) = &plan.frames {
        written.push(f.dir.join(format!("({} frames)", taken.frames_written)));
    }
    if let Some(p) = &plan.png {
        write_atomic(p, &path_picture(&plan.world, &taken.snapshots, plan.firmware.threshold, &PathStyle::default()))?;
        written.push(p.clone());
    }
    Ok(written)
}

/// The numbers of a run, for the summary.
pub struct Totals {
    pub cycles: u64,
    pub wall_seconds: f64,
}

impl Totals {
    fn mcycles_per_second(&self) -> f64 {
        self.cycles as f64 / self.wall_seconds.max(1e-9) / 1e6
    }
}

/// The summary as JSON.
pub fn summary_json(taken: &Taken, totals: &Totals, driver_status: &str, written: &[PathBuf]) -> Option<String> {
    let last = taken.snapshots.last()?;
    let v = serde_json::json!({
        "samples": taken.snapshots.len(), "cycles": totals.cycles, "simulated_seconds": totals.cycles as f64 / 1e8,
        "wall_seconds": totals.wall_seconds, "mcycles_per_second": totals.mcycles_per_second(),
        "final": {
            "loc_x": last.regs.loc_x, "loc_y": last.regs.loc_y, "orientation": last.orientation().name(),
            "movement": last.movement().name(), "sensors": last.regs.sensors,
        },
        "driver": driver_status,
        "files": written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
        "frames": taken.frames_written,
    });
    Some(v.to_string())
}

/// The summary for a person.
pub fn summary_text(taken: &Taken, totals: &Totals, driver_status: &str, written: &[PathBuf]) -> Option<String> {
    let last = taken.snapshots.last()?;
    let n = taken.snapshots.len();
    let mut out = String::new();
    let _ = writeln!(out, "samples      {n} (the reset dump and {} iterations)", n - 1);
    let _ = writeln!(out, "cycles       {} ({:.3} s at 100 MHz)", totals.cycles, totals.cycles as f64 / 1e8);
    let _ = writeln!(out, "wall time    {:.2} s ({:.1} Mcycles/s)", totals.wall_seconds, totals.mcycles_per_second());
    let _ = writeln!(
        out,
        "final        ({}, {}) facing {} {}, sensors {:02X}",
        last.regs.loc_x,
        last.regs.loc_y,
        last.orientation().name(),
        last.movement().name(),
        last.regs.sensors
    );
    if !driver_status.is_empty() {
        let _ = writeln!(out, "driver       {driver_status}");
    }
    for w in written {
        let _ = writeln!(out, "wrote        {}", w.display());
    }
    Some(out)
}
