//! A bot sample as a row of `--trace-csv` or a line of `--trace-json`: one writer for
//! `botsim run` and `botsim board`.

use botsim::{MotCtl, Snapshot};

/// The CSV header of `--trace-csv` (the contract's columns).
pub const CSV_HEADER: &str = "sample,cycle,loc_x,loc_y,bot_info,sensors,lm_dist,rm_dist";

/// One `--trace-csv` row.
pub fn csv_row(s: &Snapshot) -> String {
    let r = &s.regs;
    format!(
        "{},{},{},{},{},{},{},{}\n",
        s.sample, s.cycle, r.loc_x, r.loc_y, r.bot_info, r.sensors, r.lm_dist, r.rm_dist
    )
}

/// One `--trace-json` line, with the decoded fields and the MotCtl chosen for the next
/// iteration.
pub fn json_row(s: &Snapshot, motctl: MotCtl) -> String {
    let r = &s.regs;
    let v = serde_json::json!({
        "sample": s.sample, "cycle": s.cycle,
        "loc_x": r.loc_x, "loc_y": r.loc_y, "bot_info": r.bot_info, "sensors": r.sensors,
        "lm_dist": r.lm_dist, "rm_dist": r.rm_dist,
        "orientation": s.orientation().name(), "heading_degrees": s.orientation().degrees(),
        "movement": s.movement().name(),
        "prox_left": s.sensors().prox_left(), "prox_right": s.sensors().prox_right(),
        "on_line": s.sensors().on_line(),
        "next_motctl": motctl.0,
    });
    format!("{v}\n")
}
