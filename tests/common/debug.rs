//! Checks shared by the tests of `botsim board` and `botsim run` that look inside a KCPSM6:
//! the source-level trace against the assembler's listing, and a waveform's debug signals
//! against the disassembler.
#![allow(dead_code)]

use std::path::Path;

/// (pc, file:line, instruction text) of every line of a `--cpu-trace` file.
pub fn trace_lines(file: &Path) -> Vec<(u16, String, String)> {
    std::fs::read_to_string(file)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            // cycle time pc where source instruction...
            let pc = u16::from_str_radix(f[2], 16).unwrap();
            let source = f[4].to_string();
            let instruction = l[l.find(&source).unwrap() + source.len()..].trim_start();
            let instruction = instruction.split("  ").next().unwrap().trim().to_string();
            (pc, source, instruction)
        })
        .collect()
}

/// Every line of a trace names the address's source line as the assembler's listing does, and
/// its instruction assembles to the word at that address; the profile beside it
/// (`<stem>.profile.txt`) has its table.
pub fn check_trace_against_listing(file: &Path, program: &kcpsm6::asm::Program, name: &str, at_least: usize) {
    let cpu = file.display();
    let lines = trace_lines(file);
    assert!(lines.len() > at_least, "{cpu}: {} lines", lines.len());
    let mut pcs = std::collections::BTreeSet::new();
    for (pc, source, instruction) in &lines {
        let listed = program.listing.iter().find(|l| l.address == Some(*pc) && l.word.is_some()).unwrap();
        assert_eq!(source, &format!("{name}:{}", listed.loc.line), "{cpu} at {pc:03X}");
        pcs.insert(*pc);
        if instruction.starts_with("(interrupt") {
            continue; // an interrupt entry: the instruction at pc was cancelled
        }
        // The instruction text assembles to the word at that address.
        let word =
            kcpsm6::asm::assemble_str(&format!("ADDRESS {pc:03X}\n{instruction}\n")).unwrap().image.words[*pc as usize];
        assert_eq!(word, program.image.words[*pc as usize], "{cpu} at {pc:03X}: {instruction}");
    }
    assert!(pcs.len() > 10, "{cpu}: only {} addresses traced", pcs.len());
    let stem = file.file_name().unwrap().to_string_lossy().replace(".trace.txt", "").replace(".txt", "");
    let profile = std::fs::read_to_string(file.with_file_name(format!("{stem}.profile.txt"))).unwrap();
    assert!(profile.lines().any(|l| l.starts_with("label")), "{profile}");
}

/// A VCD vector as a number and as text (a character a byte).
pub fn vector(v: &vcd::Vector) -> (u64, String) {
    let bits: Vec<bool> = v.into_iter().map(|b| b == vcd::Value::V1).collect();
    let n = bits.iter().fold(0u64, |a, b| a << 1 | *b as u64);
    let mut text = String::new();
    let pad = (8 - bits.len() % 8) % 8;
    let all: Vec<bool> = std::iter::repeat(false).take(pad).chain(bits).collect();
    for c in all.chunks(8) {
        text.push(c.iter().fold(0u8, |a, b| a << 1 | *b as u8) as char);
    }
    (n, text)
}

/// In a board waveform, every KCPSM6's `kcpsm6_opcode` is the disassembly of the word on its
/// `instruction` port at every time stamp; returns how many changes were checked per CPU.
pub fn check_debug_signals(vcd_path: &Path, cpus: &[&[&str]]) -> Vec<usize> {
    let f = std::fs::File::open(vcd_path).unwrap();
    let mut parser = vcd::Parser::new(std::io::BufReader::new(f));
    let header = parser.parse_header().unwrap();
    let code = |scope: &[&str], name: &str| {
        let mut path: Vec<&str> = scope.to_vec();
        path.push(name);
        header.find_var(&path).unwrap_or_else(|| panic!("{path:?} in the waveform")).code
    };
    let ids: Vec<_> =
        cpus.iter().map(|s| (code(s, "instruction"), code(s, "kcpsm6_opcode"), code(s, "kcpsm6_status"))).collect();
    let mut words = vec![0u32; cpus.len()];
    let mut texts = vec![String::new(); cpus.len()];
    let mut checked = vec![0; cpus.len()];
    let mut status0 = vec![None; cpus.len()];
    let check = |words: &[u32], texts: &[String], checked: &mut [usize]| {
        for i in 0..words.len() {
            let want = kcpsm6::disasm::disassemble_word(words[i]);
            assert_eq!(texts[i].trim_end(), want, "CPU {:?}: word {:05X}", cpus[i], words[i]);
            checked[i] += 1;
        }
    };
    let mut started = false;
    for cmd in parser {
        match cmd.unwrap() {
            vcd::Command::Timestamp(_) => {
                if started {
                    check(&words, &texts, &mut checked);
                }
                started = true;
            }
            vcd::Command::ChangeVector(c, v) => {
                for (i, (instr, text, status)) in ids.iter().enumerate() {
                    if c == *instr {
                        words[i] = vector(&v).0 as u32;
                    } else if c == *text {
                        texts[i] = vector(&v).1;
                    } else if c == *status && status0[i].is_none() {
                        status0[i] = Some(vector(&v).1);
                    }
                }
            }
            _ => {}
        }
    }
    for s in status0 {
        assert_eq!(s.as_deref(), Some("A,NZ,NC,ID,Reset"), "the status at power-up");
    }
    checked
}

/// The names of each signal of a VCD header, as GTKWave gives them (`TOP.a.b.sig[7:0]`).
pub fn vcd_names(header: &vcd::Header) -> std::collections::HashMap<vcd::IdCode, Vec<String>> {
    fn walk(items: &[vcd::ScopeItem], path: &str, names: &mut std::collections::HashMap<vcd::IdCode, Vec<String>>) {
        for item in items {
            match item {
                vcd::ScopeItem::Scope(s) => walk(&s.items, &format!("{path}{}.", s.identifier), names),
                vcd::ScopeItem::Var(v) => {
                    let range = match v.index {
                        Some(vcd::ReferenceIndex::Range(a, b)) => format!("[{a}:{b}]"),
                        Some(vcd::ReferenceIndex::BitSelect(a)) => format!("[{a}]"),
                        None => String::new(),
                    };
                    names.entry(v.code).or_default().push(format!("{path}{}{range}", v.reference));
                }
                _ => {}
            }
        }
    }
    let mut names = Default::default();
    walk(&header.items, "", &mut names);
    names
}

/// Every signal's full name in a VCD.
pub fn vcd_signals(path: &Path) -> std::collections::BTreeSet<String> {
    let mut parser = vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    vcd_names(&parser.parse_header().unwrap()).into_values().flatten().collect()
}
