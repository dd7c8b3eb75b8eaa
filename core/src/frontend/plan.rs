//! From a user's sources to what is built: the top, what botsim substitutes and why, the
//! program of every ROM, the primitives' models, the pins, and the path to the `bot`.
//!
//! Substitution is by module name (botsim's `kcpsm6`, `bot`, `world_if`, `map`,
//! `world_map` and the Xilinx primitives replace the user's copies or netlists) and by
//! interface (every module with a KCPSM6 program-ROM interface, `address`, `instruction`,
//! `enable`, `clk`, becomes a behavioural ROM holding its own program).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use kcpsm6::image::Image;

use super::constraints::Board;
use super::drivers;
use super::parts::{
    bot_locy_port, foreign_port, is_bot, is_program_rom, own_module, Replacement, HELPERS, OWN_MODULES, PRIMITIVES,
};
use super::pins::{self, Role};
use super::resolve::Design;
use super::scan::{Dir, Instance, Module};
pub use super::source::Source;
use super::BoardError;

/// What the user asked for on the command line that the plan needs.
#[derive(Clone, Debug)]
pub struct Request {
    /// Programs named with `--program`, assembled or loaded: (file, image).
    pub programs: Vec<(PathBuf, Image)>,
    /// botsim's firmware for the bot, when asked for (by `--timing`, `--threshold`,
    /// `--compat`), or when the sources have no `bot_pgm`.
    pub bot_firmware: Image,
    /// True when the request selects botsim's firmware even if the user has a `bot_pgm`.
    pub force_own_firmware: bool,
    /// Of several bots, the one that options about the bot mean (`--bot-at`): its instance
    /// path from the top, with or without the top's name.
    pub first_bot: Option<String>,
}

/// A ROM to generate: the module name, its program, and where the program came from.
#[derive(Clone, Debug)]
pub struct Rom {
    pub module: String,
    pub image: Image,
    pub origin: String,
    /// The assembly source of the program, when known: the `.psm` named with `--program`, or
    /// the one beside the ROM's `.v` (`<module>.psm`, as the KCPSM6 assembler writes them)
    /// when it assembles to the ROM's INIT strings. Traces and breakpoints show its lines.
    pub source: Option<PathBuf>,
}

/// The instance name of the KCPSM6 inside botsim's `bot` (rtl/bot.v), and of its ROM.
pub const BOT_CPU_INSTANCE: &str = "BOTSIMCPU";

/// A KCPSM6 in the design, and the program ROM wired to its `instruction` port (what
/// `--cpu iss` loads into the instruction-set simulator that stands in for it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CpuSite {
    /// The hierarchical path from the top (`SYS.APPCPU`).
    pub path: String,
    /// The ROM module whose `instruction` output drives the instance's `instruction`, or
    /// why none was found.
    pub rom: Result<String, String>,
    /// Where the instance is: file:line.
    pub at: String,
}

/// Everything the build needs.
#[derive(Clone, Debug)]
pub struct Plan {
    pub top: String,
    /// The user's files to compile, as they are (unchanged) or with replaced modules blanked.
    pub files: Vec<UserFile>,
    pub include_dirs: Vec<PathBuf>,
    pub roms: Vec<Rom>,
    /// `BOTSIM_USED_<PRIMITIVE>` masks.
    pub used_outputs: BTreeMap<String, u8>,
    pub replaced: Vec<Replacement>,
    pub warnings: Vec<String>,
    pub pins: Vec<(String, Role)>,
    pub unknown_pins: Vec<String>,
    /// The board a constraint file places the top's pins on, if one does.
    pub board: Option<Board>,
    /// The top's port widths.
    pub widths: BTreeMap<String, u32>,
    /// The top's input ports, and its inout ones.
    pub inputs: BTreeSet<String>,
    pub inouts: BTreeSet<String>,
    /// The hierarchical path from the top to the bot (botsim's BotSim 2.0 `bot`, or the
    /// team's own, [`Plan::team_bot`]); `None` for a design without a bot (a final project:
    /// the board alone).
    pub bot_path: Option<String>,
    /// The bot's KCPSM6 (its path from the top).
    pub bot_cpu: Option<String>,
    /// The bot is the team's own module (a BotSim 3.1 `bot`), simulated from its RTL.
    pub team_bot: Option<TeamBot>,
    /// The design's other bots (a game's monster beside its hero), each traced and reported
    /// as the first is; at most [`MAX_BOTS`] in all.
    pub other_bots: Vec<BotSite>,
    /// botsim's own module names that are the team's modules here (other ports than
    /// botsim's: [`foreign_port`]): kept as committed, botsim's left out of the build.
    pub kept: BTreeSet<String>,
    /// The user instantiates the bot with `Loc_Y_reg` (later copies of the course files).
    pub loc_y_reg: bool,
    /// Every KCPSM6 instance: the team's and, last, the bot's.
    pub cpus: Vec<CpuSite>,
}

/// `s` with the nets of its modules that `compiled` names resolved where they have several
/// drivers ([`drivers`]), each said in `warnings` at its first driver, naming every one and
/// where; `None` when it has none.
fn resolve_shared_nets(
    s: &Source,
    compiled: &dyn Fn(&str) -> bool,
    dir: &dyn Fn(&str, &str) -> Option<Dir>,
    warnings: &mut Vec<String>,
) -> Option<Source> {
    let mut edits = Vec::new();
    for m in s.modules.iter().filter(|m| compiled(&m.name)) {
        let shared = drivers::shared_nets(m, dir);
        for n in &shared {
            let place = |d: &drivers::Driver| {
                let (line, col) = s.line_col(d.at.start);
                format!("{}:{line}:{col}", s.path.display())
            };
            let places: Vec<String> = n.drivers.iter().map(|d| format!("{} ({})", d.what, place(d))).collect();
            warnings.push(format!(
                "{}: `{}` in `{}` has {} drivers, {}: Vivado refuses it (DRC MDRV-1, Multiple Driver Nets); botsim gives each bit the value its drivers agree on and 0 where they differ (x in Verilog), on every board alike",
                place(&n.drivers[0]),
                n.net,
                m.name,
                n.drivers.len(),
                places.join(" and ")
            ));
        }
        edits.extend(drivers::rewrite(m, &shared));
    }
    if edits.is_empty() {
        return None;
    }
    let mut e = s.clone();
    edits.sort_by_key(|(at, _)| at.start);
    for (at, with) in edits.into_iter().rev() {
        e.replace(at, &with);
    }
    Some(e)
}

/// The most bots a design may have (the board's wrapper taps each: core/src/frontend/wrapper.rs).
pub const MAX_BOTS: usize = 4;

/// A bot of the design: its path from the top, its KCPSM6's, and its module when the team's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BotSite {
    pub path: String,
    pub cpu: Option<String>,
    pub team: Option<TeamBot>,
}

/// A bot the team defines (a module with the bot's ports, [`is_bot`], that is not botsim's
/// `bot`): simulated from its own RTL, observed at its ports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TeamBot {
    pub module: String,
    /// Where its module is: file:line.
    pub at: String,
    /// Its Y-register port (`LocY_reg` or `Loc_Y_reg`).
    pub locy: String,
    /// The port that makes it another BotSim than 2.0 (`Bot_Config_reg`), if one does.
    pub config: Option<String>,
    /// It has the motor-distance registers (`LMDist_reg`, `RMDist_reg`).
    pub has_distances: bool,
}

impl Plan {
    /// The path of botsim's own bot (BotSim 2.0), which its model can stand for; `None` when
    /// the design has no bot or its bot is the team's.
    pub fn own_bot(&self) -> Option<&str> {
        self.bot_path.as_deref().filter(|_| self.team_bot.is_none())
    }

    /// Some bot of the design is botsim's own (BotSim 2.0): `--bot` chooses what stands for
    /// botsim's bots.
    pub fn has_own_bot(&self) -> bool {
        self.bots().iter().any(|b| b.team.is_none())
    }

    /// Every bot of the design, the first (the one options about "the bot" mean) first.
    pub fn bots(&self) -> Vec<BotSite> {
        let first = self.bot_path.as_ref().map(|path| BotSite {
            path: path.clone(),
            cpu: self.bot_cpu.clone(),
            team: self.team_bot.clone(),
        });
        first.into_iter().chain(self.other_bots.iter().cloned()).collect()
    }
}

/// A user file in the build: its path, and its text when modules were blanked out of it
/// (or botsim edited it, or wrote it).
#[derive(Clone, Debug)]
pub struct UserFile {
    pub path: PathBuf,
    pub filtered: Option<String>,
    /// botsim wrote it (a core, a stand-in, a stub, a conversion): `path` says for what.
    pub generated: bool,
    /// A conversion: the file and line its messages point at ([`super::source::Source`]).
    pub converted_from: Option<(PathBuf, u32)>,
}

impl Plan {
    /// Plan the build of the design the resolver found ([`super::resolve`]) for `req`: each
    /// module's one definition, the hierarchy from the top, its bots, what botsim
    /// substitutes, the program ROMs, the user's files as compiled, the board's pins.
    pub fn new(design: &Design, req: &Request) -> Result<Plan, BoardError> {
        let defined = definitions(&design.sources)?;
        let kept = kept_own_names(&defined);
        let top = design.top.clone();
        if !defined.contains_key(top.as_str()) {
            return Err(BoardError::plain(format!("the top module `{top}` is not in the design's sources")));
        }
        let mut h = Hierarchy::walk(&defined, &kept, &top)?;
        let own_bot = !h.bot_paths.is_empty();
        let mut bots = h.bots(req, &top)?.into_iter();
        let (bot_path, bot_cpu, team_bot) = match bots.next() {
            Some(b) => (Some(b.path), b.cpu, b.team),
            None => (None, None, None),
        };
        let other_bots: Vec<BotSite> = bots.collect();
        let mut replaced = own_replacements(&defined, &kept, &h.used, own_bot);
        let mut warnings = Vec::new();
        let roms = program_roms(&defined, &h.used, own_bot, req, &mut replaced, &mut warnings)?;
        let files = user_files(&design.sources, &defined, &kept, &h.used, &roms, &mut warnings);
        let (top_src, top_module) = defined[top.as_str()];
        let mapped = pins::map(top_module, design.placed.as_ref()).map_err(|e| {
            BoardError::at(&top_src.path, top_module.line, top_module.col, format!("port `{}` {}", e.port, e.reason))
        })?;
        for w in &mapped.misdirected {
            warnings.push(format!("{}:{}:{}: {}", top_src.path.display(), w.line, w.col, w.message(&top)));
        }
        let ports = |dir: Dir| top_module.ports.iter().filter(|p| p.dir == dir).map(|p| p.name.clone()).collect();
        Ok(Plan {
            files,
            include_dirs: design.include_dirs.clone(),
            roms,
            used_outputs: std::mem::take(&mut h.used_outputs),
            replaced,
            warnings,
            pins: mapped.roles,
            unknown_pins: mapped.unknown,
            board: design.placed.as_ref().map(|p| p.board),
            widths: top_module.ports.iter().map(|p| (p.name.clone(), p.width)).collect(),
            inputs: ports(Dir::Input),
            inouts: ports(Dir::Inout),
            top,
            bot_path,
            bot_cpu,
            team_bot,
            other_bots,
            kept,
            loc_y_reg: h.loc_y_reg,
            cpus: h.cpus,
        })
    }
}

/// Each module of the design's sources by name, with its file; a module defined twice is an
/// error at its second definition.
type Defined<'a> = BTreeMap<&'a str, (&'a Source, &'a Module)>;

fn definitions(sources: &[Source]) -> Result<Defined<'_>, BoardError> {
    let mut defined: Defined = BTreeMap::new();
    for s in sources {
        for m in &s.modules {
            if let Some((other, om)) = defined.get(m.name.as_str()) {
                return Err(BoardError::at(
                    &s.path,
                    m.line,
                    m.col,
                    format!("module `{}` is defined twice (also at {}:{})", m.name, other.path.display(), om.line),
                ));
            }
            defined.insert(&m.name, (s, m));
        }
    }
    Ok(defined)
}

/// botsim's own names the team's modules take here with other ports: kept, and walked.
fn kept_own_names(defined: &Defined) -> BTreeSet<String> {
    OWN_MODULES
        .iter()
        .filter(|(n, _)| defined.get(n).is_some_and(|(_, m)| foreign_port(m).is_some()))
        .map(|(n, _)| n.to_string())
        .collect()
}

/// Is `n` a module botsim brings (its own, not kept as the team's, or a helper)?
fn own_name(kept: &BTreeSet<String>, n: &str) -> bool {
    (OWN_MODULES.iter().any(|(m, _)| *m == n) && !kept.contains(n)) || HELPERS.contains(&n)
}

/// The hierarchy from the top: every module used, the bots' paths, the KCPSM6s, the
/// primitives' outputs in use.
struct Hierarchy {
    used: BTreeSet<String>,
    /// botsim's BotSim 2.0 bots.
    bot_paths: Vec<String>,
    team_bots: Vec<(String, TeamBot)>,
    loc_y_reg: bool,
    used_outputs: BTreeMap<String, u8>,
    cpus: Vec<CpuSite>,
}

impl Hierarchy {
    fn walk(defined: &Defined, kept: &BTreeSet<String>, top: &str) -> Result<Hierarchy, BoardError> {
        let mut h = Hierarchy {
            used: BTreeSet::new(),
            bot_paths: Vec::new(),
            team_bots: Vec::new(),
            loc_y_reg: false,
            used_outputs: BTreeMap::new(),
            cpus: Vec::new(),
        };
        let mut missing: Option<BoardError> = None;
        let mut stack: Vec<(String, String)> = vec![(top.to_string(), String::new())];
        let mut depth_guard = 0;
        while let Some((name, path)) = stack.pop() {
            depth_guard += 1;
            if depth_guard > 100_000 {
                return Err(BoardError::plain("the module hierarchy does not end (a module instantiates itself?)"));
            }
            h.used.insert(name.clone());
            if name == "bot" && !kept.contains("bot") {
                h.bot_paths.push(path.clone());
                continue;
            }
            if let Some((src, m)) =
                defined.get(name.as_str()).filter(|(_, m)| is_bot(m) && !path.is_empty() && !own_name(kept, &name))
            {
                let config = m.ports.iter().map(|p| p.name.as_str()).find(|p| p.eq_ignore_ascii_case("Bot_Config_reg"));
                h.team_bots.push((
                    path.clone(),
                    TeamBot {
                        module: name.clone(),
                        at: format!("{}:{}", src.path.display(), m.line),
                        locy: bot_locy_port(m).unwrap_or("LocY_reg").to_string(),
                        config: config.map(str::to_string),
                        has_distances: m.port("LMDist_reg").is_some() && m.port("RMDist_reg").is_some(),
                    },
                ));
            }
            if own_name(kept, &name) {
                continue;
            }
            let Some((src, m)) = defined.get(name.as_str()) else { continue };
            if is_program_rom(m) {
                continue;
            }
            for inst in &m.instances {
                let child_path = if path.is_empty() { inst.name.clone() } else { format!("{path}.{}", inst.name) };
                if inst.module == "bot" && inst.connections.iter().any(|(p, _)| p == "Loc_Y_reg") {
                    h.loc_y_reg = true;
                }
                if inst.module == "kcpsm6" {
                    let rom = rom_of(inst, m, |n| defined.get(n).is_some_and(|(_, d)| is_program_rom(d)));
                    let at = format!("{}:{}", src.path.display(), inst.line);
                    h.cpus.push(CpuSite { path: child_path.clone(), rom, at });
                }
                if let Some((_, outs)) = PRIMITIVES.iter().find(|(p, _)| *p == inst.module) {
                    h.used.insert(inst.module.clone());
                    let mask = h.used_outputs.entry(inst.module.clone()).or_insert(0);
                    *mask |= connected_mask(inst, outs);
                    continue;
                }
                if !defined.contains_key(inst.module.as_str()) && !own_name(kept, &inst.module) {
                    missing.get_or_insert_with(|| {
                        BoardError::at(
                            &src.path,
                            inst.line,
                            inst.col,
                            format!(
                                "module `{}` (instance `{}` in `{}`) is not defined in the sources and botsim has no model of it; add its file or tie it off with --stub {}",
                                inst.module, inst.name, m.name, inst.module
                            ),
                        )
                    });
                    continue;
                }
                stack.push((inst.module.clone(), child_path));
            }
        }
        match missing {
            Some(e) => Err(e),
            None => Ok(h),
        }
    }

    /// Every bot, botsim's BotSim 2.0 ones first, each kind in the order of its path, the
    /// one `--bot-at` names first: the first is the one options about "the bot" mean. Adds
    /// botsim's bots' KCPSM6s to the CPUs.
    fn bots(&mut self, req: &Request, top: &str) -> Result<Vec<BotSite>, BoardError> {
        self.bot_paths.sort();
        self.team_bots.sort_by(|a, b| a.0.cmp(&b.0));
        let mut bots: Vec<BotSite> = Vec::new();
        for one in &self.bot_paths {
            let cpu = format!("{one}.{BOT_CPU_INSTANCE}");
            self.cpus.push(CpuSite { path: cpu.clone(), rom: Ok("bot_pgm".into()), at: "botsim's bot".into() });
            bots.push(BotSite { path: one.clone(), cpu: Some(cpu), team: None });
        }
        for (path, team) in &self.team_bots {
            let inside = format!("{path}.");
            let cpu = self.cpus.iter().find(|c| c.path.starts_with(&inside)).map(|c| c.path.clone());
            bots.push(BotSite { path: path.clone(), cpu, team: Some(team.clone()) });
        }
        if let Some(name) = &req.first_bot {
            let named = |b: &BotSite| *name == b.path || *name == format!("{top}.{}", b.path);
            let Some(k) = bots.iter().position(named) else {
                let paths: Vec<String> = bots.iter().map(|b| format!("{top}.{}", b.path)).collect();
                return Err(BoardError::plain(match paths.is_empty() {
                    true => format!("--bot-at {name}: the design has no bot"),
                    false => format!("--bot-at {name}: the design's bots are {}", paths.join(", ")),
                }));
            };
            let chosen = bots.remove(k);
            bots.insert(0, chosen);
        }
        if bots.len() > MAX_BOTS {
            let paths: Vec<&str> = bots.iter().map(|b| b.path.as_str()).collect();
            return Err(BoardError::plain(format!(
                "the design has {} bots ({}); botsim simulates up to {MAX_BOTS}",
                bots.len(),
                paths.join(", ")
            )));
        }
        Ok(bots)
    }
}

/// botsim's own modules (always in the build: a bot has them all) and the primitives the
/// design uses, as replacements of the user's copies: those of a design without a bot where
/// it uses them.
fn own_replacements(
    defined: &Defined,
    kept: &BTreeSet<String>,
    used: &BTreeSet<String>,
    own_bot: bool,
) -> Vec<Replacement> {
    let at =
        |name: &str| defined.get(name).map(|(s, m)| format!("{}:{}", s.path.display(), m.line)).unwrap_or_default();
    let mut replaced = Vec::new();
    for &(name, _) in OWN_MODULES.iter().filter(|(n, _)| !kept.contains(*n)) {
        let from = at(name);
        if !from.is_empty() && (own_bot || used.contains(name)) {
            replaced.push(Replacement { module: name.to_string(), from, with: format!("botsim's {name}") });
        } else if from.is_empty() && used.contains(name) {
            // Not committed (the team relied on the course folder): said, as the course's
            // other modules are.
            replaced.push(Replacement {
                module: name.to_string(),
                from,
                with: format!("botsim's {name} (the repository has none)"),
            });
        }
    }
    for (name, _) in PRIMITIVES {
        if used.contains(name) {
            replaced.push(Replacement {
                module: name.to_string(),
                from: at(name),
                with: format!("botsim's behavioural {name}"),
            });
        }
    }
    replaced
}

/// The program of every ROM the design uses (and the bot's firmware): `--program`'s file
/// named for it, else its own contents; each a replacement.
fn program_roms(
    defined: &Defined,
    used: &BTreeSet<String>,
    own_bot: bool,
    req: &Request,
    replaced: &mut Vec<Replacement>,
    warnings: &mut Vec<String>,
) -> Result<Vec<Rom>, BoardError> {
    let mut roms = Vec::new();
    let mut programs: Vec<(PathBuf, Image, bool)> =
        req.programs.iter().map(|(p, i)| (p.clone(), i.clone(), false)).collect();
    let rom_modules: Vec<(&Source, &Module)> = defined
        .values()
        .filter(|(_, m)| (is_program_rom(m) && used.contains(&m.name)) || (m.name == "bot_pgm" && own_bot))
        .copied()
        .collect();
    let team_roms = rom_modules.iter().filter(|(_, m)| m.name != "bot_pgm").count();
    for (src, m) in &rom_modules {
        // A ROM botsim wrote from a `.psm` (the repository has no Verilog of it) is that file.
        let at = if src.generated {
            src.path.with_extension("psm").display().to_string()
        } else {
            format!("{}:{}", src.path.display(), m.line)
        };
        if m.name == "bot_pgm" && req.force_own_firmware {
            continue;
        }
        // The program named for this ROM: by file stem, or the only one for the only ROM.
        let named = programs.iter().position(|(p, _, _)| p.file_stem().is_some_and(|s| s == m.name.as_str()));
        let named = named.or_else(|| (m.name != "bot_pgm" && team_roms == 1 && programs.len() == 1).then_some(0));
        let own_text = &src.text[m.span.clone()];
        let padded = format!("{}{own_text}", "\n".repeat(m.line.saturating_sub(1) as usize));
        let from_init = Image::parse_verilog(&src.path, &padded);
        let psm = |p: &Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("psm")).then(|| p.to_path_buf());
        let (image, origin, source) = match (named, from_init) {
            (Some(k), Ok(init)) => {
                programs[k].2 = true;
                if let Some(a) = first_difference(&programs[k].1, &init) {
                    warnings.push(format!(
                        "{} differs from the INIT strings of `{}` ({at}) from address {a:03X}: running {}",
                        programs[k].0.display(),
                        m.name,
                        programs[k].0.display()
                    ));
                }
                (programs[k].1.clone(), programs[k].0.display().to_string(), psm(&programs[k].0))
            }
            (Some(k), Err(_)) => {
                programs[k].2 = true;
                (programs[k].1.clone(), programs[k].0.display().to_string(), psm(&programs[k].0))
            }
            (None, Ok(init)) => {
                let source = source_beside(&src.path, &m.name, &init, warnings);
                let origin =
                    if src.generated { format!("{at}, assembled") } else { format!("its own contents ({at})") };
                (init, origin, source)
            }
            (None, Err(e)) => {
                return Err(BoardError::plain(format!(
                    "{at}: the program ROM `{}` holds no program ({}); name its .psm with --program",
                    m.name, e.message
                )))
            }
        };
        replaced.push(Replacement {
            module: m.name.clone(),
            from: at,
            with: format!("a behavioural ROM holding the program from {origin}"),
        });
        roms.push(Rom { module: m.name.clone(), image, origin, source });
    }
    if own_bot && !roms.iter().any(|r| r.module == "bot_pgm") {
        let why = if req.force_own_firmware {
            "botsim's firmware with the constants asked for"
        } else {
            "botsim's firmware (the sources have no bot_pgm)"
        };
        replaced.push(Replacement { module: "bot_pgm".into(), from: String::new(), with: why.into() });
        roms.push(Rom { module: "bot_pgm".into(), image: req.bot_firmware.clone(), origin: why.into(), source: None });
    }
    if let Some((p, _, _)) = programs.iter().find(|(_, _, used)| !used) {
        return Err(BoardError::plain(format!(
            "--program {}: no program ROM module named `{}` in the design (ROMs: {})",
            p.display(),
            p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            rom_modules.iter().map(|(_, m)| m.name.as_str()).collect::<Vec<_>>().join(", ")
        )));
    }
    Ok(roms)
}

/// The user's files, with replaced modules blanked (lines kept, so messages still point at
/// the user's lines) and nets with several drivers resolved.
fn user_files(
    sources: &[Source],
    defined: &Defined,
    kept: &BTreeSet<String>,
    used: &BTreeSet<String>,
    roms: &[Rom],
    warnings: &mut Vec<String>,
) -> Vec<UserFile> {
    let replaced_names: BTreeSet<String> = OWN_MODULES
        .iter()
        .filter(|(m, _)| !kept.contains(*m))
        .map(|(m, _)| m.to_string())
        .chain(PRIMITIVES.iter().map(|(p, _)| p.to_string()))
        .chain(roms.iter().map(|r| r.module.clone()))
        .collect();
    let own_modules: BTreeMap<&str, Module> =
        OWN_MODULES.iter().filter_map(|(n, _)| Some((*n, own_module(n)?))).collect();
    let dir = |module: &str, port: &str| -> Option<Dir> {
        let m = match own_name(kept, module) {
            true => own_modules.get(module)?,
            false => defined.get(module)?.1,
        };
        m.port(port).map(|p| p.dir)
    };
    let mut files = Vec::new();
    for s in sources {
        let resolved = resolve_shared_nets(s, &|m| used.contains(m) && !replaced_names.contains(m), &dir, warnings);
        let s = resolved.as_ref().unwrap_or(s);
        let drop: Vec<std::ops::Range<usize>> =
            s.modules.iter().filter(|m| replaced_names.contains(&m.name)).map(|m| m.span.clone()).collect();
        if drop.is_empty() && s.dropped.is_empty() && !s.edited {
            files.push(UserFile { path: s.path.clone(), filtered: None, generated: false, converted_from: None });
            continue;
        }
        if drop.len() == s.modules.len() && !s.text.contains("`define") {
            continue; // nothing of the user's is left in it
        }
        files.push(UserFile {
            path: s.path.clone(),
            filtered: Some(s.compiled_text(&drop)),
            generated: s.generated,
            converted_from: s.converted_from.clone(),
        });
    }
    files
}

/// The program ROM wired to the KCPSM6 instance `cpu` of module `m`: the one ROM instance of
/// `m` whose `instruction` output is connected to the same net as the CPU's `instruction`
/// input (the course's template wires them so).
fn rom_of(cpu: &Instance, m: &Module, is_rom: impl Fn(&str) -> bool) -> Result<String, String> {
    let net = |i: &Instance| {
        i.connections.iter().find(|(p, _)| p == "instruction").map(|(_, e)| e.split_whitespace().collect::<String>())
    };
    let Some(wire) = net(cpu).filter(|w| !w.is_empty()) else {
        return Err(format!("its `instruction` port is not connected by name in `{}`", m.name));
    };
    let roms: Vec<&Instance> = m
        .instances
        .iter()
        .filter(|i| (is_rom(&i.module) || i.module == "bot_pgm") && net(i).as_ref() == Some(&wire))
        .collect();
    match roms.as_slice() {
        [one] => Ok(one.module.clone()),
        [] => Err(format!("no program ROM instance in `{}` drives its `instruction` net `{wire}`", m.name)),
        _ => Err(format!("several program ROMs in `{}` drive its `instruction` net `{wire}`", m.name)),
    }
}

/// Bits of `outs` that the instance connects to a net (not left open, not a `*unused*` net).
fn connected_mask(inst: &Instance, outs: &[&str]) -> u8 {
    let mut mask = 0u8;
    for (k, out) in outs.iter().enumerate() {
        let wired = |port: &str| {
            inst.connections
                .iter()
                .any(|(p, e)| p == port && !e.trim().is_empty() && !e.to_lowercase().contains("unused"))
        };
        let inverted = match *out {
            "CLKFX" => "CLKFX180".to_string(),
            o if o.starts_with("CLKOUT") || o == "CLKFBOUT" => format!("{o}B"),
            o => o.to_string(),
        };
        if wired(out) || wired(&inverted) {
            mask |= 1 << k;
        }
    }
    mask
}

/// The `.psm` a ROM's INIT strings were assembled from: `<module>.psm` beside the ROM's file,
/// if it assembles to the same words (otherwise a warning says why its lines are not shown).
fn source_beside(rom_file: &Path, module: &str, init: &Image, warnings: &mut Vec<String>) -> Option<PathBuf> {
    let psm = rom_file.with_file_name(format!("{module}.psm"));
    if !psm.is_file() {
        return None;
    }
    match kcpsm6::asm::assemble_file(&psm, &Default::default()) {
        Ok(p) => match first_difference(&p.image, init) {
            None => Some(psm),
            Some(a) => {
                warnings.push(format!(
                    "{} differs from the INIT strings of `{module}` ({}) from address {a:03X}: traces show the ROM's disassembly (assemble it again, or name it with --program)",
                    psm.display(),
                    rom_file.display()
                ));
                None
            }
        },
        Err(e) => {
            warnings.push(format!("{}: not used for the trace of `{module}`: {e}", psm.display()));
            None
        }
    }
}

fn first_difference(a: &Image, b: &Image) -> Option<usize> {
    a.words.iter().zip(b.words.iter()).position(|(x, y)| x != y)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(name: &str, text: &str) -> Source {
        Source::new(name, text)
    }

    fn request() -> Request {
        Request { programs: vec![], bot_firmware: Image::zeroed(), force_own_firmware: false, first_bot: None }
    }

    /// `sources` as the resolver gives them, with `top`.
    fn plan(top: &str, sources: Vec<Source>, req: &Request) -> Result<Plan, BoardError> {
        let design = Design {
            top: top.into(),
            project: None,
            sources,
            include_dirs: vec![],
            notes: vec![],
            generated: vec![],
            placed: None,
        };
        Plan::new(&design, req)
    }

    #[test]
    fn every_bot_in_path_order_up_to_the_most_botsim_simulates() {
        let design = |n: usize| {
            let bots: String = (0..n).map(|k| format!(" bot b{k} (.clk(clk));\n")).collect();
            src("top.v", &format!("module top(input clk, output [15:0] led);\n{bots}endmodule\n"))
        };
        let p = plan("top", vec![design(3)], &request()).unwrap();
        assert_eq!(p.bot_path.as_deref(), Some("b0"));
        let others: Vec<&str> = p.other_bots.iter().map(|b| b.path.as_str()).collect();
        assert_eq!(others, ["b1", "b2"]);
        assert_eq!(p.bots().len(), 3);
        // Each bot's CPU is one the host gives the bot's firmware.
        assert!(p.other_bots.iter().all(|b| p.cpus.iter().any(|c| Some(&c.path) == b.cpu.as_ref())));
        // Another first, by its path with or without the top's name; one that is no bot's, said.
        for name in ["b2", "top.b2"] {
            let p = plan("top", vec![design(3)], &Request { first_bot: Some(name.into()), ..request() }).unwrap();
            assert_eq!(p.bot_path.as_deref(), Some("b2"));
            let others: Vec<&str> = p.other_bots.iter().map(|b| b.path.as_str()).collect();
            assert_eq!(others, ["b0", "b1"]);
        }
        let e = plan("top", vec![design(3)], &Request { first_bot: Some("b7".into()), ..request() }).unwrap_err();
        assert_eq!(e.to_string(), "--bot-at b7: the design's bots are top.b0, top.b1, top.b2");
        let e = plan("top", vec![design(MAX_BOTS + 1)], &request()).unwrap_err().to_string();
        assert!(e.contains(&format!("the design has {} bots (b0, b1", MAX_BOTS + 1)), "{e}");
        assert!(e.ends_with(&format!("botsim simulates up to {MAX_BOTS}")), "{e}");
    }

    #[test]
    fn the_top_the_bot_path_and_the_used_clock_outputs() {
        let top = src(
            "top.v",
            "module nexys4fpga(input clk, input btnCpuReset, output [15:0] led, output [6:0] seg, output dp, output [7:0] an, output [7:0] JA);\n\
             sys s (.clk(clk));\nendmodule\n\
             module sys(input clk);\n wire a, b, fb;\n MMCME2_ADV #(.CLKOUT0_DIVIDE_F(40.0)) m (.CLKOUT0(a), .CLKOUT1(clkout1_unused), .CLKOUT1B(), .CLKFBOUT(fb), .CLKFBIN(fb));\n\
             bot robot (.clk(a), .Loc_Y_reg());\nendmodule\n",
        );
        let p = plan("nexys4fpga", vec![top], &request()).unwrap();
        assert_eq!(p.top, "nexys4fpga");
        assert_eq!(p.bot_path.as_deref(), Some("s.robot"));
        assert!(p.loc_y_reg);
        assert_eq!(p.used_outputs["MMCME2_ADV"], 0b1000_0001);
        assert_eq!(p.unknown_pins, ["JA"]);
        assert!(p.roms.iter().any(|r| r.module == "bot_pgm"));
    }

    #[test]
    fn a_roms_source_is_the_psm_beside_it_when_it_assembles_to_its_init_strings() {
        let dir = tempfile::tempdir().unwrap();
        let psm = dir.path().join("prog.psm");
        let plan_with = |text: &str| {
            std::fs::write(&psm, text).unwrap();
            let p = kcpsm6::asm::assemble_file(&psm, &Default::default()).unwrap();
            // The ROM as the assembler writes it, from the first version of the program.
            let rom_file = dir.path().join("prog.v");
            if !rom_file.exists() {
                let v = kcpsm6::output::verilog_rom(&p.image, "prog", "prog.psm", kcpsm6::asm::RomSize::K1, None);
                std::fs::write(&rom_file, v).unwrap();
            }
            let rom_text = std::fs::read_to_string(&rom_file).unwrap();
            let top = src(
                "top.v",
                "module t(input clk);\n wire [11:0] a; wire [17:0] i; wire e;\n\
                 kcpsm6 cpu (.address(a), .instruction(i), .bram_enable(e), .clk(clk));\n\
                 prog rom (.address(a), .instruction(i), .enable(e), .clk(clk));\n bot b(.clk(clk));\nendmodule\n",
            );
            let rom = Source::new(rom_file, rom_text);
            plan("t", vec![top, rom], &request()).unwrap()
        };
        let p = plan_with("start: LOAD s0, 01\n       JUMP start\n");
        let rom = p.roms.iter().find(|r| r.module == "prog").unwrap();
        assert_eq!(rom.source.as_deref(), Some(psm.as_path()));
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
        // Edited since it was assembled: not the ROM's source, and a warning says so.
        let p = plan_with("start: LOAD s0, 02\n       JUMP start\n");
        assert_eq!(p.roms.iter().find(|r| r.module == "prog").unwrap().source, None);
        assert!(
            p.warnings.iter().any(|w| w.contains("prog.psm differs from the INIT strings of `prog`")),
            "{:?}",
            p.warnings
        );
    }

    #[test]
    fn a_design_without_a_bot_is_the_board_alone() {
        // The team's CPU and ROM, a copy of the course's bot files it does not use.
        let top = src(
            "top.v",
            "module t(input clk, output [15:0] led);\n wire [11:0] a; wire [17:0] i; wire e;\n\
             kcpsm6 cpu (.address(a), .instruction(i), .bram_enable(e), .clk(clk));\n\
             prog rom (.address(a), .instruction(i), .enable(e), .clk(clk));\nendmodule\n",
        );
        let rom = Source::new(
            "prog.v",
            kcpsm6::output::verilog_rom(
                &kcpsm6::asm::assemble_str("start: JUMP start\n").unwrap().image,
                "prog",
                "prog.psm",
                kcpsm6::asm::RomSize::K1,
                None,
            ),
        );
        let unused = src("world_if.v", "module world_if(input clk);\nendmodule\n");
        let p = plan("t", vec![top, rom, unused], &request()).unwrap();
        assert_eq!(p.bot_path, None);
        assert_eq!(p.cpus.iter().map(|c| c.path.as_str()).collect::<Vec<_>>(), ["cpu"]);
        assert_eq!(p.roms.iter().map(|r| r.module.as_str()).collect::<Vec<_>>(), ["prog"]);
        // Nothing of the bot is said to be replaced; the KCPSM6 the repository lacks is said.
        let said: Vec<(&str, &str)> = p.replaced.iter().map(|r| (r.module.as_str(), r.with.as_str())).collect();
        assert!(said.iter().all(|(m, _)| ["prog", "kcpsm6"].contains(m)), "{said:?}");
        assert!(said.contains(&("kcpsm6", "botsim's kcpsm6 (the repository has none)")), "{said:?}");
    }

    #[test]
    fn a_teams_bot_and_world_if_with_ports_botsims_lack_are_kept_and_the_bot_is_traced_at_its_ports() {
        // A BotSim 3.1-shaped bot: `bot` with Bot_Config_reg, and inside it a `world_if` with
        // a configuration port (the team's, not the course's), a kcpsm6 and its ROM.
        let top = src(
            "top.v",
            "module t(input clk, input [7:0] sw);\n  bot b (.clk(clk), .Bot_Config_reg(sw));\nendmodule\n",
        );
        let bot = src(
            "bot31.v",
            "module bot(input [7:0] MotCtl_in, output [7:0] LocX_reg, output [7:0] LocY_reg, output [7:0] Sensors_reg,\n  output [7:0] BotInfo_reg, output upd_sysregs, input clk, input reset, input [7:0] Bot_Config_reg);\n  kcpsm6 cpu (.address(a), .instruction(i), .bram_enable(e), .clk(clk));\n  prog rom (.address(a), .instruction(i), .enable(e), .clk(clk));\n  world_if wif (.BotConfig(Bot_Config_reg), .clk(clk));\nendmodule\n",
        );
        let wif = src("world_if.v", "module world_if(input [7:0] BotConfig, input clk);\nendmodule\n");
        let image = kcpsm6::asm::assemble_str("start: JUMP start\n").unwrap().image;
        let rom =
            src("prog.v", &kcpsm6::output::verilog_rom(&image, "prog", "prog.psm", kcpsm6::asm::RomSize::K1, None));
        let p = plan("t", vec![top, bot, wif, rom], &request()).unwrap();
        assert_eq!(p.kept.iter().map(String::as_str).collect::<Vec<_>>(), ["bot", "world_if"]);
        assert_eq!(p.bot_path.as_deref(), Some("b"));
        assert_eq!(p.bot_cpu.as_deref(), Some("b.cpu"));
        let team = p.team_bot.as_ref().unwrap();
        assert_eq!(
            (team.module.as_str(), team.locy.as_str(), team.config.as_deref()),
            ("bot", "LocY_reg", Some("Bot_Config_reg"))
        );
        assert_eq!(p.own_bot(), None);
        // Neither is said to be replaced, nor blanked from its file; kcpsm6 is botsim's.
        let said: Vec<&str> = p.replaced.iter().map(|r| r.module.as_str()).collect();
        assert!(!said.contains(&"bot") && !said.contains(&"world_if") && said.contains(&"kcpsm6"), "{said:?}");
        assert!(p.files.iter().any(|f| f.path.ends_with("world_if.v") && f.filtered.is_none()));
        assert!(!p.roms.iter().any(|r| r.module == "bot_pgm"), "no 2.0 firmware for a team's bot");
    }

    #[test]
    fn a_wrong_pin_direction_is_a_warning_at_the_port_and_the_port_on_no_pin() {
        let top = src("top.v", "module t(input clk,\n  input [15:0] led);\n bot b(.clk(clk));\nendmodule\n");
        let p = plan("t", vec![top], &request()).unwrap();
        assert!(
            p.warnings.iter().any(|w| w.starts_with("top.v:2:16: port `led` is the board's LED pin, an output")
                && w.contains("the design drives nothing to the LED pin, and reads `led` as 0")),
            "{:?}",
            p.warnings
        );
        assert!(p.unknown_pins.contains(&"led".to_string()) && !p.pins.iter().any(|(n, _)| n == "led"));
        // The clock has no such leniency: without it nothing runs.
        let top = src("top.v", "module t(output clk);\n bot b(.clk(clk));\nendmodule\n");
        let e = plan("t", vec![top], &request()).unwrap_err().to_string();
        assert!(e.starts_with("top.v:1:8: port `clk` is the board's clock pin, an input"), "{e}");
    }
}
