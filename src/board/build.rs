//! Building a board design: the plan's files written out, Verilator, the C++ compiler, one
//! shared library per design, cached by a hash of everything it is built from
//! (`$BOTSIM_CACHE`, else `$XDG_CACHE_HOME/botsim`, else `~/.cache/botsim`).

use std::collections::hash_map::DefaultHasher;
use std::collections::BTreeMap;
use std::hash::{Hash, Hasher};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use botsim_core::frontend::parts::{OWN_MODULES, PRIMITIVES, STUB};
use botsim_core::frontend::plan::Plan;
use botsim_core::frontend::wrapper;
use botsim_core::frontend::BoardError;

use super::explain;

use crate::interrupt::interrupted;

#[path = "../../build/verilator.rs"]
mod verilator;

const HARNESS: &str = include_str!("harness.cpp");
const MODEL_H: &str = include_str!("board_model.h");
const MODEL_CPP: &str = include_str!("board_model.cpp");
const ABI: &str = include_str!("board_abi.h");
const PRINT: &str = include_str!("botsim_print.h");
const PCH: &str = include_str!("botsim_pch.h");
const DISASM: &str = include_str!("../sim/rtl/ffi/botsim_disasm.h");
const XILINX: &str = include_str!("../../rtl/board/xilinx.v");
const CLKGEN: &str = include_str!("../../rtl/board/botsim_clkgen.v");
const DEVICES: &str = include_str!("../../rtl/board/devices.v");
const KCPSM6_ISS: &str = include_str!("../../rtl/board/kcpsm6_iss.v");
const BOT_MODEL: &str = include_str!("../../rtl/board/bot_model.v");
const KCPSM6_PROBE: &str = include_str!("../../rtl/board/kcpsm6_probe.v");

/// What stands in for every KCPSM6 of the design.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CpuModel {
    /// botsim's RTL core (rtl/kcpsm6.v), evaluated by Verilator.
    Rtl,
    /// The instruction-set simulator behind the same ports (rtl/board/kcpsm6_iss.v).
    Iss,
    /// The RTL core with a probe on its ports (rtl/board/kcpsm6_probe.v): the lock-step's
    /// RTL side.
    RtlProbed,
}

/// What stands for the course's `bot` in a build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BotKind {
    /// botsim's RTL (rtl/bot.v: its KCPSM6 as the build's CPUs are, world_if, map).
    Rtl,
    /// botsim's model of the bot behind the same ports (rtl/board/bot_model.v: the firmware
    /// on the ISS with Rust models of world_if and the map, called once per clock edge).
    Model,
}

/// botsim's own RTL, by file name.
fn own_rtl(file: &str) -> &'static str {
    match file {
        "kcpsm6.v" => include_str!("../../rtl/kcpsm6.v"),
        "bot.v" => include_str!("../../rtl/bot.v"),
        "world_if.v" => include_str!("../../rtl/world_if.v"),
        "map.v" => include_str!("../../rtl/map.v"),
        "world_map.v" => include_str!("../../rtl/world_map.v"),
        _ => unreachable!("not one of botsim's files: {file}"),
    }
}

/// Verilator's options for every board build (part of the cache key). The C++ is compiled
/// position-independent for the shared library; calls inside it bind locally (no PLT or
/// interposition for the model's inline helpers).
const VERILATOR_FLAGS: &[&str] = &[
    "--trace",
    "--timescale",
    "1ns/1ps",
    "-O3",
    "--x-assign",
    "fast",
    "-Wno-fatal",
    "-Wno-lint",
    "-Wno-style",
    "-Wno-MULTITOP",
    "-Wno-TIMESCALEMOD",
    // Vivado builds a variable given both blocking and non-blocking assignments; said once.
    "-Wwarn-BLKANDNBLK",
    // Widths at the connections of what botsim built for a design (board::explain).
    "-Wwarn-WIDTH",
    "-CFLAGS",
    "-fPIC -O2 -fvisibility-inlines-hidden -fno-semantic-interposition -DVL_USER_FINISH -DVL_USER_FATAL \
     -DVL_USER_STOP -DVL_USER_WARN -DVL_PRINTF=botsim_printf -DVL_VPRINTF=botsim_vprintf -Winvalid-pch -I..",
    "-LDFLAGS",
    "-shared -Wl,-Bsymbolic",
];

/// The variables of Verilator's makefile for every board build (part of the cache key): it
/// compiles with -Os after CFLAGS; -O2 makes boards about twice as fast (docs/PERFORMANCE.md).
const MAKE_VARS: &[&str] = &["OPT_FAST=-O2", "OPT_GLOBAL=-O2", "OPT_SLOW=-O1"];

/// The header forced first into every file of a build (botsim_pch.h), given to make apart
/// from [`VERILATOR_FLAGS`] so that the precompiled header itself is compiled without it.
const FORCED: &str = "USER_CPPFLAGS=-include botsim_pch.h";

/// The rule that compiles botsim_pch.h as the build's makefile compiles its files (a makefile
/// read after Verilator's: its variables are set).
const PCH_RULE: &str =
    "botsim_pch.h.gch: botsim_pch.h\n\t$(CXX) $(CXXFLAGS) $(CPPFLAGS) $(OPT_FAST) -x c++-header -o $@ $<\n";

/// `BOTSIM_KEEP_GENERATED=DIR`: every file of a build (the user's files as botsim edited
/// them, the wrapper and botsim's modules, the cores and stubs made for the design, Verilator's
/// output so far: `obj/`) copied into DIR, whatever the outcome, for a report or for whoever
/// teaches the analyses another Verilator's output. A build reused from the cache gives what
/// it kept (no Verilator output).
fn keep_generated(build: &Path) {
    let Some(keep) = std::env::var_os("BOTSIM_KEEP_GENERATED") else { return };
    fn copy(from: &Path, to: &Path) {
        let _ = std::fs::create_dir_all(to);
        for e in std::fs::read_dir(from).into_iter().flatten().flatten() {
            let (p, q) = (e.path(), to.join(e.file_name()));
            if p.is_dir() {
                copy(&p, &q);
            } else if !p.extension().is_some_and(|x| x == "o" || x == "so" || x == "a" || x == "d" || x == "gch") {
                let _ = std::fs::copy(&p, &q);
            }
        }
    }
    let keep = PathBuf::from(keep);
    copy(build, &keep);
    // The analyses' readers expect Verilator's files at the top (as kept before).
    copy(&build.join("obj"), &keep);
}

/// A built design.
#[derive(Clone, Debug)]
pub struct Built {
    pub library: PathBuf,
    /// Verilator's warnings about the user's files, grouped: (code, count, first message).
    pub warnings: Vec<(String, usize, String)>,
    /// Connections of what botsim built for the design whose widths differ from the
    /// design's, in botsim's words ([`explain::replacement_widths`]).
    pub widths: Vec<String>,
    /// The build's duration in seconds; `None` when the cache had it.
    pub seconds: Option<f64>,
    /// Where the design's first delay is (`file:line:col`), when it has delays: the build
    /// simulates them (Verilator's timing support).
    pub delays: Option<String>,
    /// The Verilator that built it, e.g. "5.006 2023-01-22".
    pub verilator: String,
    /// The names Verilator knows the user's files by (the build's copies, absolute paths),
    /// with the user's paths.
    names: Vec<Name>,
}

impl Built {
    /// `msg` (a message of Verilator's or of the model's runtime) with the user's paths.
    pub fn user_paths(&self, msg: &str) -> String {
        to_user(msg, &self.names)
    }
}

/// The file of a build folder that says where the design's first delay is (empty: none).
const DELAYS_FILE: &str = "delays.txt";

/// The cache folder.
pub fn cache_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("BOTSIM_CACHE") {
        return PathBuf::from(d);
    }
    if let Some(d) = std::env::var_os("XDG_CACHE_HOME") {
        return PathBuf::from(d).join("botsim");
    }
    let home = std::env::var_os("HOME").map(PathBuf::from).unwrap_or_else(std::env::temp_dir);
    home.join(".cache").join("botsim")
}

/// Mark the cache folder as one (the Cache Directory Tagging convention): backups skip it,
/// and so does botsim's own search of a repository that holds it.
fn tag_cache(dir: &Path) {
    let tag = dir.join("CACHEDIR.TAG");
    if !tag.exists() {
        let _ = std::fs::write(
            tag,
            "Signature: 8a477f597d28d172789f06886806bc55\n# botsim's build cache: safe to delete, rebuilt as needed\n",
        );
    }
}

/// The files of the build: (name in the build folder, text), user files with their origin.
struct Files {
    generated: Vec<(String, String)>,
    /// (path to pass to Verilator, the user's path) — filtered copies live in the build folder.
    user: Vec<(String, Option<String>, PathBuf)>,
    /// Which of `user` botsim wrote (cores, stand-ins, stubs, conversions).
    made: Vec<bool>,
    /// What each of `user` was converted from (a VHDL entity's file and line).
    converted: Vec<Option<(PathBuf, u32)>>,
    defines: Vec<String>,
}

fn files(plan: &Plan, params: &[(String, String)], cpu: CpuModel, bot: BotKind) -> Files {
    let mut generated = vec![
        ("botsim_board.sv".to_string(), wrapper::board_top(plan, params)),
        ("botsim_xilinx.sv".to_string(), XILINX.to_string()),
        ("botsim_clkgen.sv".to_string(), CLKGEN.to_string()),
        ("botsim_devices.sv".to_string(), DEVICES.to_string()),
    ];
    // botsim's own modules, but those whose names are the team's modules here.
    for &(_, file) in OWN_MODULES.iter().filter(|(m, _)| !plan.kept.contains(*m)) {
        let text = match (file, cpu) {
            ("kcpsm6.v", CpuModel::Iss) => KCPSM6_ISS.to_string(),
            ("bot.v", _) if bot == BotKind::Model => BOT_MODEL.to_string(),
            ("kcpsm6.v", CpuModel::RtlProbed) => {
                generated.push(("botsim_kcpsm6_probe.sv".into(), KCPSM6_PROBE.into()));
                own_rtl(file).replacen("module kcpsm6 #(", "module kcpsm6_rtl #(", 1)
            }
            _ => own_rtl(file).to_string(),
        };
        // botsim's own files are SystemVerilog (the models' DPI imports).
        generated.push((format!("botsim_{}", file.replace(".v", ".sv")), text));
    }
    for (module, text) in wrapper::roms(plan) {
        generated.push((format!("botsim_rom_{module}.sv"), text));
    }
    let mut user = Vec::new();
    let made = plan.files.iter().map(|f| f.generated).collect();
    let converted = plan.files.iter().map(|f| f.converted_from.clone()).collect();
    for (k, f) in plan.files.iter().enumerate() {
        // Verilator 5.006 cuts a file's name at a space in its messages (`Verilog files/top.v`
        // is `Verilog:2:37`): a file whose path has anything but letters, digits and `_-./`
        // goes to it as a copy in the build folder, named plainly, as an edited one does.
        let plain = |p: &Path| {
            absolute(p).to_str().is_some_and(|s| s.bytes().all(|b| b.is_ascii_alphanumeric() || b"_-./".contains(&b)))
        };
        let text = match &f.filtered {
            Some(text) => Some(text.clone()),
            None if !plain(&f.path) => std::fs::read(&f.path).ok().map(|b| String::from_utf8_lossy(&b).into_owned()),
            None => None,
        };
        match text {
            Some(text) => {
                let base = f.path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                let base: String = base
                    .chars()
                    .map(|c| if c.is_ascii_alphanumeric() || "_-.".contains(c) { c } else { '_' })
                    .collect();
                user.push((format!("user{k}_{base}"), Some(text), f.path.clone()));
            }
            None => user.push((f.path.display().to_string(), None, f.path.clone())),
        }
    }
    let mut defines = vec!["BOTSIM_WORLD_PLUSARG".to_string()];
    if plan.loc_y_reg {
        defines.push("BOTSIM_LOC_Y_REG".into());
    }
    for (prim, mask) in &plan.used_outputs {
        defines.push(format!("BOTSIM_USED_{prim}=8'h{mask:02X}"));
    }
    Files { generated, user, made, converted, defines }
}

/// Build (or find in the cache) the library for `plan` with `cpu` for its KCPSM6s; `debug`:
/// with the KCPSM6 debug signals for waveforms (`kcpsm6_opcode`, `kcpsm6_status`,
/// `sim_s0`..`sim_sF`, the scratch pad), a build of its own so that runs without a waveform
/// do not compute them.
pub fn build(
    plan: &Plan,
    params: &[(String, String)],
    cpu: CpuModel,
    bot: BotKind,
    debug: bool,
    quiet: bool,
) -> Result<Built, BoardError> {
    let mut f = files(plan, params, cpu, bot);
    if debug {
        f.defines.push("BOTSIM_DEBUG".into());
    }
    let program = std::env::var("VERILATOR").unwrap_or_else(|_| "verilator".into());
    let v = verilator::find(&program).map_err(BoardError::plain)?;
    let key = build_key(plan, &f, &v)?;
    let boards = cache_dir().join("boards");
    let dir = boards.join(format!("{}-{key}", plan.top));
    let library = dir.join("libboard.so");
    // One build per design at a time: a second run waits for the first's, then reuses it.
    let lock = cache_dir().join("locks").join(format!("{}-{key}.lock", plan.top));
    let _lock = if library.exists() { None } else { Some(Lock::take(&lock, quiet)?) };
    if library.exists() {
        return Ok(reused(plan, &f, &dir, v.version));
    }
    let t0 = Instant::now();
    remove_stale_builds(&boards);
    let tmp = dir.with_extension(format!("tmp{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp)
        .map_err(|e| BoardError::at(&tmp, 0, 0, format!("cannot create the build folder: {e}")))?;
    tag_cache(&cache_dir());
    let step = Step { tmp: tmp.clone(), budget: build_budget(), t0 };
    if !quiet {
        eprintln!(
            "botsim board: building `{}` (Verilator, then C++; the next run with these sources reuses it)",
            plan.top
        );
    }
    // Whatever fails, the files so far are kept where BOTSIM_KEEP_GENERATED asks.
    let fail = |e| {
        keep_generated(&tmp);
        let _ = std::fs::remove_dir_all(&tmp);
        e
    };
    let made = write_sources(&step, &f).and_then(|_| verilate(&step, &program, plan, &f, debug)).and_then(
        |(stderr, delays)| {
            let checked = analyse(&step, delays.as_deref())?;
            let stderr = compile(&step, &v, plan, &f, delays.is_some(), stderr)?;
            Ok((stderr, delays, checked))
        },
    );
    let (stderr, delays, checked) = made.map_err(fail)?;
    std::fs::rename(tmp.join("obj/libboard.so"), tmp.join("libboard.so"))
        .and_then(|_| std::fs::write(tmp.join("warnings.txt"), &stderr))
        .and_then(|_| checked.verdicts.save(&tmp))
        .and_then(|_| std::fs::write(tmp.join(DELAYS_FILE), delays.as_deref().unwrap_or("")))
        .and_then(|_| crate::fastforward::checks::save_unshown(&tmp, &checked.unshown))
        .map_err(|e| BoardError::at(&tmp, 0, 0, format!("cannot keep the build: {e}")))?;
    keep_generated(&tmp);
    let _ = std::fs::remove_dir_all(tmp.join("obj"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::rename(&tmp, &dir).map_err(|e| BoardError::at(&dir, 0, 0, format!("cannot keep the build: {e}")))?;
    Ok(Built {
        library,
        warnings: parse_warnings(&stderr, &f),
        widths: explain::replacement_widths(&stderr, &explained(&f), &|m| stands_for(plan, m)),
        seconds: Some(t0.elapsed().as_secs_f64()),
        delays,
        verilator: v.version,
        names: names(&f),
    })
}

/// The cache key of a build: everything it is built from (botsim's version, the Verilator,
/// the harness and the analyses, the flags, the design's files as Verilator is given them).
fn build_key(plan: &Plan, f: &Files, v: &verilator::Verilator) -> Result<String, BoardError> {
    let mut h = DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    // A design built by another Verilator is another build.
    v.version.hash(&mut h);
    v.root.hash(&mut h);
    HARNESS.hash(&mut h);
    MODEL_H.hash(&mut h);
    MODEL_CPP.hash(&mut h);
    VERILATOR_FLAGS.hash(&mut h);
    MAKE_VARS.hash(&mut h);
    // The analyses whose results the harness is compiled with.
    include_str!("../fastforward/observed.rs").hash(&mut h);
    include_str!("../fastforward/counters.rs").hash(&mut h);
    include_str!("../fastforward/demand.rs").hash(&mut h);
    include_str!("../fastforward/strobes.rs").hash(&mut h);
    include_str!("../fastforward/cpp.rs").hash(&mut h);
    include_str!("../fastforward/dialect.rs").hash(&mut h);
    include_str!("../fastforward/apart.rs").hash(&mut h);
    ABI.hash(&mut h);
    PRINT.hash(&mut h);
    PCH.hash(&mut h);
    FORCED.hash(&mut h);
    DISASM.hash(&mut h);
    // The check whose verdict the build keeps.
    include_str!("../fastforward/checks.rs").hash(&mut h);
    f.generated.hash(&mut h);
    f.defines.hash(&mut h);
    // The user's files and include folders as Verilator is given them (absolute paths), so
    // the same sources named from another folder find the same build.
    for (name, text, path) in &f.user {
        absolute(path).hash(&mut h);
        match text {
            Some(t) => (name, t).hash(&mut h),
            None => {
                std::fs::read(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?.hash(&mut h)
            }
        }
    }
    for d in &plan.include_dirs {
        absolute(d).hash(&mut h);
    }
    // Included files (.vh) are part of the input too.
    for d in &plan.include_dirs {
        if let Ok(rd) = std::fs::read_dir(d) {
            let mut incs: Vec<PathBuf> = rd
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "vh" || e == "svh"))
                .collect();
            incs.sort();
            for p in incs {
                std::fs::read(&p).unwrap_or_default().hash(&mut h);
            }
        }
    }
    Ok(format!("{:016x}", h.finish()))
}

/// A build the cache has, as it was kept.
fn reused(plan: &Plan, f: &Files, dir: &Path, verilator: String) -> Built {
    keep_generated(dir);
    let stderr = std::fs::read_to_string(dir.join("warnings.txt")).unwrap_or_default();
    Built {
        library: dir.join("libboard.so"),
        warnings: parse_warnings(&stderr, f),
        widths: explain::replacement_widths(&stderr, &explained(f), &|m| stands_for(plan, m)),
        seconds: None,
        delays: std::fs::read_to_string(dir.join(DELAYS_FILE)).ok().filter(|d| !d.is_empty()),
        verilator,
        names: names(f),
    }
}

/// A build in progress: its folder, and the time it may take from when it began.
struct Step {
    tmp: PathBuf,
    budget: Duration,
    t0: Instant,
}

impl Step {
    fn write(&self, name: &str, text: &str) -> Result<(), BoardError> {
        let path = self.tmp.join(name);
        std::fs::write(&path, text).map_err(|e| BoardError::at(&path, 0, 0, format!("cannot write: {e}")))
    }

    fn run(&self, cmd: &mut Command) -> Result<Output, BoardError> {
        run_with_budget(cmd, self.budget, self.t0)
    }
}

/// The build's sources in its folder: botsim's, the harness, the user's edited files.
fn write_sources(step: &Step, f: &Files) -> Result<(), BoardError> {
    for (name, text) in &f.generated {
        step.write(name, text)?;
    }
    for (name, text) in [
        ("harness.cpp", HARNESS),
        ("board_model.h", MODEL_H),
        ("board_model.cpp", MODEL_CPP),
        ("board_abi.h", ABI),
        ("botsim_print.h", PRINT),
        ("botsim_disasm.h", DISASM),
    ] {
        step.write(name, text)?;
    }
    for (name, text, _) in &f.user {
        if let Some(t) = text {
            step.write(name, t)?;
        }
    }
    Ok(())
}

/// Verilator on the sources: its messages, and where the design's first delay is when it has
/// delays (built again with Verilator's timing then).
fn verilate(
    step: &Step,
    program: &str,
    plan: &Plan,
    f: &Files,
    debug: bool,
) -> Result<(String, Option<String>), BoardError> {
    let mut cmd = Command::new(program);
    cmd.current_dir(&step.tmp)
        .args(["--cc", "--exe"])
        .args(["--prefix", "Vboard", "--top-module", wrapper::TOP, "--Mdir", "obj", "-o", "libboard.so"])
        .args(VERILATOR_FLAGS);
    if debug {
        // The register file and the scratch pad (up to 256 bytes) in the waveform.
        cmd.args(["--trace-max-array", "256"]);
    }
    for d in &f.defines {
        cmd.arg(format!("+define+{d}"));
    }
    for d in &plan.include_dirs {
        cmd.arg(format!("+incdir+{}", absolute(d).display()));
    }
    for (name, _) in &f.generated {
        cmd.arg(name);
    }
    for (name, text, path) in &f.user {
        if text.is_some() {
            cmd.arg(name);
        } else {
            cmd.arg(absolute(path));
        }
    }
    cmd.args(["harness.cpp", "board_model.cpp"]);
    let mut out = step.run(&mut cmd)?;
    // A design with delays (`q <= #1 d`, `initial #10_000_000 $finish`): Verilator asks how
    // to treat them, and botsim simulates them (Vivado's synthesis ignores them; a
    // simulation of the board keeps what the design says). Said once, at the first.
    let mut delays = None;
    if !out.status.success() {
        let text = String::from_utf8_lossy(&out.stderr).into_owned();
        if let Some(line) = text.lines().find(|l| l.starts_with("%Error-NEEDTIMINGOPT: ")) {
            let at = line["%Error-NEEDTIMINGOPT: ".len()..].split(": ").next().unwrap_or("").to_string();
            delays = Some(user_paths(&at, f));
            let _ = std::fs::remove_dir_all(step.tmp.join("obj"));
            cmd.arg("--timing").args(["-CFLAGS", "-DBOTSIM_TIMING"]);
            out = step.run(&mut cmd)?;
        }
    }
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    if !out.status.success() {
        return Err(first_error(&stderr, &String::from_utf8_lossy(&out.stdout), f, plan));
    }
    Ok((stderr, delays))
}

/// What the harness may assume of the design (BoardModel::load reads the verdicts; the
/// harness is given which variables a run observes through botsim_observed.h).
fn analyse(step: &Step, delays: Option<&str>) -> Result<crate::fastforward::checks::Checked, BoardError> {
    let mut checked = crate::fastforward::checks::Checked::of(&step.tmp.join("obj"));
    if let Some(at) = delays {
        // Timed events wait in Verilator's own queue, outside the state the fast-forward
        // compares; every edge is evaluated.
        let why = format!("the design has delays ({at}): every edge is simulated, and the delays with them");
        checked.verdicts.fast_forward = Some(why.clone());
        checked.verdicts.falling_edges = Some(why.clone());
        checked.verdicts.observed = Some(why.clone());
        checked.unshown = Err(why);
    }
    step.write(
        "botsim_observed.h",
        &crate::fastforward::observed::header(
            &checked.members,
            &checked.counters,
            &checked.out_port_free,
            &checked.apart,
            checked.triggers_fn.as_deref(),
        ),
    )?;
    Ok(checked)
}

/// The C++: the model and board_model.cpp into the library, with Verilator's run-time
/// objects, the harness and the precompiled header from the cache (compiled and kept by the
/// first build of these flags). Verilator's messages `stderr` with the compiler's after them.
fn compile(
    step: &Step,
    v: &verilator::Verilator,
    plan: &Plan,
    f: &Files,
    timing: bool,
    mut stderr: String,
) -> Result<String, BoardError> {
    let obj = step.tmp.join("obj");
    step.write("obj/botsim_pch.h", PCH)?;
    step.write("obj/botsim_pch.mk", PCH_RULE)?;
    let runtime = Runtime::new(v, timing, &obj);
    runtime.lend();
    if !obj.join(Runtime::PCH).exists() {
        let mut make = Command::new("make");
        make.current_dir(&obj).args(["-f", "Vboard.mk", "-f", "botsim_pch.mk"]).args(MAKE_VARS).arg(Runtime::PCH);
        let out = step.run(&mut make)?;
        if !out.status.success() {
            // Every file parses botsim_pch.h itself instead.
            let _ = std::fs::remove_file(obj.join(Runtime::PCH));
        }
    }
    let jobs = std::thread::available_parallelism().map_or(2, |n| n.get());
    let mut make = Command::new("make");
    make.current_dir(&obj).args(["-f", "Vboard.mk", "-j"]).arg(jobs.to_string()).args(MAKE_VARS).arg(FORCED);
    let out = step.run(&mut make)?;
    if out.status.success() {
        runtime.keep();
    }
    stderr.push_str(&String::from_utf8_lossy(&out.stderr));
    if !out.status.success() || !obj.join("libboard.so").exists() {
        return Err(first_error(&stderr, &String::from_utf8_lossy(&out.stdout), f, plan));
    }
    Ok(stderr)
}

/// An exclusive lock on a build (a lock file beside its folder, `flock`), released when
/// dropped (or when the process ends, however it ends).
struct Lock {
    _file: std::fs::File,
}

impl Lock {
    /// Take the lock at `path`, waiting (within the build's budget, and until Ctrl-C) for a
    /// run that holds it.
    fn take(path: &Path, quiet: bool) -> Result<Lock, BoardError> {
        use std::os::fd::AsRawFd;
        if let Some(d) = path.parent() {
            std::fs::create_dir_all(d)
                .map_err(|e| BoardError::at(d, 0, 0, format!("cannot create the build folder: {e}")))?;
        }
        let file = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
            .map_err(|e| BoardError::at(path, 0, 0, format!("cannot lock the build: {e}")))?;
        let start = Instant::now();
        let mut said = false;
        loop {
            // SAFETY: flock on a descriptor this function owns.
            if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0 {
                return Ok(Lock { _file: file });
            }
            if !said && !quiet {
                eprintln!("botsim board: waiting for another botsim that is building this design");
                said = true;
            }
            if interrupted() {
                return Err(BoardError::plain("interrupted (Ctrl-C) while waiting for another build"));
            }
            if start.elapsed() > build_budget() {
                return Err(BoardError::plain(format!(
                    "another botsim has been building this design for more than {} s ({} is locked)",
                    build_budget().as_secs(),
                    path.display()
                )));
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

/// What every build of one Verilator with botsim's flags compiles the same: Verilator's
/// run-time library (`verilated.o` and the others its makefile lists as global objects), the
/// harness (`harness.o`: it sees a design only through board_model.h) and the precompiled
/// header (botsim_pch.h). Compiled by the first build, kept in the cache, and given to the
/// next builds' makefiles, which then find them made: a build compiles only the design's model
/// and board_model.cpp (measured in docs/PERFORMANCE.md).
struct Runtime {
    /// Where the objects are kept, by what they are compiled from.
    dir: PathBuf,
    /// The build's folder of objects, and the objects its makefile needs.
    obj: PathBuf,
    names: Vec<String>,
}

impl Runtime {
    /// The precompiled botsim_pch.h.
    const PCH: &'static str = "botsim_pch.h.gch";

    fn new(v: &verilator::Verilator, timing: bool, obj: &Path) -> Runtime {
        let mut h = DefaultHasher::new();
        (&v.version, &v.root, VERILATOR_FLAGS, MAKE_VARS, PRINT, PCH, PCH_RULE, timing).hash(&mut h);
        // The harness, which sees a design only through board_model.h.
        (HARNESS, MODEL_H, ABI, DISASM).hash(&mut h);
        // The makefile's list: VM_GLOBAL_FAST and VM_GLOBAL_SLOW, one name a line.
        let classes = std::fs::read_to_string(obj.join("Vboard_classes.mk")).unwrap_or_default();
        let mut names = Vec::new();
        let mut in_global = false;
        for line in classes.lines() {
            let t = line.trim().trim_end_matches('\\').trim();
            if t.starts_with("VM_GLOBAL_FAST +=") || t.starts_with("VM_GLOBAL_SLOW +=") {
                in_global = true;
            } else if t.is_empty() || t.contains('=') || t.starts_with('#') {
                in_global = false;
            } else if in_global && t.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                names.push(t.to_string());
            }
        }
        // And what they are compiled from as it is now (an installation updated in place keeps
        // its version string).
        let include = v.root.join("include");
        for file in names.iter().map(|n| format!("{n}.cpp")).chain(["verilated.h".into(), "verilated_config.h".into()])
        {
            std::fs::read(include.join(file)).unwrap_or_default().hash(&mut h);
        }
        names.push("harness".into());
        Runtime { dir: cache_dir().join("runtime").join(format!("{:016x}", h.finish())), obj: obj.to_path_buf(), names }
    }

    /// Put the kept objects in the build's folder, newer than its makefile (which they
    /// depend on), so that make takes them as made.
    fn lend(&self) {
        // The precompiled header is large (tens of MB): linked, not copied, where it can be.
        let (kept, to) = (self.dir.join(Self::PCH), self.obj.join(Self::PCH));
        if kept.exists() && std::fs::hard_link(&kept, &to).is_err() {
            let _ = std::fs::copy(&kept, &to);
        }
        for n in &self.names {
            let (kept, to) = (self.dir.join(format!("{n}.o")), self.obj.join(format!("{n}.o")));
            if std::fs::copy(&kept, &to).is_ok() {
                let touched = std::fs::File::options()
                    .write(true)
                    .open(&to)
                    .and_then(|f| f.set_modified(std::time::SystemTime::now()));
                if touched.is_err() {
                    let _ = std::fs::remove_file(&to);
                }
            }
        }
    }

    /// Keep the objects this build compiled that the cache does not have yet (each written
    /// whole, then renamed: builds may run side by side).
    fn keep(&self) {
        let _ = std::fs::create_dir_all(&self.dir);
        let files = self.names.iter().map(|n| format!("{n}.o")).chain([Self::PCH.to_string()]);
        for file in files {
            let (made, kept) = (self.obj.join(&file), self.dir.join(&file));
            if kept.exists() || !made.exists() {
                continue;
            }
            let part = self.dir.join(format!(".{file}.{}", std::process::id()));
            if std::fs::copy(&made, &part).is_ok() && std::fs::rename(&part, &kept).is_ok() {
                continue;
            }
            let _ = std::fs::remove_file(&part);
        }
    }
}

/// Remove the temporary folders of builds whose process is gone (stopped by a crash or a
/// kill; Ctrl-C removes its own): `<design>.tmp<pid>`.
fn remove_stale_builds(boards: &Path) {
    for e in std::fs::read_dir(boards).into_iter().flatten().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(pid) = name.rsplit_once(".tmp").and_then(|(_, p)| p.parse::<libc::pid_t>().ok()) else { continue };
        // SAFETY: signal 0 only asks whether the process exists.
        let alive =
            unsafe { libc::kill(pid, 0) } == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM);
        if !alive {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// The longest a build may take: `$BOTSIM_BUILD_TIMEOUT` seconds, else 20 minutes.
fn build_budget() -> Duration {
    let secs = std::env::var("BOTSIM_BUILD_TIMEOUT").ok().and_then(|v| v.parse().ok()).unwrap_or(1200);
    Duration::from_secs(secs)
}

/// Run a step of the build that began at `start` within the build's `budget`; past it, stop
/// the whole step (Verilator, or make and its compilers: the process group) and say so.
fn run_with_budget(cmd: &mut Command, budget: Duration, start: Instant) -> Result<Output, BoardError> {
    use std::os::unix::process::CommandExt;
    let mut child = cmd.process_group(0).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().map_err(|e| {
        let program = cmd.get_program().to_string_lossy().into_owned();
        BoardError::plain(format!("cannot run {program}: {e} (install it: scripts/setup.sh)"))
    })?;
    let read = |r: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            if let Some(mut r) = r {
                let _ = r.read_to_end(&mut v);
            }
            v
        })
    };
    let out_reader = read(child.stdout.take().map(|s| Box::new(s) as Box<dyn Read + Send>));
    let err_reader = read(child.stderr.take().map(|s| Box::new(s) as Box<dyn Read + Send>));
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() < budget && !interrupted() => std::thread::sleep(Duration::from_millis(50)),
            Ok(None) => {
                // SAFETY: signals the build's own process group (process_group(0) above).
                unsafe { libc::kill(-(child.id() as libc::pid_t), libc::SIGKILL) };
                let _ = child.wait();
                if interrupted() {
                    return Err(BoardError::plain("interrupted (Ctrl-C): the build was stopped"));
                }
                return Err(BoardError::plain(format!(
                    "the build took longer than {} s and was stopped (BOTSIM_BUILD_TIMEOUT sets the limit)",
                    budget.as_secs()
                )));
            }
            Err(e) => return Err(BoardError::plain(format!("the build failed: {e}"))),
        }
    };
    let stdout = out_reader.join().unwrap_or_default();
    let stderr = err_reader.join().unwrap_or_default();
    Ok(Output { status, stdout, stderr })
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// A name Verilator is given a user's file by, the user's path for it, and for a conversion
/// the line every message about it points at (the VHDL entity's: GHDL's Verilog is not in the
/// user's tree).
#[derive(Clone, Debug)]
struct Name {
    given: String,
    user: String,
    line: Option<u32>,
}

/// The names Verilator is given the user's files by, with the user's paths: the build
/// folder's copies of edited files, the absolute paths of the others.
fn names(f: &Files) -> Vec<Name> {
    let mut names = Vec::new();
    for ((name, text, path), from) in f.user.iter().zip(&f.converted) {
        if let Some((original, line)) = from {
            names.push(Name { given: name.clone(), user: original.display().to_string(), line: Some(*line) });
            continue;
        }
        let user = path.display().to_string();
        if text.is_some() {
            names.push(Name { given: name.clone(), user, line: None });
        } else {
            // Verilator writes some absolute paths with a doubled first slash.
            let given = absolute(path).display().to_string();
            names.push(Name { given: format!("/{given}"), user: user.clone(), line: None });
            names.push(Name { given, user, line: None });
        }
    }
    names.retain(|n| n.given != n.user);
    names
}

/// `msg` with the user's paths for the build's names (a conversion's `name:line:col` as the
/// original's `file:line`).
fn to_user(msg: &str, names: &[Name]) -> String {
    let mut m = msg.to_string();
    for n in names {
        let Some(line) = n.line else {
            m = m.replace(n.given.as_str(), &n.user);
            continue;
        };
        let mut out = String::new();
        let mut rest = m.as_str();
        while let Some(i) = rest.find(n.given.as_str()) {
            out.push_str(&rest[..i]);
            out.push_str(&n.user);
            rest = &rest[i + n.given.len()..];
            // Its `:line` and `:col`, when they follow, are the conversion's: the original's line.
            let mut skipped = false;
            for _ in 0..2 {
                let digits = rest
                    .strip_prefix(':')
                    .map_or(0, |r| r.len() - r.trim_start_matches(|c: char| c.is_ascii_digit()).len());
                if digits == 0 {
                    break;
                }
                rest = &rest[1 + digits..];
                skipped = true;
            }
            if skipped {
                out.push_str(&format!(":{line}"));
            }
        }
        out.push_str(rest);
        m = out;
    }
    m
}

/// The build's files as [`explain`] reads Verilator's errors about them.
fn explained(f: &Files) -> Vec<explain::File> {
    let mut out: Vec<explain::File> = f
        .generated
        .iter()
        .map(|(name, text)| explain::File {
            given: name.clone(),
            shown: format!("botsim's {name}"),
            origin: explain::Origin::Own,
            text: text.clone(),
            original: None,
        })
        .collect();
    for ((name, text, path), made) in f.user.iter().zip(&f.made) {
        let on_disk = || std::fs::read_to_string(path).ok();
        let (given, text, original) = match text {
            Some(t) => (name.clone(), t.clone(), if *made { None } else { on_disk() }),
            None => (absolute(path).display().to_string(), on_disk().unwrap_or_default(), None),
        };
        let origin = if *made { explain::Origin::Generated } else { explain::Origin::User };
        out.push(explain::File { given, shown: path.display().to_string(), origin, text, original });
    }
    out
}

/// What of botsim's stands for the design's module `module`, if anything does.
fn stands_for(plan: &Plan, module: &str) -> Option<explain::Stand> {
    let own = OWN_MODULES.iter().any(|(m, _)| *m == module) || PRIMITIVES.iter().any(|(m, _)| *m == module);
    if own {
        return Some(explain::Stand::Model(format!("botsim's `{module}`")));
    }
    match plan.replaced.iter().find(|r| r.module == module) {
        Some(r) if r.with == STUB => Some(explain::Stand::Model(r.with.clone())),
        Some(r) => Some(explain::Stand::Built(r.with.clone())),
        None => None,
    }
}

/// Replace the build folder's copies of the user's files by the user's paths.
fn user_paths(msg: &str, f: &Files) -> String {
    to_user(msg, &names(f))
}

/// Verilator's `%Warning-CODE: file:line:col: message` lines about the user's files, grouped.
fn parse_warnings(stderr: &str, f: &Files) -> Vec<(String, usize, String)> {
    let mut groups: BTreeMap<String, (usize, String)> = BTreeMap::new();
    for line in stderr.lines() {
        let Some(rest) = line.strip_prefix("%Warning-") else { continue };
        let Some((code, msg)) = rest.split_once(": ") else { continue };
        // Widths are asked for the connections of botsim's replacements only (`widths`).
        if code.starts_with("WIDTH") {
            continue;
        }
        let own = f.generated.iter().any(|(n, _)| msg.starts_with(n.as_str()));
        if own || msg.contains("/usr/share/verilator") {
            continue;
        }
        let e = groups.entry(code.to_string()).or_insert((0, user_paths(msg, f)));
        e.0 += 1;
    }
    groups.into_iter().map(|(c, (n, m))| (c, n, m)).collect()
}

/// The first error of a failed build, with the user's file:line:col.
fn first_error(stderr: &str, stdout: &str, f: &Files, plan: &Plan) -> BoardError {
    if let Some(line) = explain::explain(stderr, &explained(f), &|m| stands_for(plan, m)) {
        return BoardError::plain(line);
    }
    for line in stderr.lines().chain(stdout.lines()) {
        if line.contains("error:") {
            return BoardError::plain(format!("the C++ build failed: {}", user_paths(line.trim(), f)));
        }
    }
    let tail: Vec<&str> = stderr.lines().rev().take(3).collect();
    BoardError::plain(format!("the Verilator build failed: {}", tail.into_iter().rev().collect::<Vec<_>>().join(" / ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conversions_lines_are_the_originals_entity_line() {
        let names = [
            Name { given: "user3_AccelCtl.vhd.v".into(), user: "hdl/AccelCtl.vhd".into(), line: Some(7) },
            Name { given: "/abs/top.v".into(), user: "top.v".into(), line: None },
        ];
        assert_eq!(
            to_user("user3_AccelCtl.vhd.v:412:9: Signal is not driven: 'x' (see /abs/top.v:3:5)", &names),
            "hdl/AccelCtl.vhd:7: Signal is not driven: 'x' (see top.v:3:5)"
        );
        // Named without a line, and twice in one message.
        assert_eq!(
            to_user("in user3_AccelCtl.vhd.v, and user3_AccelCtl.vhd.v:2", &names),
            "in hdl/AccelCtl.vhd, and hdl/AccelCtl.vhd:7"
        );
    }
}
