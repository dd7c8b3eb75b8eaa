//! Finding the design in a repository the way the vendor tool does, before anything is built.
//!
//! 1. **Where the design is**: a project file (`.xpr`, `.xise`: [`super::project`]) named on
//!    the command line or found in the folder, else the folder itself. A folder with several
//!    projects uses the one whose design has a `bot`, or asks which.
//! 2. **The top**: `--top`, the project's, or the one module with a board clock pin that
//!    reaches a `bot` and that no other such module instantiates.
//! 3. **Only what the top reaches**: from the top down, each module gets one definition;
//!    files and modules never reached are not compiled, so release templates, stale copies
//!    and testbenches beside the design cannot break it. Where a reached module has
//!    different definitions, the one taken is said: the one `--file` names, the project's,
//!    the one beside the module that instantiates it, the nearest, the newest (last
//!    committed), and a simulation netlist or a black box last.
//! 4. **What nobody committed**: a core from its configuration (Clocking Wizard, memory
//!    cores: [`super::ip`], [`super::memcore`]), a memory core from its wrapper's parameters,
//!    the course's `debounce`/`sevensegment`/`dtg` ([`super::course`]), an entity that only
//!    exists as VHDL (GHDL: [`super::vhdl`]), `--clock` and `--stub` modules; and whatever
//!    is still missing is one error listing every instance.
//! 5. **Vivado's leniency**: literals with more digits than their width are truncated as
//!    Vivado does, each said with its file:line:col.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::{Path, PathBuf};

use super::coe_match::{self, Offer, Shape};
use super::commas;
use super::constraints::{self, ConstraintFile, Placed};
use super::course;
use super::flops;
use super::ip::{ClockCore, ClockSpec, IpConfig, CLOCK_CORES};
use super::memcore::{self, library_model, parse_coe, Coe, MemCore, MEMORY_CORES};
use super::parts::{self, foreign_port, is_program_rom, Replacement, HELPERS, OWN_MODULES, PRIMITIVES};
use super::pins::{self, Role};
use super::project::Project;
use super::repo::{common_depth, tidy, Ages, FileKind, Repo};
use super::scan::{self, Instance, Module};
use super::source::Source;
use super::vhdl;
use super::BoardError;

/// What the command line says about finding the design.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// `--top`.
    pub top: Option<String>,
    /// `--file`: files whose definitions win over other copies of the same modules.
    pub prefer: Vec<PathBuf>,
    /// `--exclude`: files or folders left out.
    pub exclude: Vec<PathBuf>,
    /// `--clock`: outputs of clock modules the design has no configuration for.
    pub clocks: Vec<ClockSpec>,
    /// `--stub`: modules tied off.
    pub stubs: Vec<String>,
    /// `--include`: more include folders.
    pub include_dirs: Vec<PathBuf>,
    /// `--memory MODULE=FILE`: the `.coe` that holds a memory core's contents, for a core
    /// committed without its configuration under another name than the module's.
    pub memories: Vec<(String, PathBuf)>,
}

/// The design as the build takes it.
#[derive(Clone, Debug)]
pub struct Design {
    pub top: String,
    /// The project file it comes from, if any.
    pub project: Option<PathBuf>,
    /// What the build compiles: the reached modules' files (the rest of each blanked out)
    /// and what botsim generated for the design.
    pub sources: Vec<Source>,
    pub include_dirs: Vec<PathBuf>,
    /// Every decision, one line each.
    pub notes: Vec<String>,
    /// What botsim made for the design, for the report.
    pub generated: Vec<Replacement>,
    /// Where the team's constraint file places the top's ports, if one does.
    pub placed: Option<Placed>,
}

/// Does an instance connect a block memory core's ports as the Block Memory Generator names
/// them (`clka`, `addra`, and `douta` or `dina`: a simple dual-port RAM reads on port B)?
fn looks_like_memory_core(connected: &[&str]) -> bool {
    let has = |p: &str| connected.iter().any(|c| c.eq_ignore_ascii_case(p));
    has("clka") && has("addra") && (has("douta") || has("dina"))
}

/// The ports of BotSim 2.0's `bot` (rtl/bot.v): a `bot` instance that connects another is
/// not BotSim 2.0's.
fn botsim20_ports() -> Vec<String> {
    let bot = scan::scan(include_str!("../../../rtl/bot.v"));
    bot.iter().find(|m| m.name == "bot").map(|m| m.ports.iter().map(|p| p.name.clone()).collect()).unwrap_or_default()
}

/// Find the design named by `inputs` (folders, files, a project file).
pub fn resolve(inputs: &[PathBuf], opts: &Options) -> Result<Design, BoardError> {
    let mut explicit_files = Vec::new();
    let mut folders = Vec::new();
    let mut named_projects = Vec::new();
    for input in inputs {
        let meta = std::fs::metadata(input).map_err(|e| BoardError::at(input, 0, 0, format!("cannot read: {e}")))?;
        if meta.is_dir() {
            folders.push(input.clone());
        } else if FileKind::of(input) == FileKind::Project {
            named_projects.push(input.clone());
        } else {
            explicit_files.push(input.clone());
        }
    }
    // The repository: the folders named, or the one holding a named project (its git
    // work tree, else the project's folder), plus files named one by one.
    let mut roots = folders.clone();
    for p in &named_projects {
        roots.push(repository_root(p));
    }
    let mut repo = Repo::walk(&roots)?;
    for f in &explicit_files {
        repo.add(f.clone());
    }
    for p in &named_projects {
        for f in Project::read(p)?.files.into_iter().filter(|f| f.is_file()) {
            repo.add(f);
        }
    }
    for f in &opts.prefer {
        repo.add(f.clone());
    }
    let pool = Pool::new(&repo, opts)?;

    let projects: Vec<PathBuf> = if !named_projects.is_empty() {
        named_projects.clone()
    } else if explicit_files.is_empty() {
        repo.projects.clone()
    } else {
        Vec::new()
    };
    if projects.is_empty() {
        return pool.design(None, opts, &repo);
    }
    if projects.len() == 1 {
        let project = Project::read(&projects[0])?;
        let design = pool.design(Some(&project), opts, &repo);
        let forced = !named_projects.is_empty() || opts.top.is_some();
        return match design {
            Ok(d) if forced || pool.reaches_bot(&d.top) => Ok(d),
            // A project whose design has no bot beside a folder whose design has one (a first
            // project beside the Rojobot's): the folder; else the project (a final project).
            Ok(d) => match pool.design(None, opts, &repo) {
                Ok(mut folder) if pool.reaches_bot(&folder.top) => {
                    folder.notes.insert(
                        0,
                        format!(
                            "{}: its design (top `{}`) has no `bot`; using the folder's design, which has one",
                            projects[0].display(),
                            d.top
                        ),
                    );
                    Ok(folder)
                }
                _ => Ok(d),
            },
            Err(e) if forced => Err(e),
            Err(e) => pool.design(None, opts, &repo).map_err(|_| e),
        };
    }
    // Several projects: the one whose design has a bot, or the user's choice.
    let mut with_bot = Vec::new();
    let mut failed: Vec<BoardError> = Vec::new();
    for p in &projects {
        let design = Project::read(p).and_then(|project| pool.design(Some(&project), opts, &repo));
        match design {
            Ok(d) if pool.reaches_bot(&d.top) => with_bot.push(d),
            Ok(_) => {}
            Err(e) => failed.push(e),
        }
    }
    let list = projects.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ");
    match with_bot.len() {
        1 if named_projects.is_empty() => {
            let mut d = with_bot.remove(0);
            let chosen = d.project.clone().unwrap_or_default();
            d.notes.insert(
                0,
                format!(
                    "several projects here ({list}); using {}, the one with a `bot` (name another to run it)",
                    chosen.display()
                ),
            );
            Ok(d)
        }
        // None runs with a bot, and one does not build: what stops it, which is likelier the
        // user's than a project that runs without the bot.
        0 if !failed.is_empty() => {
            let more = match failed.len() {
                1 => String::new(),
                n => format!("; {} more do not build", n - 1),
            };
            let mut e = failed.remove(0);
            e.message = format!("{} (of the projects here: {list}{more})", e.message);
            Err(e)
        }
        _ => Err(BoardError::plain(format!(
            "several projects here: {list}; name the one to run (botsim board {})",
            projects[0].display()
        ))),
    }
}

/// The folder a project's repository starts at: its git work tree, else the project's
/// folder; written from the project's path (`proj2/..` is `.`).
fn repository_root(project: &Path) -> PathBuf {
    let dir = project.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new(".")).to_path_buf();
    let mut up = dir.clone();
    for _ in 0..64 {
        if up.join(".git").exists() {
            return tidy(&up);
        }
        if std::fs::canonicalize(&up).map_or(true, |c| c.parent().is_none()) {
            break;
        }
        up = up.join("..");
    }
    tidy(&dir)
}

/// One definition of a module: source and module index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Def {
    src: usize,
    module: usize,
}

/// Every Verilog file of the repository, scanned, and every IP configuration, by name.
struct Pool {
    sources: Vec<Source>,
    defs: BTreeMap<String, Vec<Def>>,
    ips: BTreeMap<String, Vec<Result<IpConfig, BoardError>>>,
    /// VHDL entities by lower-case name: (file, entity as written).
    entities: BTreeMap<String, Vec<(PathBuf, String)>>,
    ages: std::cell::OnceCell<Ages>,
    root: PathBuf,
    /// The repository's constraint files and what each places.
    constraints: Vec<ConstraintFile>,
}

/// Generated artefacts Vivado leaves beside a core (board.md §6): a simulation netlist is
/// taken only when nothing else defines the module.
fn is_netlist(path: &Path) -> bool {
    let name = path.file_name().map(|n| n.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    name.ends_with("_sim_netlist.v") || name.ends_with("_funcsim.v") || name.ends_with("_stub.v")
}

impl Pool {
    fn new(repo: &Repo, opts: &Options) -> Result<Pool, BoardError> {
        let excluded = |p: &Path| {
            let p = std::path::absolute(p).unwrap_or(p.to_path_buf());
            opts.exclude.iter().any(|x| p.starts_with(std::path::absolute(x).unwrap_or(x.clone())))
        };
        let mut sources = Vec::new();
        let mut defs: BTreeMap<String, Vec<Def>> = BTreeMap::new();
        for f in repo.hdl.iter().filter(|f| !excluded(f)) {
            let s = Source::read(f)?;
            for (k, m) in s.modules.iter().enumerate() {
                defs.entry(m.name.clone()).or_default().push(Def { src: sources.len(), module: k });
            }
            sources.push(s);
        }
        let mut ips: BTreeMap<String, Vec<Result<IpConfig, BoardError>>> = BTreeMap::new();
        for f in repo.ip.iter().filter(|f| !excluded(f)) {
            let ip = IpConfig::read(f);
            let name = match &ip {
                Ok(ip) => ip.name.clone(),
                Err(_) => f.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            };
            ips.entry(name).or_default().push(ip);
        }
        let mut entities: BTreeMap<String, Vec<(PathBuf, String)>> = BTreeMap::new();
        for f in repo.vhdl.iter().filter(|f| !excluded(f)) {
            let text = String::from_utf8_lossy(&std::fs::read(f).unwrap_or_default()).into_owned();
            for (e, _) in vhdl::entities(&text) {
                entities.entry(e.to_ascii_lowercase()).or_default().push((f.clone(), e));
            }
        }
        let root = repo.roots.first().cloned().unwrap_or_else(|| PathBuf::from("."));
        let constraints = constraints::read_all(&repo.constraints);
        Ok(Pool { sources, defs, ips, entities, ages: std::cell::OnceCell::new(), root, constraints })
    }

    fn module(&self, d: Def) -> &Module {
        &self.sources[d.src].modules[d.module]
    }

    fn path(&self, d: Def) -> &Path {
        &self.sources[d.src].path
    }

    fn at(&self, d: Def) -> String {
        format!("{}:{}", self.path(d).display(), self.module(d).line)
    }

    /// The error for a definition with no `endmodule` (a file cut short), if `d` is one:
    /// nothing else said of the design can be trusted while it stands.
    fn unterminated(&self, d: Def) -> Result<(), BoardError> {
        let m = self.module(d);
        if let Some((line, col, what)) = &m.unreadable {
            return Err(BoardError::at(self.path(d), *line, *col, what.clone()));
        }
        if !m.unterminated {
            return Ok(());
        }
        Err(BoardError::at(
            self.path(d),
            m.line,
            m.col,
            format!(
                "the module `{}` does not end (no `endmodule`): the file was cut short? (--exclude it if it is not the design's)",
                m.name
            ),
        ))
    }

    /// The definitions of `name`, but for black boxes in Vivado's synthesis stubs
    /// (`<ip>_stub.v`: the core's ports and nothing else).
    fn definitions(&self, name: &str) -> Vec<Def> {
        let stub = |d: &Def| {
            self.module(*d).empty && self.path(*d).to_string_lossy().to_ascii_lowercase().ends_with("_stub.v")
        };
        self.defs.get(name).map(|v| v.iter().copied().filter(|d| !stub(d)).collect()).unwrap_or_default()
    }

    /// Does the definition `d` reach a `bot` instance?
    fn def_reaches_bot(&self, d: Def) -> bool {
        self.module(d).instances.iter().any(|i| self.reaches_bot(&i.module))
    }

    /// Where the repository's constraint file that places the most of the ports of `d`
    /// places them, if one does.
    fn placed(&self, d: Def) -> Option<Placed> {
        Placed::choose(&self.constraints, self.module(d), self.path(d))
    }

    /// Does any definition of `name` reach a bot (a `bot` instance, or a module with the bot's
    /// ports)?
    fn reaches_bot(&self, name: &str) -> bool {
        let mut seen = BTreeSet::new();
        let mut stack = vec![name.to_string()];
        while let Some(n) = stack.pop() {
            if n == "bot" || self.definitions(&n).iter().any(|d| parts::is_bot(self.module(*d))) {
                return true;
            }
            if !seen.insert(n.clone()) {
                continue;
            }
            for d in self.definitions(&n) {
                stack.extend(self.module(d).instances.iter().map(|i| i.module.clone()));
            }
        }
        false
    }

    /// The refusal of a design of the MIPSfpga era (board.md §8) that `top` reaches: the
    /// Rojobot 3.1 IP, its application CPU a MIPS microAptiv core. botsim runs neither yet;
    /// one line names both where they are, before anything else is said of the design.
    fn mips_era(&self, top: &str) -> Option<BoardError> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![top.to_string()];
        let (mut ip, mut mips) = (None, None);
        while let Some(n) = stack.pop() {
            if !seen.insert(n.clone()) {
                continue;
            }
            for d in self.definitions(&n) {
                for inst in &self.module(d).instances {
                    if ip.is_none() && is_rojobot31_ip(inst) {
                        ip = Some((d, inst.clone()));
                    }
                    if mips.is_none() && inst.module == MIPS_CORE {
                        mips = Some(format!("{}:{}:{}", self.path(d).display(), inst.line, inst.col));
                    }
                    stack.push(inst.module.clone());
                }
            }
        }
        let (d, inst) = ip?;
        let core = match mips {
            Some(at) => format!("its MIPS microAptiv core (`{MIPS_CORE}`, {at})"),
            None => "the MIPS microAptiv SoC of that era".to_string(),
        };
        Some(BoardError::at(
            self.path(d),
            inst.line,
            inst.col,
            format!(
                "`{}` (instance `{}`) is the Rojobot 3.1 IP (rojobot31) of the MIPSfpga era, driven by {core}: \
                 botsim does not run Rojobot 3.1 with a MIPS SoC yet (it runs BotSim 2.0 and PicoBlaze designs)",
                inst.module, inst.name
            ),
        ))
    }

    fn ages(&self) -> &Ages {
        self.ages.get_or_init(|| Ages::of(&self.root))
    }

    /// The top: `--top`, the project's, or the one board module that reaches a bot and
    /// that no other one instantiates.
    fn top(&self, opts: &Options, project: Option<&Project>) -> Result<String, BoardError> {
        if let Some(t) = &opts.top {
            return if self.definitions(t).is_empty() {
                Err(BoardError::plain(format!("--top {t}: no module of that name in the sources")))
            } else {
                Ok(t.clone())
            };
        }
        if let Some(p) = project {
            if let Some(t) = &p.top {
                return if self.definitions(t).is_empty() {
                    // ISE and VHDL tops are written in any case.
                    match self.defs.keys().find(|k| k.eq_ignore_ascii_case(t) && !self.definitions(k).is_empty()) {
                        Some(k) => Ok(k.clone()),
                        None => Err(BoardError::at(
                            &p.path,
                            0,
                            0,
                            format!("its top module `{t}` is defined in no Verilog file of the repository"),
                        )),
                    }
                } else {
                    Ok(t.clone())
                };
            }
        }
        let own = |n: &str| OWN_MODULES.iter().any(|(m, _)| *m == n) || PRIMITIVES.iter().any(|(m, _)| *m == n);
        let boards: BTreeSet<&str> = self
            .defs
            .keys()
            .filter(|n| !own(n))
            .filter(|n| {
                self.definitions(n).iter().any(|d| {
                    let m = self.module(*d);
                    !is_program_rom(m)
                        && (m.ports.iter().any(|p| pins::role(&p.name) == Some(Role::Clock))
                            || self.placed(*d).is_some_and(|p| {
                                p.ports.keys().any(|port| p.role(port, 0, 1) == Some(Some(Role::Clock)))
                            }))
                })
            })
            .map(String::as_str)
            .collect();
        let with_bot: BTreeSet<&str> = boards.iter().copied().filter(|n| self.reaches_bot(n)).collect();
        let pick = |set: &BTreeSet<&str>| -> Vec<String> {
            // Not instantiated by another module of the set (a testbench, which has no
            // board pins, does not count).
            set.iter()
                .filter(|n| {
                    !set.iter().any(|other| {
                        other != *n
                            && self
                                .definitions(other)
                                .iter()
                                .any(|d| self.module(*d).instances.iter().any(|i| i.module == **n))
                    })
                })
                .map(|n| n.to_string())
                .collect()
        };
        // A design of the MIPSfpga era is said as such, whatever else could be its top.
        if let Some(e) = pick(&boards).iter().find_map(|n| self.mips_era(n)) {
            return Err(e);
        }
        let mut candidates = pick(&with_bot);
        if candidates.is_empty() {
            candidates = pick(&boards);
        }
        // A top cut short may be why there are several, or none with the bot.
        for n in pick(&boards) {
            for d in self.definitions(&n) {
                self.unterminated(d)?;
            }
        }
        match candidates.as_slice() {
            [one] => Ok(one.clone()),
            [] => Err(BoardError::plain(
                "cannot find the top module: no module has a board clock pin (clk, clk100, CLK100MHZ); name it with --top",
            )),
            many => {
                let list: Vec<String> = many
                    .iter()
                    .map(|n| format!("`{n}` ({})", self.definitions(n).first().map(|d| self.at(*d)).unwrap_or_default()))
                    .collect();
                Err(BoardError::plain(format!("several modules could be the top: {}; name one with --top", list.join(", "))))
            }
        }
    }

    /// The definition of `name` to use, from `defs`, and the note that says why when there
    /// was a choice; an error naming them when nothing decides (no file date does: in a
    /// downloaded archive every file has the same, and a backup copy written last would
    /// win). `parent`: the file of the module that instantiates it.
    fn choose(
        &self,
        name: &str,
        defs: &[Def],
        parent: Option<&Path>,
        listed: &BTreeSet<PathBuf>,
        opts: &Options,
    ) -> Result<(Def, Option<String>), BoardError> {
        if defs.len() == 1 {
            return Ok((defs[0], None));
        }
        // Copies that differ in nothing but comments and layout are one definition.
        let text = |d: Def| scan::normalized(&self.sources[d.src].text, self.module(d).span.clone());
        let first = text(defs[0]);
        if defs[1..].iter().all(|d| text(*d) == first) {
            return Ok((self.order_by_age(defs)[0], None));
        }
        let canon = |p: &Path| std::fs::canonicalize(p).unwrap_or(p.to_path_buf());
        let mut cands = defs.to_vec();
        let mut why = String::new();
        let narrow = |cands: &mut Vec<Def>, keep: &dyn Fn(Def) -> bool, reason: String, why: &mut String| {
            let kept: Vec<Def> = cands.iter().copied().filter(|d| keep(*d)).collect();
            if !kept.is_empty() && kept.len() < cands.len() {
                *cands = kept;
                if why.is_empty() {
                    *why = reason;
                }
            }
        };
        let preferred: Vec<PathBuf> = opts.prefer.iter().map(|p| canon(p)).collect();
        narrow(&mut cands, &|d| preferred.contains(&canon(self.path(d))), "the one --file names".into(), &mut why);
        narrow(&mut cands, &|d| listed.contains(&canon(self.path(d))), "the project's".into(), &mut why);
        narrow(&mut cands, &|d| !is_netlist(self.path(d)), "not a simulation netlist".into(), &mut why);
        if let Some(parent) = parent {
            let dir = parent.parent().unwrap_or(Path::new("."));
            let depth = |d: Def| common_depth(&canon(self.path(d)), &canon(dir));
            let best = cands.iter().map(|d| depth(*d)).max().unwrap_or(0);
            narrow(
                &mut cands,
                &|d| self.path(d).parent() == Some(dir),
                format!("beside {}, which instantiates it", parent.display()),
                &mut why,
            );
            narrow(&mut cands, &|d| depth(d) == best, format!("the nearest to {}", parent.display()), &mut why);
        }
        let ordered = self.order_by_age(&cands);
        let taken = ordered[0];
        if cands.len() > 1 {
            // Git's history decides when it tells the last committed; nothing else does.
            let ages = self.ages();
            let times: Vec<Option<i64>> = ordered.iter().map(|d| ages.committed(self.path(*d))).collect();
            let newest =
                times[0].filter(|t| times.iter().all(|o| o.is_some()) && times[1..].iter().all(|o| *o < Some(*t)));
            if newest.is_none() {
                let all: Vec<String> = cands.iter().map(|d| self.at(*d)).collect();
                let nothing = if times.iter().any(Option::is_none) {
                    "no project lists one, none is beside the module that instantiates it, and there is no git history to tell the last committed"
                } else {
                    "no project lists one, none is beside the module that instantiates it, and git committed them together"
                };
                return Err(BoardError::plain(format!(
                    "`{name}` has {} different definitions and nothing tells which the design uses ({nothing}): {}; name one with --file FILE (or --exclude the others)",
                    cands.len(),
                    all.join(", ")
                )));
            }
            why = "the last committed".into();
        }
        let others: Vec<String> = defs.iter().filter(|d| **d != taken).map(|d| self.at(*d)).collect();
        let note = format!(
            "`{name}` has {} different definitions: took {} ({why}) over {} (--file or --exclude chooses another)",
            defs.len(),
            self.at(taken),
            others.join(", ")
        );
        Ok((taken, Some(note)))
    }

    /// Newest first (last committed, else modified), then nearest the root, then by path.
    fn order_by_age(&self, defs: &[Def]) -> Vec<Def> {
        let mut v = defs.to_vec();
        let ages = self.ages();
        v.sort_by_key(|d| {
            let p = self.path(*d);
            (std::cmp::Reverse(ages.of_file(p)), p.components().count(), p.to_path_buf())
        });
        v
    }

    /// The design from the top down.
    fn design(&self, project: Option<&Project>, opts: &Options, repo: &Repo) -> Result<Design, BoardError> {
        let mut notes = Vec::new();
        // The project's files, found by name when they are listed with another machine's
        // paths.
        let mut listed = BTreeSet::new();
        if let Some(p) = project {
            for f in &p.files {
                if f.exists() {
                    listed.insert(std::fs::canonicalize(f).unwrap_or(f.clone()));
                    continue;
                }
                let name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                match repo.find_near(&name, p.path.parent().unwrap_or(Path::new("."))) {
                    Some(found) => {
                        notes.push(format!(
                            "{}: lists {}, which is not here; using {}",
                            p.path.display(),
                            f.display(),
                            found.display()
                        ));
                        listed.insert(std::fs::canonicalize(&found).unwrap_or(found));
                    }
                    None if matches!(FileKind::of(f), FileKind::Hdl | FileKind::Ip | FileKind::Vhdl) => notes
                        .push(format!("{}: lists {}, which is not in the repository", p.path.display(), f.display())),
                    None => {}
                }
            }
        }
        let top = self.top(opts, project)?;
        if let Some(e) = self.mips_era(&top) {
            return Err(e);
        }
        let mut walk = Walk::new(self, opts, repo, &listed);
        walk.run(&top)?;
        notes.append(&mut walk.notes);
        let mut design = walk.finish(top, project.map(|p| p.path.clone()))?;
        notes.append(&mut design.notes);
        design.notes = notes;
        Ok(design)
    }
}

/// What stands for a reached module.
#[derive(Clone, Debug)]
enum Choice {
    /// The user's definition.
    User(Def),
    /// Botsim's own module or a primitive model.
    Own,
    /// Verilog botsim generated (a core, a stand-in, a stub), with its report line (none for
    /// a program ROM assembled from its `.psm`: the plan reports ROMs).
    Generated(Source, Option<Replacement>),
}

/// A module nobody defines, where it is instantiated.
struct Missing {
    module: String,
    instance: String,
    parent: String,
    at: String,
    hint: String,
    /// The option that gets past it (`--stub NAME`, `--clock NAME.PORT=FREQ ...`), if one does.
    step: Option<String>,
}

struct Walk<'a> {
    pool: &'a Pool,
    opts: &'a Options,
    repo: &'a Repo,
    listed: &'a BTreeSet<PathBuf>,
    chosen: BTreeMap<String, Choice>,
    order: Vec<String>,
    missing: Vec<Missing>,
    notes: Vec<String>,
    /// Every instance of a stubbed or `--clock` module, for their ports.
    instances: BTreeMap<String, Vec<Instance>>,
    /// A choice that cannot be made (two definitions nothing orders): ends the walk.
    error: Option<BoardError>,
    /// The repository's `.coe` files that read, once a core needs them.
    coes: Option<Vec<(PathBuf, Coe)>>,
}

impl<'a> Walk<'a> {
    fn new(pool: &'a Pool, opts: &'a Options, repo: &'a Repo, listed: &'a BTreeSet<PathBuf>) -> Walk<'a> {
        Walk {
            pool,
            opts,
            repo,
            listed,
            chosen: BTreeMap::new(),
            order: Vec::new(),
            missing: Vec::new(),
            notes: Vec::new(),
            instances: BTreeMap::new(),
            error: None,
            coes: None,
        }
    }

    fn run(&mut self, top: &str) -> Result<(), BoardError> {
        let defs = self.pool.definitions(top);
        // Two definitions of the top (Project 1's and Project 2's): the one whose design has
        // the bot.
        let mut defs = defs;
        if defs.len() > 1 {
            let with_bot: Vec<Def> = defs.iter().copied().filter(|d| self.pool.def_reaches_bot(*d)).collect();
            if !with_bot.is_empty() && with_bot.len() < defs.len() {
                let others: Vec<String> =
                    defs.iter().filter(|d| !with_bot.contains(d)).map(|d| self.pool.at(*d)).collect();
                if let [one] = with_bot[..] {
                    self.notes.push(format!(
                        "the top `{top}` has {} definitions: took {}, whose design has the bot, over {}",
                        defs.len(),
                        self.pool.at(one),
                        others.join(", ")
                    ));
                }
                defs = with_bot;
            }
        }
        let (d, note) = self.pool.choose(top, &defs, None, self.listed, self.opts)?;
        self.pool.unterminated(d)?;
        self.notes.extend(note);
        self.chosen.insert(top.to_string(), Choice::User(d));
        self.order.push(top.to_string());
        let mut queue: VecDeque<(String, Def)> = VecDeque::from([(top.to_string(), d)]);
        let bot_ports = botsim20_ports();
        while let Some((_, def)) = queue.pop_front() {
            let m = self.pool.module(def).clone();
            let file = self.pool.path(def).to_path_buf();
            if is_program_rom(&m) {
                continue; // replaced by a behavioural ROM: what it instantiates is not needed
            }
            for inst in &m.instances {
                // A `bot` the team defines with ports BotSim 2.0's lacks is the team's own (a
                // BotSim 3.1 bot), simulated as committed; any other is botsim's.
                let team_bot = inst.module == "bot" && self.is_team_own("bot", &file);
                if inst.module == "bot" && !team_bot {
                    if let Some((port, _)) =
                        inst.connections.iter().find(|(p, _)| !p.starts_with('#') && !bot_ports.contains(p))
                    {
                        return Err(BoardError::at(
                            &file,
                            inst.line,
                            inst.col,
                            format!(
                                "this `bot` has a port `{port}` that BotSim 2.0's bot does not have (a later BotSim?); botsim simulates BotSim 2.0 (ports: {})",
                                bot_ports.join(", ")
                            ),
                        ));
                    }
                }
                if self.opts.stubs.contains(&inst.module) || self.clock_specs(&inst.module, &inst.name).is_some() {
                    self.instances.entry(inst.module.clone()).or_default().push(inst.clone());
                }
                if self.chosen.contains_key(&inst.module) {
                    continue;
                }
                let chosen = self.choose_for(inst, &m, &file);
                if let Some(e) = self.error.take() {
                    return Err(e);
                }
                if let Some(child) = chosen {
                    if let Choice::User(d) = &child {
                        self.pool.unterminated(*d)?;
                    }
                    // botsim's own modules replace the user's copies (the course's): not walked
                    // into. A team's module of the same name with other ports is walked.
                    let own = OWN_MODULES.iter().any(|(o, _)| *o == inst.module)
                        && !matches!(&child, Choice::User(d) if foreign_port(self.pool.module(*d)).is_some());
                    if let (Choice::User(d), false) = (&child, own) {
                        queue.push_back((inst.module.clone(), *d));
                    }
                    self.chosen.insert(inst.module.clone(), child);
                    self.order.push(inst.module.clone());
                }
                if inst.module == "bot" && !team_bot && !self.chosen.contains_key("bot_pgm") {
                    // botsim's bot runs the user's bot_pgm, if there is one.
                    let defs = self.pool.definitions("bot_pgm");
                    if !defs.is_empty() {
                        let (d, note) = self.pool.choose("bot_pgm", &defs, Some(&file), self.listed, self.opts)?;
                        self.notes.extend(note);
                        self.chosen.insert("bot_pgm".into(), Choice::User(d));
                        self.order.push("bot_pgm".into());
                    }
                }
            }
        }
        Ok(())
    }

    /// Is the module `name` (one of botsim's own names), as it would be chosen for an instance
    /// in `file`, the team's own ([`foreign_port`])?
    fn is_team_own(&self, name: &str, file: &Path) -> bool {
        if let Some(Choice::User(d)) = self.chosen.get(name) {
            return foreign_port(self.pool.module(*d)).is_some();
        }
        let defs = self.pool.definitions(name);
        if defs.is_empty() {
            return false;
        }
        match self.pool.choose(name, &defs, Some(file), self.listed, self.opts) {
            Ok((d, _)) => foreign_port(self.pool.module(d)).is_some(),
            Err(_) => false,
        }
    }

    fn clock_specs(&self, module: &str, instance: &str) -> Option<Vec<&'a ClockSpec>> {
        let v: Vec<&ClockSpec> =
            self.opts.clocks.iter().filter(|c| c.target == module || c.target == instance).collect();
        (!v.is_empty()).then_some(v)
    }

    /// What stands for the module `inst` instantiates (first met in `scope`, in `file`);
    /// `None` when it is missing (recorded) or made at the end (stubs, `--clock`).
    fn choose_for(&mut self, inst: &Instance, scope: &Module, file: &Path) -> Option<Choice> {
        let name = inst.module.as_str();
        let parent = scope.name.as_str();
        let pool = self.pool;
        if OWN_MODULES.iter().any(|(m, _)| *m == name) {
            // The user's copy is reported as replaced (and blanked by the plan).
            let defs = pool.definitions(name);
            return Some(if defs.is_empty() {
                Choice::Own
            } else {
                let d = match pool.choose(name, &defs, Some(file), self.listed, self.opts) {
                    Ok((d, _)) => d,
                    Err(e) => {
                        self.error.get_or_insert(e);
                        return None;
                    }
                };
                Choice::User(d)
            });
        }
        if PRIMITIVES.iter().any(|(m, _)| *m == name) || HELPERS.contains(&name) {
            return Some(Choice::Own);
        }
        if self.opts.stubs.iter().any(|s| s == name) || self.clock_specs(name, &inst.name).is_some() {
            return None; // made once every instance is known
        }
        // The user's Verilog (simulation netlists only when nothing else defines it).
        let defs = pool.definitions(name);
        let real: Vec<Def> = defs.iter().copied().filter(|d| !is_netlist(pool.path(*d))).collect();
        if !real.is_empty() {
            return Some(self.user(name, &real, file));
        }
        // A core from its configuration.
        if let Some(c) = self.configured(name, file) {
            return Some(c);
        }
        if !defs.is_empty() {
            return Some(self.user(name, &defs, file));
        }
        // A memory core committed as its contents alone (`<name>.coe`, or --memory's file).
        if let Some(c) = self.coe_core(inst, scope, file) {
            return c;
        }
        // A program ROM whose Verilog was never committed, only its program: assembled here.
        let connects = |p: &str| inst.connections.iter().any(|(c, _)| c == p);
        if connects("instruction") && connects("address") {
            let dir = file.parent().unwrap_or(Path::new("."));
            if let Some(psm) = self.repo.find_near(&format!("{name}.psm"), dir) {
                match kcpsm6::asm::assemble_file(&psm, &Default::default()) {
                    Ok(program) => {
                        let text = kcpsm6::output::verilog_rom(
                            &program.image,
                            name,
                            &psm.display().to_string(),
                            kcpsm6::asm::RomSize::K4,
                            None,
                        );
                        self.notes.push(format!(
                            "`{name}` (instance `{}` in `{parent}`) is in no Verilog file: its program is {}, assembled",
                            inst.name,
                            psm.display()
                        ));
                        return Some(Choice::Generated(Source::generated(psm.with_extension("v"), text), None));
                    }
                    Err(e) => {
                        self.missing(
                            inst,
                            parent,
                            file,
                            format!("its program {} does not assemble: {}", psm.display(), e.errors_text()),
                        );
                        return None;
                    }
                }
            }
        }
        // The course's modules.
        let connected: Vec<&str> = inst.connections.iter().map(|(p, _)| p.as_str()).collect();
        if let Some((text, module)) = course::stand_in(name, &connected) {
            let unknown: Vec<&str> = inst
                .connections
                .iter()
                .map(|(p, _)| p.as_str())
                .filter(|p| !p.starts_with('#') && module.port(p).is_none())
                .collect();
            if unknown.is_empty() {
                let path = PathBuf::from(format!("botsim/course/{}.v", name));
                return Some(Choice::Generated(
                    Source::generated(path, text),
                    Some(Replacement {
                        module: name.to_string(),
                        from: String::new(),
                        with: format!("botsim's clean-room course `{name}` (the repository has none)"),
                    }),
                ));
            }
            self.missing(
                inst,
                parent,
                file,
                format!(
                "the course's `{name}` is not in the repository, and botsim's stand-in has no port {} (its ports: {})",
                unknown.join(", "),
                module.ports.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", ")
            ),
            );
            return None;
        }
        // An entity that only exists as VHDL.
        if let Some(found) = pool.entities.get(&name.to_ascii_lowercase()) {
            let (vhd, entity) = found[0].clone();
            let beside: Vec<PathBuf> = self.repo.vhdl.iter().filter(|p| p.parent() == vhd.parent()).cloned().collect();
            let generics: Vec<(String, String)> = inst
                .params
                .iter()
                .filter(|(n, v)| !n.starts_with('#') && v.trim().parse::<i64>().is_ok())
                .map(|(n, v)| (n.clone(), v.trim().to_string()))
                .collect();
            match vhdl::to_verilog(&vhd, &beside, &entity, name, &generics) {
                Ok(verilog) => {
                    let path = PathBuf::from(format!("{}.v", vhd.display()));
                    let line = std::fs::read_to_string(&vhd)
                        .ok()
                        .and_then(|t| vhdl::entities(&t).into_iter().find(|(e, _)| e.eq_ignore_ascii_case(&entity)))
                        .map_or(1, |(_, line)| line);
                    let mut source = Source::generated(path, verilog);
                    source.converted_from = Some((vhd.clone(), line));
                    return Some(Choice::Generated(
                        source,
                        Some(Replacement {
                            module: name.to_string(),
                            from: vhd.display().to_string(),
                            with: "GHDL's synthesis of the VHDL entity to Verilog".into(),
                        }),
                    ));
                }
                Err(e) => {
                    self.missing(
                        inst,
                        parent,
                        file,
                        format!("it exists only as VHDL ({}), and {e}; tie it off with --stub {name}", vhd.display()),
                    );
                    return None;
                }
            }
        }
        let hint = if let Some(Ok(ip)) = pool.ips.get(name).and_then(|v| v.first()) {
            format!(
                "an IP core botsim has no model of (`{}`, {}); tie it off with --stub {name}",
                ip.core,
                ip.path.display()
            )
        } else if let Some(Err(e)) = pool.ips.get(name).and_then(|v| v.first()) {
            format!("its IP configuration cannot be read ({e}); tie it off with --stub {name}")
        } else if let Some(d) = pool.defs.get(name).and_then(|v| v.first()) {
            format!("only a black box declares it ({}); add its file, or tie it off with --stub {name}", pool.at(*d))
        } else if looks_like_clock_core(inst) {
            let clocks = clock_options(inst);
            let read = clock_nets_read(inst).map_or(String::new(), |r| format!(", the frequencies read from {r}"));
            let hint = format!(
                "a clock core with no configuration (ports {}): give its frequencies with {} (one --clock per output{read}), or add its .xci",
                inst.connections.iter().map(|(p, _)| p.as_str()).collect::<Vec<_>>().join(", "),
                clocks
            );
            self.missing(inst, parent, file, hint);
            if let Some(m) = self.missing.last_mut() {
                m.step = Some(clocks);
            }
            return None;
        } else {
            format!("add its file, or tie it off with --stub {name}")
        };
        self.missing(inst, parent, file, hint);
        None
    }

    /// A memory core whose configuration was never committed, from its `.coe`: the file
    /// `--memory` names for the module, else `<module>.coe` in the repository (nearest to
    /// the instance), else the one `.coe` that fits the connected widths and whose name is
    /// the closest to the module's ([`coe_match`]); with none of those, a core with a write
    /// port is a RAM starting at zero, and any other is missing, its candidates listed.
    /// `None` when the instance has no memory core's ports; `Some(None)` when it is
    /// recorded as missing.
    fn coe_core(&mut self, inst: &Instance, scope: &Module, file: &Path) -> Option<Option<Choice>> {
        let name = inst.module.as_str();
        let parent = scope.name.as_str();
        let connected: Vec<&str> = inst.connections.iter().map(|(p, _)| p.as_str()).collect();
        let named = self.opts.memories.iter().find(|(m, _)| m == name).map(|(_, f)| f.clone());
        if named.is_none() && !looks_like_memory_core(&connected) {
            return None;
        }
        let dir = file.parent().unwrap_or(Path::new("."));
        let shape = Shape::connected(inst, scope);
        let coe = match named {
            Some(f) if f.is_file() => f,
            Some(f) => {
                let file_name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                match self.repo.find_near(&file_name, dir) {
                    Some(found) => found,
                    None => {
                        let hint = format!("--memory {name}={}: no such file in the repository", f.display());
                        self.missing(inst, parent, file, hint);
                        return Some(None);
                    }
                }
            }
            None => match self.repo.find_near(&format!("{name}.coe"), dir) {
                Some(own) => own,
                None => return Some(self.unnamed_core(inst, parent, file, &shape)),
            },
        };
        match MemCore::from_coe(name, &connected, &coe) {
            // Said in the substitution report, with the file.
            Ok(core) => Some(Some(self.core(core, String::new()))),
            Err(e) => {
                self.missing(inst, parent, file, format!("its contents {} do not read: {e}", coe.display()));
                Some(None)
            }
        }
    }

    /// A memory core with no configuration and no `.coe` of its name: the repository's
    /// `.coe` files offered to it ([`coe_match::offer`]).
    fn unnamed_core(&mut self, inst: &Instance, parent: &str, file: &Path, shape: &Shape) -> Option<Choice> {
        let name = inst.module.as_str();
        let connected: Vec<&str> = inst.connections.iter().map(|(p, _)| p.as_str()).collect();
        let repo = self.repo;
        let coes = self.coes.get_or_insert_with(|| {
            repo.files_with_extension("coe")
                .into_iter()
                .filter_map(|p| {
                    let text = std::fs::read(&p).ok()?;
                    parse_coe(&String::from_utf8_lossy(&text)).ok().map(|c| (p, c))
                })
                .collect()
        });
        let shown = |p: &Path| memory_arg(repo, p);
        let fitting = shape.describe();
        let lead = format!("a memory core with no configuration and no {name}.coe");
        let writes = memcore::writable(&connected);
        // A file named after another module the repository instantiates is that module's.
        let others: BTreeSet<String> = self
            .pool
            .sources
            .iter()
            .flat_map(|s| s.modules.iter().flat_map(|m| m.instances.iter().map(|i| i.module.to_ascii_lowercase())))
            .chain(self.opts.memories.iter().map(|(m, _)| m.to_ascii_lowercase()))
            .filter(|m| !m.eq_ignore_ascii_case(name))
            .collect();
        let stem = |p: &Path| p.file_stem().map(|s| s.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
        let coes: &Vec<(PathBuf, Coe)> = coes;
        let offered = coes.iter().filter(|(p, _)| !others.contains(&stem(p)));
        let candidates = match coe_match::offer(name, shape, offered) {
            Offer::Taken(c) => {
                let words = coes.iter().find(|(p, _)| *p == c.path).map_or(0, |(_, coe)| coe.words.len());
                return match MemCore::from_coe(name, &connected, &c.path) {
                    Ok(core) => {
                        self.notes.push(format!(
                            "`{name}` (instance `{}` in `{parent}`) is {lead}: its contents are {}, whose {words} words fit {fitting} and whose name is the closest to the module's (name another with --memory {name}=FILE)",
                            inst.name,
                            shown(&c.path),
                        ));
                        Some(self.core(core, String::new()))
                    }
                    Err(e) => {
                        self.missing(inst, parent, file, format!("its contents {} do not read: {e}", c.path.display()));
                        None
                    }
                };
            }
            Offer::Choose(c) => c,
        };
        // Those whose names resemble another module's more than this one's last, said.
        let claimed = |c: &coe_match::Candidate| {
            let stem = stem(&c.path);
            others
                .iter()
                .map(|m| (m, coe_match::resemblance(m, &stem)))
                .filter(|&(_, r)| r >= coe_match::RESEMBLES && r > c.resemblance)
                .max_by(|x, y| x.1.total_cmp(&y.1))
                .map(|(m, _)| m)
        };
        let mut candidates: Vec<(coe_match::Candidate, Option<&String>)> =
            candidates.into_iter().map(|c| (c.clone(), claimed(&c))).collect();
        candidates.sort_by_key(|(_, by)| by.is_some());
        let listed: Vec<String> = candidates
            .iter()
            .map(|(c, by)| match by {
                Some(m) => format!("{} (closer to `{m}`)", shown(&c.path)),
                None => shown(&c.path),
            })
            .collect();
        let candidates: Vec<coe_match::Candidate> = candidates.into_iter().map(|(c, _)| c).collect();
        if writes {
            if let (Some(depth), Some(width)) = (shape.depth(), shape.data) {
                let core = MemCore::zeroed(name, &connected, depth, width);
                let others = if listed.is_empty() {
                    String::new()
                } else {
                    format!("; the .coe files that fit: {} (name one with --memory {name}=FILE)", listed.join(", "))
                };
                self.notes.push(format!(
                    "`{name}` (instance `{}` in `{parent}`) is {lead}, with a write port: a RAM of {depth} x {width} bits (what {fitting} reach) starting at zero, as the Block Memory Generator makes one without a .coe{others}",
                    inst.name,
                ));
                return Some(self.core(core, String::new()));
            }
        }
        let all = repo.files_with_extension("coe");
        let (hint, step) = match candidates.first() {
            Some(best) => (
                format!(
                    "{lead}, and {}, closest first: {}; --memory {name}={} names the first (or another FILE), or tie it off with --stub {name}",
                    if best.resemblance >= coe_match::RESEMBLES {
                        format!("the names of the .coe files that fit {fitting} resemble the module's as closely as each other")
                    } else {
                        format!("no .coe's name resembles the module's; those that fit {fitting}")
                    },
                    listed.join(", "),
                    memory_arg(repo, &best.path)
                ),
                format!("--memory {name}={}", memory_arg(repo, &best.path)),
            ),
            None if all.is_empty() => (format!("{lead}: add its .xci or .coe, or tie it off with --stub {name}"), format!("--stub {name}")),
            None => (
                format!(
                    "{lead}, and none of the repository's .coe files fits {fitting} ({}): name its contents with --memory {name}=FILE, or tie it off with --stub {name}",
                    all.iter().map(|p| shown(p)).collect::<Vec<_>>().join(", ")
                ),
                format!("--stub {name}"),
            ),
        };
        self.missing(inst, parent, file, hint);
        if let Some(m) = self.missing.last_mut() {
            m.step = Some(step);
        }
        None
    }

    fn user(&mut self, name: &str, defs: &[Def], file: &Path) -> Choice {
        let (d, note) = match self.pool.choose(name, defs, Some(file), self.listed, self.opts) {
            Ok(c) => c,
            Err(e) => {
                self.error.get_or_insert(e);
                return Choice::User(defs[0]);
            }
        };
        self.notes.extend(note);
        // A generated wrapper of Xilinx's memory library model: the core from its
        // configuration, else from the parameters the wrapper gives the model.
        let m = self.pool.module(d);
        if let Some(lib) = m.instances.iter().find(|i| library_model(&i.module).is_some()) {
            if let Some(c) = self.configured(name, self.pool.path(d)) {
                return c;
            }
            let dir = self.pool.path(d).parent().unwrap_or(Path::new("."));
            let find = |n: &str| self.repo.find_near(n, dir);
            match MemCore::from_wrapper(m, lib, self.pool.path(d), &find) {
                Ok(core) => return self.core(core, self.pool.at(d)),
                Err(e) => self.notes.push(format!("{e} (the wrapper is compiled as it is)")),
            }
        }
        Choice::User(d)
    }

    fn core(&mut self, core: MemCore, from: String) -> Choice {
        self.notes.extend(core.notes.iter().cloned());
        let path = PathBuf::from(format!("botsim/cores/{}.v", core.name));
        Choice::Generated(
            Source::generated(path, core.verilog()),
            Some(Replacement {
                module: core.name.clone(),
                from,
                with: format!("{}, from {}", core.summary(), core.origin),
            }),
        )
    }

    /// A clock or memory core from its `.xci`/`.xco`.
    fn configured(&mut self, name: &str, file: &Path) -> Option<Choice> {
        let configs: Vec<&IpConfig> = self.pool.ips.get(name)?.iter().filter_map(|r| r.as_ref().ok()).collect();
        let supported: Vec<&IpConfig> = configs
            .into_iter()
            .filter(|c| CLOCK_CORES.contains(&c.core.as_str()) || MEMORY_CORES.contains(&c.core.as_str()))
            .collect();
        // The project's, else the nearest to the instance.
        let canon = |p: &Path| std::fs::canonicalize(p).unwrap_or(p.to_path_buf());
        let dir = canon(file.parent().unwrap_or(Path::new(".")));
        let ip = supported
            .iter()
            .max_by_key(|c| (self.listed.contains(&canon(&c.path)), common_depth(&canon(&c.path), &dir)))
            .copied()?;
        if supported.len() > 1 {
            self.notes.push(format!("`{name}` has {} IP configurations; using {}", supported.len(), ip.path.display()));
        }
        let result = if CLOCK_CORES.contains(&ip.core.as_str()) {
            ClockCore::from_config(ip).map(|c| {
                let path = PathBuf::from(format!("botsim/cores/{}.v", c.name));
                let with = format!("a Clocking Wizard from its configuration ({})", c.summary());
                Choice::Generated(
                    Source::generated(path, c.verilog()),
                    Some(Replacement { module: name.to_string(), from: ip.path.display().to_string(), with }),
                )
            })
        } else {
            let dir = ip.path.parent().unwrap_or(Path::new("."));
            let find = |n: &str| self.repo.find_near(n, dir);
            MemCore::from_config(ip, &find).map(|c| {
                let core = c.expect("a memory core's configuration");
                self.core(core, ip.path.display().to_string())
            })
        };
        match result {
            Ok(c) => Some(c),
            Err(e) => {
                self.missing.push(Missing {
                    module: name.to_string(),
                    instance: String::new(),
                    parent: String::new(),
                    at: e.location.clone().unwrap_or_default(),
                    hint: e.message,
                    step: None,
                });
                // Recorded as missing: nothing stands for it.
                Some(Choice::Own)
            }
        }
    }

    fn missing(&mut self, inst: &Instance, parent: &str, file: &Path, hint: String) {
        self.missing.push(Missing {
            module: inst.module.clone(),
            instance: inst.name.clone(),
            parent: parent.to_string(),
            at: format!("{}:{}:{}", file.display(), inst.line, inst.col),
            step: hint.contains(&format!("--stub {}", inst.module)).then(|| format!("--stub {}", inst.module)),
            hint,
        });
    }

    /// The design: stubs and `--clock` modules made from every instance, the chosen
    /// definitions' files with everything else blanked, and the missing modules as one error.
    fn finish(mut self, top: String, project: Option<PathBuf>) -> Result<Design, BoardError> {
        let project_dir = project.as_ref().and_then(|p| p.parent()).map(Path::to_path_buf);
        let mut generated = Vec::new();
        let mut sources: Vec<Source> = Vec::new();
        for (module, insts) in std::mem::take(&mut self.instances) {
            let ports: BTreeSet<String> = insts
                .iter()
                .flat_map(|i| &i.connections)
                .map(|(p, _)| p.clone())
                .filter(|p| !p.starts_with('#'))
                .collect();
            let params: BTreeSet<String> =
                insts.iter().flat_map(|i| &i.params).map(|(p, _)| p.clone()).filter(|p| !p.starts_with('#')).collect();
            let ports: Vec<String> = ports.into_iter().collect();
            if self.opts.stubs.contains(&module) {
                let params: Vec<String> = params.into_iter().collect();
                sources.push(Source::generated(
                    format!("botsim/stubs/{module}.v"),
                    super::parts::stub(&module, &ports, &params),
                ));
                generated.push(Replacement {
                    module: module.clone(),
                    from: String::new(),
                    with: super::parts::STUB.into(),
                });
            } else if let Some(specs) = self.clock_specs(&module, &insts[0].name) {
                let core = ClockCore::from_specs(&module, &specs, &ports);
                let with = format!("a clock module as --clock describes it ({})", core.summary());
                sources.push(Source::generated(format!("botsim/cores/{module}.v"), core.verilog()));
                generated.push(Replacement { module: module.clone(), from: String::new(), with });
            }
        }
        if !self.missing.is_empty() {
            // One line per module (a module cut off with the end of its file may have many
            // instances): its first instance, and how many more.
            let mut firsts: Vec<(&Missing, usize)> = Vec::new();
            for m in &self.missing {
                match firsts.iter_mut().find(|(f, _)| f.module == m.module) {
                    Some((_, more)) => *more += 1,
                    None => firsts.push((m, 0)),
                }
            }
            let n = firsts.len();
            let mut msg = if n == 1 {
                "a module of the design is missing:".to_string()
            } else {
                format!("{n} modules of the design are missing:")
            };
            for (m, more) in &firsts {
                let place = match (m.instance.is_empty(), more) {
                    (true, _) => String::new(),
                    (false, 0) => format!(" (instance `{}` in `{}`)", m.instance, m.parent),
                    (false, k) => format!(" (instance `{}` in `{}`, and {k} more)", m.instance, m.parent),
                };
                msg.push_str(&format!("\n  {}: `{}`{place}: {}", m.at, m.module, m.hint));
            }
            msg.push_str(&self.way_past(&top));
            return Err(BoardError::plain(msg));
        }
        // The user's files: each with the modules chosen from it, the rest blanked.
        let mut by_file: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for name in &self.order {
            match self.chosen.get(name) {
                Some(Choice::User(d)) => by_file.entry(d.src).or_default().push(d.module),
                Some(Choice::Generated(src, rep)) => {
                    sources.push(src.clone());
                    generated.extend(rep.clone());
                }
                _ => {}
            }
        }
        let mut user = Vec::new();
        let mut include_dirs: Vec<PathBuf> = Vec::new();
        for (src, keep) in by_file {
            let s = &self.pool.sources[src];
            let mut out = s.clone();
            out.modules =
                s.modules.iter().enumerate().filter(|(k, _)| keep.contains(k)).map(|(_, m)| m.clone()).collect();
            out.dropped =
                s.modules.iter().enumerate().filter(|(k, _)| !keep.contains(k)).map(|(_, m)| m.span.clone()).collect();
            self.lenient(&mut out);
            self.references(&mut out, project_dir.as_deref())?;
            let dir = s.path.parent().unwrap_or(Path::new(".")).to_path_buf();
            if !include_dirs.contains(&dir) {
                include_dirs.push(dir);
            }
            user.push(out);
        }
        include_dirs.extend(self.opts.include_dirs.iter().cloned());
        user.extend(sources);
        // The constraint file that places the top's ports: their package pins say what they
        // are on the board.
        let placed = user
            .iter()
            .find_map(|s| s.modules.iter().find(|m| m.name == top).map(|m| (s, m)))
            .and_then(|(s, m)| Placed::choose(&self.pool.constraints, m, &s.path));
        if let Some(p) = &placed {
            self.notes.push(format!(
                "the top's pins as {} places them on the {} ({} of its ports)",
                p.file.display(),
                p.board.name(),
                p.ports.len()
            ));
        }
        Ok(Design { top, project, sources: user, include_dirs, notes: self.notes, generated, placed })
    }

    /// The line after the missing modules that gets past them all in one step, when a module
    /// of the team's (not the top) holds several of them (an icon module holding its ROM
    /// cores): `--stub` that module, beside each other missing module's own option.
    fn way_past(&self, top: &str) -> String {
        // Each missing module once (its first instance).
        let mut unique: Vec<&Missing> = Vec::new();
        for m in &self.missing {
            if !unique.iter().any(|u| u.module == m.module) {
                unique.push(m);
            }
        }
        let n = unique.len();
        let mut held: BTreeMap<&str, usize> = BTreeMap::new();
        for m in &unique {
            *held.entry(m.parent.as_str()).or_default() += 1;
        }
        let stubbed = |parent: &str| {
            held.get(parent).is_some_and(|&k| k > 1) && parent != top && !self.pool.definitions(parent).is_empty()
        };
        let at = |parent: &str| self.pool.definitions(parent).first().map(|d| self.pool.at(*d)).unwrap_or_default();
        let mut steps: Vec<String> = Vec::new();
        for m in &unique {
            let step = if stubbed(&m.parent) { Some(format!("--stub {}", m.parent)) } else { m.step.clone() };
            let Some(step) = step else { return String::new() };
            if !steps.contains(&step) {
                steps.push(step);
            }
        }
        let groups: Vec<(&str, usize)> = held.iter().filter(|(p, _)| stubbed(p)).map(|(p, k)| (*p, *k)).collect();
        match groups.as_slice() {
            [] if n > 1 => format!("\n  {} gets past all {n}", steps.join(" ")),
            [] => String::new(),
            [(parent, k)] if *k == n => format!(
                "\n  all {n} are instantiated in `{parent}` ({}): --stub {parent} ties off that module (its outputs 0) instead",
                at(parent)
            ),
            _ => {
                let why: Vec<String> = groups
                    .iter()
                    .map(|(p, k)| format!("{k} are instantiated in `{p}` ({}), which --stub {p} ties off (its outputs 0)", at(p)))
                    .collect();
                format!("\n  {}: {} gets past all {n}", why.join("; "), steps.join(" "))
            }
        }
    }

    /// Rewrite what Vivado accepts and Verilator refuses in the compiled parts of `s`, and
    /// say so.
    fn lenient(&mut self, s: &mut Source) {
        // Instances without a name get the one the scan gave them (after the text's other
        // edits: each insertion shifts what follows it on its line).
        let mut unnamed: Vec<(usize, String, String, u32, u32)> = s
            .modules
            .iter()
            .flat_map(|m| &m.instances)
            .filter_map(|i| i.unnamed_at.map(|at| (at, i.name.clone(), i.module.clone(), i.line, i.col)))
            .filter(|(at, ..)| !s.dropped.iter().any(|d| d.start <= *at && *at < d.end))
            .collect();
        unnamed.sort_by_key(|u| std::cmp::Reverse(u.0));
        for (_, name, module, line, col) in unnamed.iter().rev() {
            self.notes.push(format!(
                "{}:{line}:{col}: this `{module}` instance has no name (Verilog needs one; Vivado names it itself): botsim calls it `{name}`",
                s.path.display()
            ));
        }
        for (at, name, ..) in &unnamed {
            // A space before it where the text has none (`bot(`), and one after.
            let spaced = s.text[..*at].ends_with(|c: char| c.is_whitespace() || c == '/');
            s.replace(*at..*at, &format!("{}{name} ", if spaced { "" } else { " " }));
        }
        let kept = |at: &std::ops::Range<usize>| !s.dropped.iter().any(|d| d.start <= at.start && at.end <= d.end);
        // A port of an ANSI header declared again as a wire in the body (Vivado reads the
        // port's declaration): blanked, columns kept.
        let again: Vec<scan::Redeclared> =
            scan::redeclared_ansi_ports(&s.text).into_iter().filter(|r| r.blank.iter().all(&kept)).collect();
        for r in &again {
            self.notes.push(format!(
                "{}:{}:{}: the {} {} of `{}` declared again as {} in its body (Verilog does not allow it; Vivado reads the port's declaration): botsim reads it so",
                s.path.display(),
                r.line,
                r.col,
                if r.names.len() == 1 { "port" } else { "ports" },
                r.names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", "),
                r.module,
                if r.names.len() == 1 { "a wire" } else { "wires" },
            ));
            for b in r.blank.iter().rev() {
                s.text.replace_range(b.clone(), &" ".repeat(b.len()));
            }
            s.edited = true;
        }
        let fixes: Vec<scan::Oversized> =
            scan::oversized_literals(&s.text).into_iter().filter(|o| kept(&o.at)).collect();
        for o in fixes.iter().rev() {
            // Padded with spaces: every column after it stays where it was.
            let padded = format!("{:<width$}", o.fixed, width = o.text.len());
            s.text.replace_range(o.at.clone(), &padded);
            s.edited = true;
        }
        // A trailing comma before a list's `)` (Vivado reads the list without it): a space.
        let commas: Vec<commas::TrailingComma> =
            commas::trailing_commas(&s.text).into_iter().filter(|c| kept(&(c.at..c.at + 1))).collect();
        for c in &commas {
            s.text.replace_range(c.at..c.at + 1, " ");
            s.edited = true;
        }
        if let Some(c) = commas.first() {
            self.notes.push(format!(
                "{}:{}:{}: a comma before the `)` that ends {} (Verilog has no empty item there; Vivado reads the list without it): botsim reads it so{}",
                s.path.display(),
                c.line,
                c.col,
                c.list,
                match commas.len() {
                    1 => String::new(),
                    n => format!(" ({} more in the file)", n - 1),
                }
            ));
        }
        // SystemVerilog's keywords are names in a Verilog file (Vivado reads `.v` as
        // Verilog-2005): escaped, they stay names for Verilator, which reads SystemVerilog.
        let verilog = s.path.extension().is_some_and(|e| e.eq_ignore_ascii_case("v"));
        if verilog {
            let names: Vec<_> = scan::sv_keywords_as_names(&s.text).into_iter().filter(|(at, ..)| kept(at)).collect();
            if let Some((_, line, col, word)) = names.first() {
                self.notes.push(format!(
                    "{}:{line}:{col}: `{word}` is a name here (a Verilog file), not SystemVerilog's keyword: botsim reads it so, as Vivado does{}",
                    s.path.display(),
                    if names.len() > 1 { format!(" ({} places in the file)", names.len()) } else { String::new() }
                ));
            }
            for (at, _, _, word) in names.into_iter().rev() {
                s.replace(at, &format!("\\{word} "));
            }
        }
        // Flip-flops written with blocking assignments: non-blocking, as Vivado builds them.
        let flops: Vec<(String, flops::BlockingFlop)> = s
            .modules
            .iter()
            .flat_map(|m| flops::blocking_flops(&s.text, m.span.clone()).into_iter().map(|f| (m.name.clone(), f)))
            .collect();
        let mut writes: Vec<usize> = flops.iter().flat_map(|(_, f)| f.writes.iter().copied()).collect();
        writes.sort_unstable();
        for at in writes.into_iter().rev() {
            s.replace(at..at, "<");
        }
        if let Some((module, f)) = flops.first() {
            let more = match flops.len() {
                1 => String::new(),
                n => format!(
                    " ({} more in the file: {})",
                    n - 1,
                    flops[1..].iter().map(|(_, f)| format!("`{}`", f.name)).collect::<Vec<_>>().join(", ")
                ),
            };
            self.notes.push(format!(
                "{}:{}:{}: `{}` in `{module}` is given blocking assignments (=) in a clocked always block that does not read it after: Vivado builds a flip-flop, which the other blocks read as it was before the clock edge; botsim simulates that flip-flop (<=), on every board alike{more}",
                s.path.display(),
                f.line,
                f.col,
                f.name
            ));
        }
        // One line a file: the first, and how many more (an icon table has dozens).
        if let Some(o) = fixes.first() {
            self.notes.push(format!(
                "{}:{}:{}: `{}` has more digits than its width holds; Vivado keeps the low bits (`{}`), and so does botsim{}",
                s.path.display(),
                o.line,
                o.col,
                o.text,
                o.fixed,
                match fixes.len() {
                    1 => String::new(),
                    n => format!(" ({} more in the file, each kept so)", n - 1),
                }
            ));
        }
    }
}

impl Walk<'_> {
    /// The files `s` names (includes, `$readmemh`/`$readmemb` files) found as Vivado finds
    /// them: beside the source, in the include folders, in the project's folder or the
    /// repository's; else by name in the repository (in any case, as on Windows). Each is
    /// written as the path found, so the build and the run find it wherever they run; one
    /// that is nowhere is an error at its file:line:col.
    fn references(&mut self, s: &mut Source, project_dir: Option<&Path>) -> Result<(), BoardError> {
        let dir = s.path.parent().unwrap_or(Path::new(".")).to_path_buf();
        let refs: Vec<scan::FileRef> = scan::file_references(&s.text)
            .into_iter()
            .filter(|r| !s.dropped.iter().any(|d| d.start <= r.at.start && r.at.end <= d.end))
            .collect();
        for r in refs.into_iter().rev() {
            let name = r.name.replace('\\', "/");
            if name.is_empty() || Path::new(&name).is_absolute() {
                continue;
            }
            let mut places: Vec<PathBuf> = vec![dir.clone()];
            places.extend(self.opts.include_dirs.iter().cloned());
            places.extend(project_dir.map(Path::to_path_buf));
            places.extend(self.repo.roots.iter().cloned());
            let direct = places.iter().map(|p| p.join(&name)).find(|p| p.is_file());
            let base = Path::new(&name).file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let found = direct.clone().or_else(|| self.repo.find_near(&base, &dir));
            let what = match r.kind {
                scan::RefKind::Include => "includes",
                scan::RefKind::Readmem => "reads",
            };
            let at = format!("{}:{}:{}", s.path.display(), r.line, r.col);
            match found {
                Some(f) => {
                    let abs = std::fs::canonicalize(&f).unwrap_or(f.clone());
                    let beside = direct.as_ref().is_some_and(|d| d.parent() == Some(dir.as_path()));
                    if !beside || r.kind == scan::RefKind::Readmem {
                        let how = if beside {
                            "beside the source, as Vivado reads it".to_string()
                        } else {
                            format!("{}", tidy(&f).display())
                        };
                        self.notes.push(format!("{at}: {what} \"{}\": {how}", r.name));
                    }
                    s.replace(r.at.clone(), &format!("\"{}\"", abs.display()));
                }
                None if r.kind == scan::RefKind::Readmem => {
                    return Err(BoardError::plain(format!(
                        "{at}: $readmem reads \"{}\", which is not in the repository (add the file)",
                        r.name
                    )));
                }
                None => {}
            }
        }
        Ok(())
    }
}

/// An instance whose connections look like a Clocking Wizard's (`clk_in1`, `clk_out1`, ...).
/// The module name of the MIPS microAptiv core (MIPSfpga's `m14k_top`): a licensed RTL that
/// teams' repositories instantiate and rarely commit.
const MIPS_CORE: &str = "m14k_top";

/// An instance of the Rojobot 3.1 IP (board.md §8): the bot's motor input beside a world-map
/// port (its map is outside it), whatever the component's name.
/// How `--memory` names `path`: its file name where no other file of the repository has it,
/// else its path.
fn memory_arg(repo: &Repo, path: &Path) -> String {
    match path.file_name() {
        Some(n) if repo.find(&n.to_string_lossy()).as_deref() == Some(path) => n.to_string_lossy().into_owned(),
        _ => path.display().to_string(),
    }
}

fn is_rojobot31_ip(inst: &Instance) -> bool {
    let connects = |p: &str| inst.connections.iter().any(|(c, _)| c == p);
    connects("MotCtl_in") && connects("worldmap_addr") && connects("worldmap_data")
}

/// The `--clock` options for a clock core's instance: one per output port it connects (a port
/// not an input, reset or status by its name), each at the frequency its name gives
/// (`CLK_75MHZ`: 75 MHz) or the name of the net it drives does (`clk75mhz`), else 25 MHz as
/// an example.
fn clock_options(inst: &Instance) -> String {
    clock_outputs(inst)
        .iter()
        .map(|(p, net)| {
            let f = frequency_in_name(p).or_else(|| frequency_in_net(net)).unwrap_or_else(|| "25MHz".into());
            format!("--clock {}.{p}={f}", inst.module)
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A clock core's outputs by their names (`clk_out1` when none looks like one), each with the
/// net it drives.
fn clock_outputs(inst: &Instance) -> Vec<(&str, &str)> {
    let outputs: Vec<(&str, &str)> = inst
        .connections
        .iter()
        .map(|(p, n)| (p.as_str(), n.as_str()))
        .filter(|(p, _)| {
            let l = p.to_ascii_lowercase();
            !p.starts_with('#')
                && ![
                    "in", "rst", "reset", "lock", "power", "pwr", "psen", "psincdec", "psclk", "daddr", "den", "dwe",
                    "di",
                ]
                .iter()
                .any(|w| l.starts_with(w) || l.contains(&format!("_{w}")))
                && !l.contains("clkin")
                && !l.contains("clkfb")
        })
        .collect();
    if outputs.is_empty() {
        vec![("clk_out1", "")]
    } else {
        outputs
    }
}

/// Where [`clock_options`] read frequencies from the nets a core's outputs drive (the ports'
/// own names giving none): `the nets' names: clk25mhz, clk75mhz`; `None` when it read none.
fn clock_nets_read(inst: &Instance) -> Option<String> {
    let read: Vec<&str> = clock_outputs(inst)
        .into_iter()
        .filter(|(p, n)| frequency_in_name(p).is_none() && frequency_in_net(n).is_some())
        .map(|(_, n)| n)
        .collect();
    match read.len() {
        0 => None,
        1 => Some(format!("the net's name: {}", read[0])),
        _ => Some(format!("the nets' names: {}", read.join(", "))),
    }
}

/// The frequency a net's name gives: as [`frequency_in_name`] (`clk75mhz`), or a number with
/// `M` after it (`clk_50M`, `clk50m`), or a clock's name ending in a number of 5 or more
/// (`pixclk25`, `clk_65`: MHz, as clocks are named); `None` otherwise (`clk1`, `clk_out2`).
fn frequency_in_net(net: &str) -> Option<String> {
    let name = net.trim().rsplit('.').next().unwrap_or("");
    if !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return None; // a select or an expression
    }
    if let Some(f) = frequency_in_name(name) {
        return Some(f);
    }
    let l = name.to_ascii_lowercase();
    if !l.contains("clk") && !l.contains("clock") {
        return None;
    }
    let body = l.strip_suffix('m').unwrap_or(&l);
    let mega = body.len() < l.len();
    let digits: String = body.chars().rev().take_while(|c| c.is_ascii_digit() || *c == '_' || *c == 'p').collect();
    let digits: String = digits.chars().rev().collect::<String>().trim_matches('_').to_string();
    if !digits.starts_with(|c: char| c.is_ascii_digit())
        || body[..body.len() - digits.len()].ends_with(|c: char| c.is_ascii_digit())
    {
        return None;
    }
    let value = digits.replacen(['_', 'p'], ".", 1).replace(['_', 'p'], "");
    let v: f64 = value.parse().ok()?;
    (v >= 5.0 || (mega && v > 0.0)).then(|| format!("{value}MHz"))
}

/// The frequency a port's name gives, as `--clock` takes it: `CLK_75MHZ` 75MHz,
/// `clk_6_25MHz` 6.25MHz, `clk100mhz` 100MHz; `None` for a name without one.
fn frequency_in_name(port: &str) -> Option<String> {
    let l = port.to_ascii_lowercase();
    let end = l.find("mhz").or_else(|| l.find("khz"))?;
    let unit = if l[end..].starts_with("mhz") { "MHz" } else { "kHz" };
    let digits: String = l[..end].chars().rev().take_while(|c| c.is_ascii_digit() || *c == '_' || *c == 'p').collect();
    let digits: String = digits.chars().rev().collect::<String>().trim_matches('_').to_string();
    if !digits.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    // `6_25` and `6p25` are 6.25; a `_` between thousands is not written in a clock's name.
    let value = digits.replacen(['_', 'p'], ".", 1).replace(['_', 'p'], "");
    value.parse::<f64>().ok().filter(|v| *v > 0.0).map(|_| format!("{value}{unit}"))
}

fn looks_like_clock_core(inst: &Instance) -> bool {
    let ports: Vec<String> = inst.connections.iter().map(|(p, _)| p.to_ascii_lowercase()).collect();
    ports.iter().any(|p| p.starts_with("clk_in") || p == "clkin")
        || (ports.iter().any(|p| p.starts_with("clk_out"))
            && ports.iter().any(|p| p.contains("locked") || p.contains("reset")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree(files: &[(&str, &str)]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for (f, text) in files {
            let p = dir.path().join(f);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, text).unwrap();
        }
        dir
    }

    const TOP: &str =
        "module nexys4fpga(input clk, output [15:0] led);\n  sys s (.clk(clk));\n  bot b (.clk(clk));\nendmodule\n";

    fn names(d: &Design) -> Vec<(String, Vec<String>)> {
        d.sources
            .iter()
            .map(|s| {
                let p = s.path.to_string_lossy().into_owned();
                let short = p.rsplit_once("/tmp").map_or(p.clone(), |_| {
                    p.split('/').rev().take(2).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("/")
                });
                (short, s.modules.iter().map(|m| m.name.clone()).collect())
            })
            .collect()
    }

    #[test]
    fn only_what_the_top_reaches_is_compiled() {
        let t = tree(&[
            ("src/top.v", TOP),
            ("src/sys.v", "module sys(input clk); endmodule\nmodule unused(input a); broken syntax here\nendmodule\n"),
            ("KCPSM6_Release9/ROM_form.v", "module jtag_loader_6(input a); endmodule\n"),
            ("src/prog.v", "module jtag_loader_6(input a); assign x = 1; endmodule\n"),
            ("tb/tb.v", "module tb; nexys4fpga dut (.clk(c)); endmodule\n"),
        ]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        assert_eq!(d.top, "nexys4fpga");
        assert_eq!(
            names(&d),
            [("src/sys.v".to_string(), vec!["sys".to_string()]), ("src/top.v".into(), vec!["nexys4fpga".into()])]
        );
        // The unused module of a reached file is blanked, lines kept.
        let sys = d.sources.iter().find(|s| s.path.ends_with("sys.v")).unwrap();
        assert_eq!(sys.dropped.len(), 1);
        assert!(!sys.compiled_text(&[]).contains("broken"));
        assert_eq!(sys.compiled_text(&[]).lines().count(), 3);
    }

    #[test]
    fn different_copies_the_one_beside_the_parent_wins_and_is_said() {
        let t = tree(&[
            ("src/top.v", TOP),
            ("src/sys.v", "module sys(input clk); assign a = 1; endmodule\n"),
            ("old/sys.v", "module sys(input clk); assign a = 0; endmodule\n"),
            ("copy/sys.v", "// same as src, other comment\nmodule sys(input clk);\n assign a = 1;\nendmodule\n"),
        ]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let sys = d.sources.iter().find(|s| s.module("sys").is_some()).unwrap();
        assert!(sys.path.ends_with("src/sys.v"), "{:?}", sys.path);
        let note = d.notes.iter().find(|n| n.contains("`sys` has 3 different definitions")).unwrap();
        assert!(note.contains("src/sys.v:1 (beside") && note.contains("old/sys.v:1"), "{note}");
        // --file chooses another.
        let opts = Options { prefer: vec![t.path().join("old/sys.v")], ..Options::default() };
        let d = resolve(&[t.path().to_path_buf()], &opts).unwrap();
        assert!(d.sources.iter().any(|s| s.module("sys").is_some() && s.path.ends_with("old/sys.v")));
        // --exclude leaves a folder out: the other two copies remain, and nothing orders them
        // (no project, neither beside the top, no git history; their files' dates are no
        // reason): one error naming both and the option.
        let opts = Options { exclude: vec![t.path().join("src")], ..Options::default() };
        let e = resolve(&[t.path().to_path_buf(), t.path().join("src/top.v")], &opts).unwrap_err().to_string();
        assert!(e.contains("`sys` has 2 different definitions and nothing tells which"), "{e}");
        assert!(e.contains("old/sys.v:1") && e.contains("copy/sys.v:2") && e.contains("--file"), "{e}");
        assert!(!e.contains("src/sys.v"), "{e}");
    }

    #[test]
    fn a_frame_buffer_without_a_coe_is_a_zeroed_ram_when_its_widths_are_read_and_missing_when_not() {
        let top = |addr: &str| {
            format!(
                "module top(input clk, input [15:0] sw, output [15:0] led);\n  parameter W = 8;\n  wire [{addr}] a = sw[9:0];\n  wire [W-1:0] q;\n  fb F (.clka(clk), .wea(sw[15]), .addra(a), .dina(sw[7:0]), .douta(q));\n  assign led = q;\nendmodule\n"
            )
        };
        // The address read from its declaration, the data from the input's part select.
        let t = tree(&[("top.v", &top("9:0"))]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let core = d.sources.iter().find(|s| s.module("fb").is_some()).unwrap();
        assert!(core.text.contains("reg [7:0] mem [0:1023];"), "{}", core.text);
        assert!(
            d.notes.iter().any(|n| n.contains("a RAM of 1024 x 8 bits") && n.contains("starting at zero")),
            "{:?}",
            d.notes
        );
        // An address whose width is a parameter's: not guessed.
        let t = tree(&[("top.v", &top("W+1:0"))]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        assert!(e.contains("`fb` (instance `F` in `top`): a memory core with no configuration and no fb.coe: add its .xci or .coe, or tie it off with --stub fb"), "{e}");
    }

    #[test]
    fn every_missing_module_at_once_with_what_gets_past_it() {
        let t = tree(&[(
            "top.v",
            "module top(input clk);\n  clk_wiz_0 cw (.clk_in1(clk), .clk_out1(c25), .locked(l));\n  uart u (.clk(clk));\n  bot b (.clk(clk));\n  spi s (.clk(clk));\nendmodule\n",
        )]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        let lines: Vec<&str> = e.lines().collect();
        assert_eq!(lines[0], "3 modules of the design are missing:");
        assert!(lines[1].ends_with("top.v:2:3: `clk_wiz_0` (instance `cw` in `top`): a clock core with no configuration (ports clk_in1, clk_out1, locked): give its frequencies with --clock clk_wiz_0.clk_out1=25MHz (one --clock per output), or add its .xci"), "{e}");
        assert!(
            lines[2]
                .contains("top.v:3:3: `uart` (instance `u` in `top`): add its file, or tie it off with --stub uart"),
            "{e}"
        );
        assert!(lines[3].contains("top.v:5:3: `spi`"), "{e}");
        assert_eq!(lines[4], "  --clock clk_wiz_0.clk_out1=25MHz --stub uart --stub spi gets past all 3", "{e}");
        let opts = Options {
            stubs: vec!["uart".into(), "spi".into()],
            clocks: vec![ClockSpec::parse("clk_wiz_0.clk_out1=25MHz").unwrap()],
            ..Options::default()
        };
        let d = resolve(&[t.path().to_path_buf()], &opts).unwrap();
        let made: Vec<&str> = d.generated.iter().map(|r| r.module.as_str()).collect();
        assert_eq!(made, ["clk_wiz_0", "spi", "uart"]);
    }

    #[test]
    fn a_clock_cores_options_use_its_own_output_names_and_the_frequencies_they_give() {
        let inst = |ports: &[&str]| Instance {
            module: "cw".into(),
            name: "u".into(),
            line: 1,
            col: 1,
            connections: ports.iter().map(|p| (p.to_string(), "x".into())).collect(),
            spans: vec![],
            params: vec![],
            unnamed_at: None,
            guarded: false,
        };
        assert_eq!(
            clock_options(&inst(&["clk_in1", "CLK_75MHZ", "CLK_25MHZ", "reset", "locked"])),
            "--clock cw.CLK_75MHZ=75MHz --clock cw.CLK_25MHZ=25MHz"
        );
        assert_eq!(clock_options(&inst(&["CLK_IN1", "CLK_OUT1", "RESET", "LOCKED"])), "--clock cw.CLK_OUT1=25MHz");
        assert_eq!(
            clock_options(&inst(&["clk_in1", "clk_6_25MHz", "clk100mhz"])),
            "--clock cw.clk_6_25MHz=6.25MHz --clock cw.clk100mhz=100MHz"
        );
        // The nets a core's outputs drive, where its ports' names give no frequency.
        let wired = |pairs: &[(&str, &str)]| Instance {
            connections: pairs.iter().map(|(p, n)| (p.to_string(), n.to_string())).collect(),
            ..inst(&[])
        };
        let game =
            wired(&[("clk_in1", "clk"), ("clk_out1", "clk25mhz"), ("clk_out2", "clk75mhz"), ("clk_out3", "clk50mhz")]);
        assert_eq!(
            clock_options(&game),
            "--clock cw.clk_out1=25MHz --clock cw.clk_out2=75MHz --clock cw.clk_out3=50MHz"
        );
        assert_eq!(clock_nets_read(&game).as_deref(), Some("the nets' names: clk25mhz, clk75mhz, clk50mhz"));
        let named =
            wired(&[("clk_in1", "clk"), ("clk_out1", "clk_50M"), ("clk_out2", "pixclk25"), ("clk_out3", "clk2")]);
        assert_eq!(
            clock_options(&named),
            "--clock cw.clk_out1=50MHz --clock cw.clk_out2=25MHz --clock cw.clk_out3=25MHz"
        );
        assert_eq!(clock_nets_read(&named).as_deref(), Some("the nets' names: clk_50M, pixclk25"));
        for net in ["clk_out2", "clk1", "c25", "count25", "clk[1]", "video_clk_12_5"] {
            assert_eq!(frequency_in_net(net).is_some(), net == "video_clk_12_5", "{net}");
        }
        assert_eq!(frequency_in_net("video_clk_12_5").as_deref(), Some("12.5MHz"));
        assert_eq!(frequency_in_name("clk_out1"), None);
        assert_eq!(frequency_in_name("pix_clk_65MHz"), Some("65MHz".into()));
        for o in
            clock_options(&inst(&["clk_in1", "CLK_75MHZ", "clk_6_25MHz"])).split("--clock ").filter(|o| !o.is_empty())
        {
            ClockSpec::parse(o.trim()).unwrap_or_else(|e| panic!("{o}: {e}"));
        }
    }

    #[test]
    fn missing_modules_mostly_in_one_team_module_are_passed_with_its_stub_and_the_others_steps_in_one_line() {
        let t = tree(&[
            ("top.v", "module top(input clk);\n  clk_wiz_0 cw (.clk_in1(clk), .clk_out1(c25), .locked(l));\n  icon i (.clk(c25));\n  bot b (.clk(clk));\nendmodule\n"),
            ("icon.v", "module icon(input clk);\n  rom_a a (.clka(clk));\n  rom_b b (.clka(clk));\n  rom_c c (.clka(clk));\nendmodule\n"),
        ]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        let last = e.lines().last().unwrap();
        assert!(e.starts_with("4 modules of the design are missing:"), "{e}");
        assert!(last.contains("3 are instantiated in `icon` ("), "{e}");
        assert!(last.ends_with("--clock clk_wiz_0.clk_out1=25MHz --stub icon gets past all 4"), "{e}");
        // The line's options do get past them all.
        let opts = Options {
            stubs: vec!["icon".into()],
            clocks: vec![ClockSpec::parse("clk_wiz_0.clk_out1=25MHz").unwrap()],
            ..Options::default()
        };
        resolve(&[t.path().to_path_buf()], &opts).unwrap();
    }

    #[test]
    fn a_design_of_the_mipsfpga_era_is_refused_in_one_line_naming_the_rojobot31_ip_and_the_mips_core() {
        // The Rojobot 3.1 IP under any component name, the MIPS core not committed; another
        // module with a clock pin beside the top (which would make "several tops").
        let top = "module mfp_nexys4_ddr(input CLK100MHZ, output [15:0] LED);\n  mfp_sys sys (.SI_ClkIn(CLK100MHZ));\n  rojobot31_upper_0 robot(.MotCtl_in(m), .LocX_reg(x), .worldmap_addr(a), .worldmap_data(d), .clk_in(CLK100MHZ), .Bot_Config_reg(8'h0));\nendmodule\n";
        let sys = "module mfp_sys(input SI_ClkIn);\n  m14k_top top (.SI_ClkIn(SI_ClkIn));\nendmodule\n";
        let other = "module debounce(input clk, input [5:0] pbtn_in, output [5:0] pbtn_db);\nendmodule\n";
        let t = tree(&[("hw/mfp_nexys4_ddr.v", top), ("hw/mfp_sys.v", sys), ("hw/debounce.v", other)]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(
            e.contains(
                "mfp_nexys4_ddr.v:3:3: `rojobot31_upper_0` (instance `robot`) is the Rojobot 3.1 IP (rojobot31)"
            ),
            "{e}"
        );
        assert!(e.contains("its MIPS microAptiv core (`m14k_top`, ") && e.contains("mfp_sys.v:2:3)"), "{e}");
        // Named as the top, the same.
        let opts = Options { top: Some("mfp_nexys4_ddr".into()), ..Options::default() };
        let named = resolve(&[t.path().to_path_buf()], &opts).unwrap_err().to_string();
        assert_eq!(named, e);
    }

    #[test]
    fn a_missing_module_with_many_instances_is_one_line() {
        // A file cut before its last module: the module is gone, its eight instances stay.
        let mut top = String::from("module top(input clk, output [7:0] led);\n");
        for k in 0..8 {
            top.push_str(&format!("  cell c{k} (.i(clk), .o(led[{k}]));\n"));
        }
        top.push_str("  bot b (.clk(clk));\nendmodule\n");
        let t = tree(&[("top.v", &top)]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        let lines: Vec<&str> = e.lines().collect();
        assert_eq!(lines[0], "a module of the design is missing:", "{e}");
        assert_eq!(lines.len(), 2, "{e}");
        assert!(lines[1].contains("`cell` (instance `c0` in `top`, and 7 more)"), "{e}");
    }

    #[test]
    fn an_ansi_port_declared_again_as_a_wire_is_read_as_vivado_reads_it_and_said() {
        let spi = "module spi(input clk, output SS, output SCLK, output MOSI);\n  wire SS, SCLK, MOSI;\n  wire [3:0] n, MOSI2;\n  assign SS = clk;\nendmodule\n";
        let top = "module nexys4fpga(input clk, output [15:0] led);\n  spi s (.clk(clk), .SS(led[0]));\n  bot b (.clk(clk));\nendmodule\n";
        let t = tree(&[("top.v", top), ("spi.v", spi)]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let note = d.notes.iter().find(|n| n.contains("declared again")).unwrap_or_else(|| panic!("{:?}", d.notes));
        assert!(note.ends_with("spi.v:2:3: the ports `SS`, `SCLK`, `MOSI` of `spi` declared again as wires in its body (Verilog does not allow it; Vivado reads the port's declaration): botsim reads it so"), "{note}");
        let text = &d.sources.iter().find(|s| s.path.ends_with("spi.v")).unwrap().text;
        assert_eq!(text.lines().nth(1), Some(" ".repeat(22).as_str()));
        // Other wires, and the line count, as they were.
        assert_eq!(text.lines().nth(2), Some("  wire [3:0] n, MOSI2;"));
        assert_eq!(text.lines().count(), spi.lines().count());
    }

    #[test]
    fn a_bot_of_another_botsim_is_named_by_its_port() {
        let t = tree(&[("top.v", "module top(input clk);\n  bot b (.clk(clk), .Bot_Config_reg(cfg));\nendmodule\n")]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        assert!(
            e.contains("top.v:2:3: this `bot` has a port `Bot_Config_reg` that BotSim 2.0's bot does not have"),
            "{e}"
        );
    }

    #[test]
    fn the_top_is_the_board_module_that_reaches_the_bot() {
        let t = tree(&[
            ("p2/top.v", TOP),
            ("p2/sys.v", "module sys(input clk); endmodule\n"),
            ("p1/top1.v", "module proj1(input clk, output [15:0] led); endmodule\n"),
        ]);
        assert_eq!(resolve(&[t.path().to_path_buf()], &Options::default()).unwrap().top, "nexys4fpga");
        let t = tree(&[
            ("a.v", TOP),
            ("b.v", "module final_top(input clk); bot b (.clk(clk)); endmodule\n"),
            ("s.v", "module sys(input clk); endmodule\n"),
        ]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        assert!(e.starts_with("several modules could be the top: `final_top` ("), "{e}");
        assert!(e.ends_with("; name one with --top"), "{e}");
    }

    #[test]
    fn oversized_literals_are_truncated_as_vivado_does_and_said() {
        let t = tree(&[(
            "top.v",
            "module top(input clk, output [7:0] led);\n  assign led = 8'h1FF;\n  bot b (.clk(clk));\nendmodule\n",
        )]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let top = d.sources.iter().find(|s| s.module("top").is_some()).unwrap();
        assert!(top.edited && top.text.contains("assign led = 8'hFF ;"), "{}", top.text);
        assert!(d.notes.iter().any(|n| n.ends_with("top.v:2:16: `8'h1FF` has more digits than its width holds; Vivado keeps the low bits (`8'hFF`), and so does botsim")), "{:?}", d.notes);
        // Many in one file (an icon table): one line, the first and how many more.
        let rows: String = (0..12).map(|k| format!("  wire [3:0] r{k} = 4'b1{k:04b};\n")).collect();
        let t = tree(&[(
            "top.v",
            &format!("module top(input clk, output [7:0] led);\n{rows}  bot b (.clk(clk));\nendmodule\n"),
        )]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let said: Vec<&String> = d.notes.iter().filter(|n| n.contains("more digits")).collect();
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("top.v:2:") && said[0].ends_with("(11 more in the file, each kept so)"), "{said:?}");
        let top = d.sources.iter().find(|s| s.module("top").is_some()).unwrap();
        assert!(top.text.contains("r11 = 4'b1011 ;"), "{}", top.text);
    }

    #[test]
    fn readmem_files_and_includes_are_found_as_vivado_finds_them_or_named_when_missing() {
        let top = "`include \"Defs.vh\"\nmodule top(input clk);\n  reg [1:0] rom [0:3];\n  initial $readmemh(\"icon.mem\", rom);\n  initial $readmemb(\"data/Table.MEM\", rom);\n  bot b (.clk(clk));\nendmodule\n";
        let t = tree(&[
            ("hdl/top.v", top),
            ("hdl/icon.mem", "0 1 2 3\n"),
            ("mem/table.mem", "00\n"),
            ("inc/defs.vh", "`define X 1\n"),
        ]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let s = d.sources.iter().find(|s| s.module("top").is_some()).unwrap();
        let abs = |p: &str| std::fs::canonicalize(t.path().join(p)).unwrap().display().to_string();
        for p in ["hdl/icon.mem", "mem/table.mem", "inc/defs.vh"] {
            assert!(s.text.contains(&format!("\"{}\"", abs(p))), "{p}: {}", s.text);
        }
        // The module's span follows the longer text: nothing of it is cut.
        assert!(s.text[s.modules[0].span.clone()].ends_with("endmodule"));
        let notes = d.notes.join("\n");
        assert!(notes.contains("hdl/top.v:4:21: reads \"icon.mem\": beside the source, as Vivado reads it"), "{notes}");
        assert!(
            notes.contains("hdl/top.v:5:21: reads \"data/Table.MEM\": ") && notes.contains("mem/table.mem"),
            "{notes}"
        );
        assert!(notes.contains("hdl/top.v:1:10: includes \"Defs.vh\": ") && notes.contains("inc/defs.vh"), "{notes}");
        let t = tree(&[("top.v", "module top(input clk);\n  reg r [0:1];\n  initial $readmemh(\"gone.mem\", r);\n  bot b (.clk(clk));\nendmodule\n")]);
        let e = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap_err().to_string();
        assert!(
            e.ends_with("top.v:3:21: $readmem reads \"gone.mem\", which is not in the repository (add the file)"),
            "{e}"
        );
    }

    #[test]
    fn a_program_rom_committed_only_as_its_psm_is_assembled() {
        let top = "module top(input clk);\n  wire [11:0] a; wire [17:0] i; wire e;\n\
                   kcpsm6 cpu (.address(a), .instruction(i), .bram_enable(e), .clk(clk));\n\
                   prog rom (.address(a), .instruction(i), .enable(e), .clk(clk));\n  bot b (.clk(clk));\nendmodule\n";
        let t = tree(&[("hdl/top.v", top), ("psm/prog.psm", "start: LOAD s0, 2A\n       JUMP start\n")]);
        let d = resolve(&[t.path().to_path_buf()], &Options::default()).unwrap();
        let rom = d.sources.iter().find(|s| s.module("prog").is_some()).unwrap();
        assert!(rom.path.ends_with("psm/prog.v"), "{:?}", rom.path);
        let image = kcpsm6::Image::parse_verilog(&rom.path, &rom.text).unwrap();
        assert_eq!(image.words[0], 0x0102A);
        assert!(
            d.notes
                .iter()
                .any(|n| n.contains("`prog` (instance `rom` in `top`) is in no Verilog file: its program is")),
            "{:?}",
            d.notes
        );
    }
}
