//! Build script: Verilog -> Verilator C++ -> a static library with a C shim -> Rust FFI.
//!
//! 1. check the tools (Verilator 5, libclang) and stop with one line naming the setup script;
//! 2. verilate each design once, each with its own `--prefix` (spec/verilator.md 4.1, 4.4);
//! 3. compile the generated model files (listed in `V<prefix>_classes.mk`, never hard-coded),
//!    the Verilator runtime (with VL_USER_FINISH/VL_USER_FATAL) and the shims with `cc`,
//!    optimised whatever the Cargo profile, each into a library rebuilt only when its inputs
//!    change;
//! 4. generate the FFI with bindgen from the plain C header `src/sim/rtl/ffi/shim.h`.
//!
//! A run for `cargo clippy` does 1 and 4 only: a check never links, and the models took most
//! of the lint stage's time (they were built again, in the check's own output folder).

use std::collections::BTreeSet;
use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "build/sources.rs"]
mod sources;
#[path = "build/verilator.rs"]
mod verilator;

/// One verilated design: a prefix, a top module, its sources and parameters.
struct Design {
    prefix: &'static str,
    top: &'static str,
    sources: Vec<PathBuf>,
    params: Vec<String>,
}

/// The CPU harness variants: scratch-pad size, hwbuild, interrupt_vector.
const CPU_VARIANTS: [(u32, u8, u16); 3] = [(64, 0x00, 0x3FF), (128, 0x5A, 0x1C0), (256, 0xFF, 0x7F0)];

/// A design's file list (rtl/bot.f, rtl/sim/cpu.f: one path per line relative to the
/// repository, `#` comments), the one list the gate and the scripts read too.
fn file_list(root: &Path, list: &str) -> Vec<PathBuf> {
    let path = root.join(list);
    println!("cargo:rerun-if-changed={}", path.display());
    let text = fs::read_to_string(&path).unwrap_or_else(|e| fail(&format!("cannot read {list}: {e}")));
    text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).map(|l| root.join(l)).collect()
}

fn fail(msg: &str) -> ! {
    eprintln!("error: {msg}");
    std::process::exit(1);
}

fn main() {
    let root = PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap());
    let out = PathBuf::from(env::var("OUT_DIR").unwrap());
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/sim/rtl/ffi");
    println!("cargo:rerun-if-env-changed=VERILATOR");
    println!("cargo:rerun-if-env-changed=VERILATOR_ROOT");
    println!("cargo:rerun-if-env-changed=BOTSIM_COVERAGE");
    // A coverage build (scripts/ci/coverage.sh): line and toggle coverage points in every model.
    let coverage = env::var_os("BOTSIM_COVERAGE").is_some();

    let verilator = env::var("VERILATOR").unwrap_or_else(|_| "verilator".into());
    let vroot = verilator_root(&verilator);
    if check_only() {
        assemble_firmware(&root, &out);
        bindings(&root, &out);
        variants(&out);
        return;
    }

    let mut designs: Vec<Design> = CPU_VARIANTS
        .iter()
        .map(|&(spm, hw, vec)| Design {
            prefix: match spm {
                64 => "Vcpu64",
                128 => "Vcpu128",
                _ => "Vcpu256",
            },
            top: "kcpsm6_harness",
            sources: file_list(&root, "rtl/sim/cpu.f"),
            params: vec![
                format!("-GSPM_SIZE={spm}"),
                format!("-GHWBUILD=8'h{hw:02X}"),
                format!("-GVECTOR=12'h{vec:03X}"),
            ],
        })
        .collect();
    let bot_pgm = assemble_firmware(&root, &out);
    // The design, the simulator's own waivers (public signals the shim reads), the firmware.
    let mut bot_sources = file_list(&root, "rtl/bot.f");
    bot_sources.push(root.join("rtl/sim/bot.vlt"));
    bot_sources.push(bot_pgm);
    designs.push(Design { prefix: "Vbot", top: "bot", sources: bot_sources.clone(), params: vec![] });
    // Again with the KCPSM6's debug signals (Xilinx's names, for waveforms: the instruction's
    // text, the status, the registers), as a board's waveform build has them.
    let debug = vec!["+define+BOTSIM_DEBUG".to_string(), "--trace-max-array".into(), "256".into()];
    designs.push(Design { prefix: "Vbotdbg", top: "bot", sources: bot_sources, params: debug });
    designs.sort_by_key(|d| d.prefix);

    // Each design, the runtime and the shims become their own static library. A library is
    // rebuilt only when what it is compiled from changed (a content hash in a stamp file), so
    // an edit to one RTL file recompiles one model: see "Build times" in the README.
    let mut runtime = BTreeSet::new();
    let mut include_dirs = Vec::new();
    let mut model_libs = Vec::new();
    for d in &designs {
        let mdir = out.join(d.prefix);
        verilate(&verilator, &root, &mdir, d, coverage);
        let classes = fs::read_to_string(mdir.join(format!("{}_classes.mk", d.prefix)))
            .unwrap_or_else(|e| fail(&format!("cannot read Verilator's file list: {e}")));
        let mut files = Vec::new();
        for var in ["VM_CLASSES_FAST", "VM_CLASSES_SLOW", "VM_SUPPORT_FAST", "VM_SUPPORT_SLOW"] {
            for name in mk_list(&classes, var) {
                files.push(mdir.join(format!("{name}.cpp")));
            }
        }
        for var in ["VM_GLOBAL_FAST", "VM_GLOBAL_SLOW"] {
            runtime.extend(mk_list(&classes, var));
        }
        rerun_for_sources(&mdir, d.prefix, &vroot, &out);
        // The model's headers are part of its input too (the generated .h files).
        let mut inputs = files.clone();
        inputs.extend(list_dir(&mdir).into_iter().filter(|f| f.extension().is_some_and(|e| e == "h")));
        model_libs.push((format!("{}_model", d.prefix), files, inputs, mdir.clone()));
        include_dirs.push(mdir);
    }
    // Everything besides the inputs' contents that shapes the objects: a change rebuilds all.
    let config = format!(
        "{:?} {DEFINES:?} opt=2 coverage={coverage} cxx={:?} root={}",
        compiler_flags(),
        env::var("CXX").ok(),
        vroot.display()
    );
    let cpp = |includes: &[PathBuf]| {
        let mut b = cc::Build::new();
        b.cpp(true)
            .std("c++17")
            .warnings(false)
            .opt_level(2) // never -O0: an unoptimised model runs ~7x slower (spec/verilator.md 4.3)
            .debug(false)
            .cpp_link_stdlib(None) // linked once, after all the libraries (below)
            .define("VM_COVERAGE", if coverage { "1" } else { "0" })
            .include(vroot.join("include"))
            .include(vroot.join("include/vltstd"))
            .include(root.join("src/sim/rtl/ffi"));
        for f in compiler_flags() {
            b.flag_if_supported(f);
        }
        for (name, value) in DEFINES {
            b.define(name, *value);
        }
        for dir in includes {
            b.include(dir);
        }
        b
    };
    // The shims come first on the link line: they use the models, which use the runtime.
    let shims = [root.join("src/sim/rtl/ffi/cpu_shim.cpp"), root.join("src/sim/rtl/ffi/bot_shim.cpp")];
    let mut shim_inputs = shims.to_vec();
    shim_inputs.extend(list_dir(&root.join("src/sim/rtl/ffi")));
    for mdir in &include_dirs {
        shim_inputs.extend(list_dir(mdir).into_iter().filter(|f| f.extension().is_some_and(|e| e == "h")));
    }
    cached_lib(&out, "botsim_shims", &config, &shim_inputs, || {
        let mut b = cpp(&include_dirs);
        b.files(&shims);
        b
    });
    for (name, files, inputs, mdir) in &model_libs {
        cached_lib(&out, name, &config, inputs, || {
            let mut b = cpp(std::slice::from_ref(mdir));
            b.files(files);
            b
        });
    }
    let runtime_files: Vec<PathBuf> =
        runtime.iter().map(|name| vroot.join("include").join(format!("{name}.cpp"))).collect();
    cached_lib(&out, "verilator_runtime", &config, &runtime_files, || {
        let mut b = cpp(&[]);
        b.files(&runtime_files);
        b
    });
    println!("cargo:rustc-link-lib=stdc++");

    bindings(&root, &out);
    variants(&out);
}

/// Whether this run serves `cargo clippy`, which checks and lints but never links: Cargo gives
/// build scripts the wrapper it puts around the workspace's rustc, and Clippy's is its driver.
fn check_only() -> bool {
    env::var_os("RUSTC_WORKSPACE_WRAPPER")
        .is_some_and(|w| Path::new(&w).file_stem().is_some_and(|s| s.to_string_lossy().starts_with("clippy-driver")))
}

/// Flags for every C++ file (applied when the compiler supports them).
fn compiler_flags() -> [&'static str; 3] {
    ["-faligned-new", "-fcf-protection=none", "-Wno-unused-parameter"]
}

/// Defines for every C++ file: the runtime as the models need it, $finish and fatal errors
/// handled by the shims (spec/verilator.md H4).
const DEFINES: &[(&str, Option<&str>)] = &[
    ("VM_SC", Some("0")),
    ("VM_TRACE", Some("1")),
    ("VM_TRACE_VCD", Some("1")),
    ("VM_TRACE_FST", Some("0")),
    ("VL_USER_FINISH", None),
    ("VL_USER_FATAL", None),
];

/// The files of a folder (not recursive), sorted.
fn list_dir(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

/// Compile the static library `lib<name>.a` with `build` unless the stamp says its inputs
/// (contents) and configuration are those it was last built from; either way, link it.
fn cached_lib(out: &Path, name: &str, config: &str, inputs: &[PathBuf], build: impl FnOnce() -> cc::Build) {
    // FNV-1a over the configuration and every input's name and contents.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    };
    eat(config.as_bytes());
    for f in inputs {
        eat(f.to_string_lossy().as_bytes());
        eat(&fs::read(f).unwrap_or_else(|e| fail(&format!("cannot read {}: {e}", f.display()))));
    }
    let stamp = out.join(format!("{name}.stamp"));
    let lib = out.join(format!("lib{name}.a"));
    let key = format!("{h:016x}\n");
    if lib.exists() && fs::read_to_string(&stamp).ok().as_deref() == Some(key.as_str()) {
        println!("cargo:rustc-link-search=native={}", out.display());
        println!("cargo:rustc-link-lib=static={name}");
        return;
    }
    let _ = fs::remove_file(&stamp);
    build().compile(name);
    fs::write(&stamp, key).unwrap_or_else(|e| fail(&format!("cannot write {}: {e}", stamp.display())));
}

/// Assemble the firmware with its default constants into the ROM module Verilator compiles.
fn assemble_firmware(root: &Path, out: &Path) -> PathBuf {
    use kcpsm6::asm::{assemble_file, Options, RomSize};
    let psm = root.join("rtl/bot_pgm.psm");
    println!("cargo:rerun-if-changed={}", psm.display());
    let opts = Options { rom_size: Some(RomSize::K1), ..Options::default() };
    let program =
        assemble_file(&psm, &opts).unwrap_or_else(|d| fail(&format!("rtl/bot_pgm.psm does not assemble:\n{d}")));
    let v = kcpsm6::output::verilog_rom(&program.image, "bot_pgm", "bot_pgm.psm", RomSize::K1, program.default_jump);
    let path = out.join("bot_pgm.v");
    fs::write(&path, v).unwrap_or_else(|e| fail(&format!("cannot write {}: {e}", path.display())));
    path
}

/// The Verilator runtime's root, after checking the version (build/verilator.rs).
fn verilator_root(verilator: &str) -> PathBuf {
    let v = verilator::find(verilator).unwrap_or_else(|e| fail(&e));
    v.root
}

fn verilate(verilator: &str, root: &Path, mdir: &Path, d: &Design, coverage: bool) {
    let _ = fs::remove_dir_all(mdir);
    let mut cmd = Command::new(verilator);
    cmd.current_dir(root)
        .args(["--cc", "--no-timing", "-O3", "--x-assign", "fast", "--x-initial", "unique", "--trace"])
        .args(["--prefix", d.prefix, "--top-module", d.top])
        .arg("--Mdir")
        .arg(mdir)
        .args(&d.params)
        .args(if coverage { &["--coverage-line", "--coverage-toggle"][..] } else { &[][..] })
        .args(&d.sources);
    let o = cmd.output().unwrap_or_else(|e| fail(&format!("cannot run verilator: {e}")));
    for line in String::from_utf8_lossy(&o.stderr).lines() {
        println!("cargo:warning={line}");
    }
    if !o.status.success() {
        fail(&format!("verilator failed on {} ({})", d.top, d.prefix));
    }
}

/// The names in a `VAR += \` block of a Verilator makefile fragment.
fn mk_list(text: &str, var: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        if l.trim_start().starts_with(var) && l.contains("+=") {
            for item in lines.by_ref() {
                let t = item.trim().trim_end_matches('\\').trim();
                if t.is_empty() {
                    break;
                }
                names.push(t.to_string());
                if !item.trim_end().ends_with('\\') {
                    break;
                }
            }
        }
    }
    names
}

/// rerun-if-changed for every design source Verilator read (build/sources.rs).
fn rerun_for_sources(mdir: &Path, prefix: &str, vroot: &Path, out: &Path) {
    let dat = fs::read_to_string(mdir.join(format!("{prefix}__verFiles.dat"))).unwrap_or_default();
    for path in sources::design_sources(&dat, vroot, out) {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

fn bindings(root: &Path, out: &Path) {
    let header = root.join("src/sim/rtl/ffi/shim.h");
    // bindgen panics when libclang cannot be loaded: keep the message to our one line.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(|| {
        bindgen::Builder::default()
            .header(header.to_string_lossy())
            .allowlist_function("cpu_sim_.*")
            .allowlist_function("bot_sim_.*")
            .allowlist_type("Cpu.*")
            .allowlist_type("Bot.*")
            .derive_default(true)
            .generate()
    });
    std::panic::set_hook(hook);
    match result {
        Ok(Ok(b)) => b.write_to_file(out.join("bindings.rs")).unwrap_or_else(|e| fail(&format!("bindings: {e}"))),
        Ok(Err(e)) => fail(&format!("bindgen failed on src/sim/rtl/ffi/shim.h: {e}")),
        Err(_) => fail("libclang not found (bindgen needs it): run `bash scripts/setup.sh` (installs libclang-dev)"),
    }
}

/// The CPU harness variants for the Rust side.
fn variants(out: &Path) {
    let mut s = String::from("/// (scratch-pad bytes, hwbuild, interrupt_vector) of each verilated CPU harness.\n");
    s.push_str(&format!("pub const CPU_VARIANTS: [(u32, u8, u16); {}] = {:?};\n", CPU_VARIANTS.len(), CPU_VARIANTS));
    fs::write(out.join("variants.rs"), s).unwrap_or_else(|e| fail(&format!("{e}")));
}
