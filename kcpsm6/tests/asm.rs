//! Assembler golden tests: expected words are computed by hand from the opcode table (§1.2).

use std::path::Path;

use kcpsm6::asm::{assemble_file, assemble_source, assemble_str, Options, RomSize, SymbolValue};

fn words(src: &str) -> Vec<u32> {
    let p = assemble_str(src).unwrap_or_else(|e| panic!("{e}"));
    let n = p.last_address().map_or(0, |a| a as usize + 1);
    p.image.words[..n].to_vec()
}

fn errors(src: &str) -> Vec<String> {
    errors_with(src, &Options::default())
}

fn errors_with(src: &str, opts: &Options) -> Vec<String> {
    match assemble_source(Path::new("t.psm"), src, opts) {
        Ok(_) => vec![],
        Err(d) => d.errors().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn every_instruction_form() {
    let src = "
        LOAD s1, s2
        LOAD s1, 7B
        STAR s1, s2
        STAR s1, 7B
        AND sA, sB
        OR sA, 0F
        XOR sA, FF
        ADD sF, s0
        ADDCY sF, 01
        SUB s3, s4
        SUBCY s3, 10
        TEST s5, 80
        TESTCY s5, s6
        COMPARE s7, 33
        COMPARECY s7, s8
        SL0 s9
        SL1 s9
        SLX s9
        SLA s9
        RL s9
        SR0 s9
        SR1 s9
        SRX s9
        SRA s9
        RR s9
        HWBUILD s2
        REGBANK A
        REGBANK B
        INPUT s0, (s1)
        INPUT s0, 3C
        OUTPUT s0, (s1)
        OUTPUT s0, 3C
        OUTPUTK 5A, 7
        STORE s2, (s3)
        STORE s2, 3F
        FETCH s2, (s3)
        FETCH s2, 3F
        DISABLE INTERRUPT
        ENABLE INTERRUPT
        RETURNI DISABLE
        RETURNI ENABLE
        JUMP 123
        JUMP Z, 123
        JUMP NZ, 123
        JUMP C, 123
        JUMP NC, 123
        JUMP@ (s4, s5)
        CALL 456
        CALL Z, 456
        CALL NZ, 456
        CALL C, 456
        CALL NC, 456
        CALL@ (s4, s5)
        RETURN
        RETURN Z
        RETURN NZ
        RETURN C
        RETURN NC
        LOAD&RETURN s6, 41
    ";
    let expect = [
        0x00120, 0x0117B, 0x16120, 0x1717B, 0x02AB0, 0x05A0F, 0x07AFF, 0x10F00, 0x13F01, 0x18340, 0x1B310, 0x0D580,
        0x0E560, 0x1D733, 0x1E780, 0x14906, 0x14907, 0x14904, 0x14900, 0x14902, 0x1490E, 0x1490F, 0x1490A, 0x14908,
        0x1490C, 0x14280, 0x37000, 0x37001, 0x08010, 0x0903C, 0x2C010, 0x2D03C, 0x2B5A7, 0x2E230, 0x2F23F, 0x0A230,
        0x0B23F, 0x28000, 0x28001, 0x29000, 0x29001, 0x22123, 0x32123, 0x36123, 0x3A123, 0x3E123, 0x26450, 0x20456,
        0x30456, 0x34456, 0x38456, 0x3C456, 0x24450, 0x25000, 0x31000, 0x35000, 0x39000, 0x3D000, 0x21641,
    ];
    assert_eq!(words(src), expect);
}

#[test]
fn case_rules() {
    // Mnemonics, registers, conditions and hex digits in any case; user names case-sensitive.
    assert_eq!(words("load S1, 7b\njump nz, 00a\nregbank b\nenable interrupt\n"), [0x0117B, 0x3600A, 0x37001, 0x28001]);
    assert_eq!(words("Loop: JUMP loop\nloop: JUMP Loop\n"), [0x22001, 0x22000]);
    assert!(errors("x: JUMP X\n")[0].contains("undefined label 'X'"));
}

#[test]
fn number_forms() {
    assert_eq!(
        words("LOAD s0, 123'd\nLOAD s0, 10100011'b\nLOAD s0, \"A\"\nLOAD s0, \";\"\nLOAD s0, \"\"\"\n"),
        [0x0107B, 0x010A3, 0x01041, 0x0103B, 0x01022]
    );
    assert_eq!(
        words("JUMP 4095'd\nJUMP 000000000011'b\nOUTPUTK 00, 1111'b\nOUTPUTK 00, 12'd\n"),
        [0x22FFF, 0x22003, 0x2B00F, 0x2B00C]
    );
    let e = errors("LOAD s0, 7\nLOAD s0, 123\nJUMP 12\nLOAD s0, 256'd\nLOAD s0, 1010'b\nOUTPUTK 00, 10\n");
    assert_eq!(
        e,
        [
            "t.psm:1:10: error: hex value '7' must have exactly 2 digits",
            "t.psm:2:10: error: hex value '123' must have exactly 2 digits",
            "t.psm:3:6: error: hex value '12' must have exactly 3 digits",
            "t.psm:4:10: error: decimal value '256'd' is out of range 0'd-255'd",
            "t.psm:5:10: error: binary value '1010'b' must have exactly 8 digits",
            "t.psm:6:13: error: hex value '10' must have exactly 1 digit",
        ]
    );
}

#[test]
fn constants_are_global_and_inverted_with_tilde() {
    let src = "
        LOAD s0, mask      ; used before its definition
        AND s0, ~mask
        OUTPUT s0, port
        OUTPUTK mask, kport
        CONSTANT mask, 0F
        CONSTANT port, 20'd
        CONSTANT kport, 0C
        CONSTANT letter, \"Z\"
        LOAD s1, letter
    ";
    assert_eq!(words(src), [0x0100F, 0x030F0, 0x2D014, 0x2B0FC, 0x0115A]);
    assert!(errors("CONSTANT big, 10\nOUTPUTK 00, big\n")[0].contains("OUTPUTK port must be 0-F"));
}

#[test]
fn predefined_constants_and_strings() {
    assert_eq!(words("LOAD s0, CR\nLOAD s1, ESC\nLOAD s2, ST\nLOAD s3, DCS\n"), [0x0100D, 0x0111B, 0x0129C, 0x01390]);
    assert_eq!(words("OUTPUTK KCPSM6_version$, 0\n"), [0x2B760, 0x2B320, 0x2B2E0, 0x2B370, 0x2B300]);
    let opts = Options { timestamp: 1_413_035_130, ..Options::default() }; // 11 Oct 2014 13:45:30
    let p = assemble_source(
        Path::new("t.psm"),
        "LOAD s0, timestamp_hours\nLOAD s1, datestamp_year\nLOAD s2, datestamp_month\nLOAD&RETURN s3, datestamp$\n",
        &opts,
    )
    .unwrap();
    assert_eq!(&p.image.words[..3], &[0x0100D, 0x0110E, 0x0120A]);
    let date: Vec<u8> = p.image.words[3..14].iter().map(|w| *w as u8).collect();
    assert_eq!(date, b"11 Oct 2014");
}

#[test]
fn namereg_is_sequential() {
    let src = "
        LOAD s5, 01
        NAMEREG s5, count
        ADD count, 01
        NAMEREG count, total
        ADD total, 02
        NAMEREG total, s5
        ADD s5, 03
    ";
    assert_eq!(words(src), [0x01501, 0x11501, 0x11502, 0x11503]);
    let e = errors("NAMEREG s5, count\nADD s5, 01\nNAMEREG count, total\nADD count, 01\n");
    assert_eq!(
        e,
        [
            "t.psm:2:5: error: register 's5' was renamed 'count' by NAMEREG",
            "t.psm:4:5: error: expected a register, found 'count'",
        ]
    );
    // STAR's first operand addresses the other bank: only default names.
    assert_eq!(words("NAMEREG s1, x\nSTAR s1, x\n"), [0x16110]);
    assert!(errors("NAMEREG s1, x\nSTAR x, 01\n")[0].contains("STAR needs a default register name"));
}

#[test]
fn address_labels_upper_lower_and_default_jump() {
    let src = "
        JUMP start
        ADDRESS 100
start:  LOAD s0, start'upper
        LOAD s1, start'lower
        ADDRESS 2FE
        LOAD s2, 300'd'lower_is_not_a_thing
    ";
    assert!(errors(src)[0].contains("t.psm:7:"));
    let src = "
        JUMP start
        ADDRESS 123
start:  LOAD s0, start'upper
        LOAD s1, start'lower
        DEFAULT_JUMP panic
        ADDRESS 3FF
panic:  JUMP panic
    ";
    let p = assemble_str(src).unwrap();
    assert_eq!(p.image.words[0], 0x22123);
    assert_eq!(p.image.words[0x123], 0x01001);
    assert_eq!(p.image.words[0x124], 0x01123);
    assert_eq!(p.image.words[0x3FF], 0x223FF);
    // Unused locations hold JUMP panic.
    assert_eq!(p.image.words[1], 0x223FF);
    assert_eq!(p.image.words[0xFFF], 0x223FF);
    assert_eq!(p.default_jump, Some(0x3FF));
    assert!(
        errors("ADDRESS 010\nLOAD s0, 00\nADDRESS 005\n")[0].contains("ADDRESS 005 is below the current address 011")
    );
}

#[test]
fn strings_and_tables_expand() {
    let src = "
        STRING hi$, \"Hi!\"
        TABLE t#, [01, FF, 7B]
        TABLE tens#, [10, 255]'d
        TABLE bin#, [00000001, 10000000]'b
        OUTPUTK hi$, 3
        LOAD&RETURN s4, t#
        LOAD&RETURN s4, tens#
        OUTPUTK bin#, F
    ";
    assert_eq!(words(src), [0x2B483, 0x2B693, 0x2B213, 0x21401, 0x214FF, 0x2147B, 0x2140A, 0x214FF, 0x2B01F, 0x2B80F]);
    // The STRING text runs from the first to the last quote, semicolons included.
    let p = assemble_str("STRING s$, \"a;\"b\" ; note\nOUTPUTK s$, 0\n").unwrap();
    let text: Vec<u8> = p.image.words[..4].iter().map(|w| (w >> 4) as u8).collect();
    assert_eq!(text, b"a;\"b");
}

#[test]
fn inst_writes_raw_words() {
    assert_eq!(words("INST 2EA7B\nINST 3FFFF\nINST 00000\n"), [0x2EA7B, 0x3FFFF, 0x00000]);
    assert!(errors("INST 40000\n")[0].contains("above 3FFFF"));
    assert!(errors("INST 1234\n")[0].contains("exactly 5 digits"));
}

#[test]
fn include_is_relative_to_the_including_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("lib")).unwrap();
    std::fs::write(dir.path().join("main.psm"), "INCLUDE \"lib/a.psm\"\nJUMP sub_a\n").unwrap();
    std::fs::write(dir.path().join("lib/a.psm"), "INCLUDE \"b.psm\"\nsub_a: LOAD s0, kb\nRETURN\n").unwrap();
    std::fs::write(dir.path().join("lib/b.psm"), "CONSTANT kb, 42\n").unwrap();
    let p = assemble_file(&dir.path().join("main.psm"), &Options::default()).unwrap();
    assert_eq!(&p.image.words[..3], &[0x01042, 0x25000, 0x22000]);
    assert_eq!(p.files.len(), 3);

    std::fs::write(dir.path().join("loop.psm"), "INCLUDE \"loop.psm\"\n").unwrap();
    let e = assemble_file(&dir.path().join("loop.psm"), &Options::default()).unwrap_err().to_string();
    assert!(e.contains("loop.psm:1:9: error: INCLUDE \"loop.psm\" includes itself"), "{e}");
    let e = assemble_file(&dir.path().join("missing.psm"), &Options::default()).unwrap_err().to_string();
    assert!(e.ends_with("missing.psm: error: cannot read file: no such file or directory"), "{e}");
}

#[test]
fn defines_override_constants_and_psm_environment() {
    let src =
        "CONSTANT threshold, 0F\nCONSTANT delay, %PSM_delay\nLOAD s0, threshold\nLOAD s1, delay\nLOAD s2, extra\n";
    let opts = Options {
        defines: vec![("threshold".into(), "4'd".into()), ("extra".into(), "\"x\"".into())],
        env: vec![("psm_DELAY".into(), "18".into())],
        ..Options::default()
    };
    let p = assemble_source(Path::new("t.psm"), src, &opts).unwrap();
    assert_eq!(&p.image.words[..3], &[0x01004, 0x01118, 0x01278]);
    assert_eq!(p.symbol("threshold"), Some(&SymbolValue::Constant(4)));
    let e = errors_with(src, &Options::default());
    assert_eq!(e[0], "t.psm:2:17: error: environment value 'PSM_delay' is not set");
    let bad = Options { defines: vec![("threshold".into(), "0x0F".into())], ..Options::default() };
    assert!(
        errors_with("CONSTANT threshold, 0F\nLOAD s0, threshold\n", &bad)[0].starts_with("-D threshold=0x0F: error:")
    );
}

#[test]
fn every_error_of_a_run_is_reported_in_order() {
    let src = "
start:  LOAD s0, 01
start:  LOAD s1, 02
        FOO s0, 01
        LOAD s2, undefined_c
        JUMP undefined_l
        CONSTANT BAD, 01
        LOAD s0
        OUTPUT s0, s1
    ";
    let e = errors(src);
    assert_eq!(
        e,
        [
            "t.psm:3:1: error: 'start' is already defined (first defined at t.psm:2:1)",
            "t.psm:4:9: error: unknown instruction or directive 'FOO'",
            "t.psm:5:18: error: undefined constant 'undefined_c'",
            "t.psm:6:14: error: undefined label 'undefined_l'",
            "t.psm:7:18: error: 'BAD' is not a valid name: it reads as a hex value",
            "t.psm:8:9: error: LOAD takes two operands: a register and a register or constant",
            "t.psm:9:20: error: write a register port or address as '(s1)'",
        ]
    );
}

#[test]
fn program_past_fff_or_past_the_chosen_rom_size() {
    assert!(errors("ADDRESS FFF\nLOAD s0, 00\nLOAD s0, 01\n")[0]
        .contains("t.psm:3:1: error: program runs past the last address FFF"));
    // Only comments and constants may follow an instruction at FFF.
    assert!(errors("ADDRESS FFF\nLOAD s0, 00\nCONSTANT x, 01\n; fine\n").is_empty());
    assert!(errors("ADDRESS FFF\nLOAD s0, 00\nlate:\n")[0].contains("past the last address FFF"));
    let k1 = Options { rom_size: Some(RomSize::K1), ..Options::default() };
    assert_eq!(
        errors_with("ADDRESS 3FF\nLOAD s0, 00\nLOAD s0, 01\n", &k1),
        ["t.psm:3:1: error: program runs past the 1024-word ROM (last address 3FF)"]
    );
    let k2 = Options { rom_size: Some(RomSize::K2), ..Options::default() };
    assert!(errors_with("ADDRESS 7FF\nSTRING s$, \"ab\"\nOUTPUTK s$, 0\n", &k2)[0].contains("2048-word ROM"));
}

#[test]
fn warnings_are_not_fatal() {
    let p = assemble_source(Path::new("t.psm"), "CONSTANT unused, 01\nLOAD s0, 00\n", &Options::default()).unwrap();
    assert_eq!(p.warnings.len(), 1);
    assert_eq!(p.warnings[0].to_string(), "t.psm:1:10: warning: constant 'unused' is never used");
}

#[test]
fn hostile_inputs_do_not_panic() {
    for src in [
        "",
        "\0",
        ":",
        "::",
        "a:b:c:",
        "LOAD",
        "LOAD ,",
        "LOAD s0,,",
        "JUMP@",
        "JUMP@ (",
        "JUMP@ (s0",
        "CALL@ (s0 s1)",
        "TABLE t#, [",
        "TABLE t#, []",
        "TABLE t#, [1,]",
        "STRING",
        "STRING x$, \"",
        "\"",
        "\"\"",
        "INCLUDE",
        "INCLUDE x",
        "INCLUDE \"\"",
        "ADDRESS",
        "ADDRESS FFFF",
        "NAMEREG",
        "NAMEREG s0",
        "NAMEREG s0, s1",
        "CONSTANT",
        "CONSTANT x",
        "CONSTANT x, ",
        "LOAD s0, ~",
        "LOAD s0, ''",
        "LOAD s0, x'upper",
        "LOAD s0, 'd",
        "OUTPUTK",
        "RETURN Q",
        "REGBANK C",
        "INST",
        "DEFAULT_JUMP",
        "DEFAULT_JUMP 000\nDEFAULT_JUMP 000",
        "é: LOAD s0, 00",
        "LOAD s0, \"é\"",
        "TABLE t#, [\"a\", 02]'d",
        "%",
        "LOAD&RETURN s0, nope$",
        "OUTPUTK nope#, 0",
    ] {
        let _ = assemble_str(src);
    }
}

// ---- what kcpsm6.exe accepted in real programs (issue: two of 29 public programs) ------------

#[test]
fn windows_include_paths_with_back_slashes() {
    // `INCLUDE ".\interfaces\ports.psm"` and `..\`: kcpsm6.exe ran on Windows.
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("src/interfaces")).unwrap();
    std::fs::write(dir.path().join("src/main.psm"), "INCLUDE \".\\interfaces\\ports.psm\"\nOUTPUT s0, leds\n").unwrap();
    std::fs::write(dir.path().join("src/interfaces/ports.psm"), "INCLUDE \"..\\..\\common.psm\"\nCONSTANT leds, 02\n")
        .unwrap();
    std::fs::write(dir.path().join("common.psm"), "LOAD s0, 5A\n").unwrap();
    let p = assemble_file(&dir.path().join("src/main.psm"), &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&p.image.words[..2], &[0x0105A, 0x2D002]);
    assert_eq!(p.files.len(), 3);
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn include_names_that_differ_only_in_case_are_found_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("Lib")).unwrap();
    std::fs::write(dir.path().join("main.psm"), "INCLUDE \"lib\\PORTS.psm\"\nOUTPUT s0, leds\n").unwrap();
    std::fs::write(dir.path().join("Lib/ports.psm"), "CONSTANT leds, 02\n").unwrap();
    let p = assemble_file(&dir.path().join("main.psm"), &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.image.words[0], 0x2D002);
    let w: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(w.len(), 1);
    assert!(w[0].contains("main.psm:1:9: warning: INCLUDE \"lib\\PORTS.psm\" found as"), "{w:?}");
    assert!(w[0].ends_with("Lib/ports.psm' (the names differ in case, which Windows ignores)"), "{w:?}");
}

#[test]
fn a_trailing_comma_after_a_condition_is_ignored_with_a_warning() {
    let src = "loop: RETURN NZ, ;comment\nJUMP NZ, loop,\nCALL C, loop, ; x\nRETURN C,\n";
    let p = assemble_source(Path::new("t.psm"), src, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&p.image.words[..4], &[0x35000, 0x36000, 0x38000, 0x39000]);
    let w: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(
        w,
        [
            "t.psm:1:16: warning: trailing ',' ignored",
            "t.psm:2:14: warning: trailing ',' ignored",
            "t.psm:3:13: warning: trailing ',' ignored",
            "t.psm:4:9: warning: trailing ',' ignored",
        ]
    );
    // A comma with nothing before it is still an error.
    assert_eq!(errors("RETURN ,\n"), ["t.psm:1:8: error: missing operand before ','"]);
}

#[test]
fn predefined_strings_and_stamps_can_be_set_with_d() {
    // Rebuild an old ROM byte for byte: the date, time and version it was assembled with.
    let src = "LOAD&RETURN s0, datestamp$\nLOAD&RETURN s1, timestamp$\nLOAD&RETURN s2, KCPSM6_version$\n\
               LOAD s3, datestamp_year\nLOAD s4, timestamp_hours\n";
    let opts = Options {
        defines: vec![
            ("datestamp$".into(), "11 Oct 2014".into()),
            ("timestamp$".into(), "\"13:45:30\"".into()),
            ("KCPSM6_version$".into(), "v2.63".into()),
            ("datestamp_year".into(), "14'd".into()),
            ("timestamp_hours".into(), "13'd".into()),
        ],
        timestamp: 0,
        ..Options::default()
    };
    let p = assemble_source(Path::new("t.psm"), src, &opts).unwrap_or_else(|e| panic!("{e}"));
    let bytes = |r: std::ops::Range<usize>| p.image.words[r].iter().map(|w| *w as u8).collect::<Vec<u8>>();
    assert_eq!(bytes(0..11), b"11 Oct 2014");
    assert_eq!(bytes(11..19), b"13:45:30");
    assert_eq!(bytes(19..24), b"v2.63");
    assert_eq!(&p.image.words[24..26], &[0x0130E, 0x0140D]);
    let bad = Options { defines: vec![("x$".into(), "caf\u{e9}".into())], ..Options::default() };
    assert_eq!(
        errors_with("LOAD s0, 00\n", &bad),
        ["-D x$=caf\u{e9}: error: STRING text may hold only printable ASCII, found '\\u{e9}'"]
    );
    // A user's STRING can be overridden too.
    let user = Options { defines: vec![("s$".into(), "xy".into())], ..Options::default() };
    let p = assemble_source(Path::new("t.psm"), "STRING s$, \"a\"\nOUTPUTK s$, 0\n", &user).unwrap();
    assert_eq!(&p.image.words[..2], &[0x2B780, 0x2B790]);
}

#[test]
fn an_unreadable_include_is_reported_alone() {
    // The names it would have defined are not reported as undefined on top of it.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("main.psm"), "INCLUDE \"ports.psm\"\nOUTPUT s0, leds\nJUMP init\n").unwrap();
    let e = assemble_file(&dir.path().join("main.psm"), &Options::default()).unwrap_err();
    let lines: Vec<String> = e.0.iter().map(|d| d.to_string()).collect();
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains("main.psm:1:9: error: cannot read INCLUDE file"), "{lines:?}");
    assert!(lines[0].ends_with("ports.psm': no such file or directory"), "{lines:?}");
}

#[test]
fn leniencies_of_the_syntax_give_the_same_words() {
    // Case, spacing, comments and separators as the spec allows them (§4.1); each word by
    // hand from the opcode table. CR LF endings and trailing blanks included.
    let src = "; a comment line\r\n\
               \t; an indented one\r\n\
               \tload\tS0,7b\t\t; tabs; mnemonic, register and hex digits in any case\r\n\
               LOAD s1 ,  0F   \r\n\
               lbl:LOAD s2,s3\n\
               lbl2 :  ADD s2, 01\n\
               JUMP   NZ ,lbl\n\
               INPUT s4, ( s5 )\n\
               OUTPUT S4,(s5)\n\
               JUMP@ ( s6 ,s7 )\n\
               ENABLE   interrupt\n\
               returni Enable\n\
               REGBANK b\n\
               STORE s0, 3f\n\
               FETCH s0, 10'D\n\
               LOAD s0, 00001010'B\n\
               TEST s0, \";\"\n\
               LOAD s0, 01;no blank before the comment\n\
               RETURN NZ, ;a trailing comma\n\
               ADD sf, SA\n\
               \n   \n\
               stop: ; a label with only a comment\n\
               JUMP stop\n";
    let expect = [
        0x0107B, 0x0110F, 0x00230, 0x11201, 0x36002, 0x08450, 0x2C450, 0x26670, 0x28001, 0x29001, 0x37001, 0x2F03F,
        0x0B00A, 0x0100A, 0x0D03B, 0x01001, 0x35000, 0x10FA0, 0x22012,
    ];
    assert_eq!(words(src), expect);
}

#[test]
fn a_byte_order_mark_is_skipped_as_kcpsm6_skips_it() {
    // Windows editors begin a UTF-8 file with U+FEFF; the program is the same without it, and
    // an error on the first line keeps the column the editor shows.
    assert_eq!(words("\u{feff}start: LOAD s0, 01\nJUMP start\n"), words("start: LOAD s0, 01\nJUMP start\n"));
    let e = assemble_str("\u{feff}LOAD s0, 0G\n").unwrap_err().to_string();
    assert!(e.contains(":1:10:"), "{e}");
}
