//! Breakpoints (`--break`), the waveform's window marks and its GTKWave save file.

use std::collections::BTreeMap;
use std::path::Path;

use botsim::files::write_atomic;
use botsim::kcpsm6::source::SourceMap;
use botsim_core::board::gtkw::View;
use botsim_core::board::stimulus::parse_time;
use botsim_core::debug::{cpu_signals, register_filters, Break, BreakSpec, Breaks};
use botsim_core::frontend::plan::Plan;

/// Where a `--break` stopped a run.
#[derive(Clone, Debug)]
pub struct BreakStop {
    pub time_ps: u64,
    /// What it says ("stopped by --break ...").
    pub message: String,
    /// A bot condition (at a sample), not a CPU's breakpoint.
    pub bot: bool,
}

/// What a `--break` stopped.
pub type Stopped = Option<BreakStop>;

/// What the save file opens on: the whole waveform, or after a breakpoint about twelve
/// instructions of a 100 MHz KCPSM6 (wide enough for their text) with the marker on the
/// stop: those before a CPU's stop, those after a bot condition's sample (the firmware's
/// answer to it begins there).
pub fn save_file_view(start_ps: u64, end_ps: u64, stop: Option<&BreakStop>) -> View {
    const SPAN_PS: u64 = 240_000;
    const MARGIN_PS: u64 = 40_000;
    match stop {
        Some(s) if (start_ps..=end_ps).contains(&s.time_ps) => {
            let t = s.time_ps;
            let from = if s.bot { t.saturating_sub(MARGIN_PS) } else { (t + MARGIN_PS).saturating_sub(SPAN_PS) };
            let from = from.max(start_ps);
            View { start_ps: from, end_ps: (from + SPAN_PS).min(end_ps), marker_ps: Some(t) }
        }
        _ => View { start_ps, end_ps: end_ps.max(start_ps + 1), marker_ps: None },
    }
}

/// The GTKWave save file beside a waveform (`w.vcd` -> `w.gtkw`), with its translate filters:
/// the board pins, the bot's registers (BotInfo as heading and movement, MotCtl as movement)
/// and every KCPSM6 (its address as `label+offset` where the program's source is known, the
/// instruction text, the status, the registers, the port bus); with `bot_model`, the bot has
/// no KCPSM6 in the waveform.
pub fn write_save_file(
    vcd: &Path,
    plan: &Plan,
    sources: &BTreeMap<String, SourceMap>,
    probed: bool,
    bot_model: bool,
    view: View,
) -> Result<(), String> {
    use botsim_core::board::gtkw::{filter_text, Format, SaveFile};
    let top = "TOP.botsim_board";
    let side = |suffix: &str| {
        let name = vcd.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        vcd.with_file_name(format!("{name}.{suffix}"))
    };
    let mut s = SaveFile::new(&std::path::absolute(vcd).unwrap_or_else(|_| vcd.to_path_buf()));
    s.view(view);
    let sig = |n: &str, f: Format| (format!("{top}.{n}"), f, None);
    // The wrapper's board pins (wrapper.rs), each in the radix it reads best in.
    const PINS: [(&str, Format); 13] = [
        ("clk", Format::Binary),
        ("reset_pressed", Format::Binary),
        ("btn[4:0]", Format::Binary),
        ("sw[15:0]", Format::Hex),
        ("led[15:0]", Format::Binary),
        ("an[7:0]", Format::Binary),
        ("seg[6:0]", Format::Binary),
        ("dp", Format::Binary),
        ("vga_r[3:0]", Format::Hex),
        ("vga_g[3:0]", Format::Hex),
        ("vga_b[3:0]", Format::Hex),
        ("hsync", Format::Binary),
        ("vsync", Format::Binary),
    ];
    s.group("Board pins", PINS.iter().map(|(n, f)| sig(n, *f)).collect());
    // The bot's registers, on a board with a bot.
    if plan.bot_path.is_some() {
        let (info, motctl) = register_filters();
        let info_file = side("botinfo.txt");
        write_atomic(&info_file, info.as_bytes())?;
        let motctl_file = side("motctl.txt");
        write_atomic(&motctl_file, motctl.as_bytes())?;
        let (fi, fm) = (s.filter(&info_file), s.filter(&motctl_file));
        s.group(
            "Bot registers",
            vec![
                sig("bot_upd", Format::Binary),
                sig("bot_locx[7:0]", Format::Decimal),
                sig("bot_locy[7:0]", Format::Decimal),
                (format!("{top}.bot_info[7:0]"), Format::Hex, Some(fi)),
                sig("bot_sensors[7:0]", Format::Binary),
                sig("bot_lmdist[7:0]", Format::Decimal),
                sig("bot_rmdist[7:0]", Format::Decimal),
                (format!("{top}.bot_motctl[7:0]"), Format::Hex, Some(fm)),
            ],
        );
    }
    let own: Vec<String> = plan.bots().into_iter().filter(|b| b.team.is_none()).map(|b| b.path).collect();
    let in_bot = |path: &str| own.iter().any(|b| path.strip_prefix(b.as_str()).is_some_and(|r| r.starts_with('.')));
    for site in plan.cpus.iter().filter(|c| !(bot_model && in_bot(&c.path))) {
        let at = format!("{top}.user.{}", site.path);
        let debug = if probed { format!("{at}.core") } else { at.clone() };
        let labels = match sources.get(&site.path) {
            Some(map) => {
                let file = side(&format!("{}.labels.txt", site.path));
                write_atomic(&file, filter_text((0..4096u32).map(|a| (a, map.describe(a as u16))), 3).as_bytes())?;
                Some(s.filter(&file))
            }
            None => None,
        };
        let v = cpu_signals(&at, &debug, labels);
        s.group(&site.path, v);
    }
    write_atomic(&vcd.with_extension("gtkw"), s.text().as_bytes())
}

/// The `--break` specs: each CPU's breakpoints by instance path (addresses and port writes
/// apply to the team's CPUs; labels and lines to the CPU whose program has them), and the
/// conditions on the bot's samples.
pub fn breakpoints(
    specs: &[String],
    plan: &Plan,
    sources: &BTreeMap<String, SourceMap>,
) -> Result<(BTreeMap<String, Breaks>, Vec<BreakSpec>), String> {
    let bot_cpu = plan.bot_cpu.clone();
    let team: Vec<&str> =
        plan.cpus.iter().map(|c| c.path.as_str()).filter(|p| Some(*p) != bot_cpu.as_deref()).collect();
    let mut cpu: BTreeMap<String, Breaks> = BTreeMap::new();
    let mut bot = Vec::new();
    for text in specs {
        let spec = BreakSpec::parse(text)?;
        match &spec.kind {
            Break::Bot(_) if plan.bot_path.is_none() => {
                return Err(format!(
                    "--break {text}: the design has no bot (a condition on the bot's samples needs one)"
                ))
            }
            Break::Bot(_) => bot.push(spec),
            Break::Pc(_) | Break::Port(..) => {
                for p in &team {
                    cpu.entry(p.to_string()).or_default().add(&spec, sources.get(*p))?;
                }
            }
            Break::Label(_) | Break::Line(..) => {
                let mut found = false;
                for (path, map) in sources {
                    found |= cpu.entry(path.clone()).or_default().add(&spec, Some(map))?;
                }
                if !found {
                    return Err(format!(
                        "--break {text}: no CPU's program has it (the source is known for programs given with --program and for the bot's firmware)"
                    ));
                }
            }
        }
    }
    cpu.retain(|_, b| !b.is_empty());
    Ok((cpu, bot))
}

/// Where a waveform window opens or closes: after a bot sample, or at a time (cycles of the
/// 100 MHz clock are a time).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    Sample(u64),
    Time(u64),
}

/// `N` (sample N, as `botsim run` takes it), `Nc` (cycle N of 100 MHz) or a time with a unit.
pub fn parse_mark(s: &str, name: &str) -> Result<Mark, String> {
    if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) {
        return s.parse().map(Mark::Sample).map_err(|_| format!("--{name} {s}: too large"));
    }
    parse_time(s).map(Mark::Time).map_err(|e| format!("--{name}: {e} or a sample number"))
}
