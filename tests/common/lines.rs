//! The board's peripheral lines as `botsim board --lines` writes them, and decoders written
//! from spec board.md §7 (not from botsim's): each checks the timing the spec gives and fails
//! on a frame that breaks it.

/// The columns of `--lines`.
pub const RSTX: usize = 0;
pub const AMP_PWM: usize = 1;
pub const AMP_SD: usize = 2;
pub const RSRX: usize = 3;
pub const PS2_CLK: usize = 4;
pub const PS2_DATA: usize = 5;
pub const ACL_SCK: usize = 6;
pub const ACL_MOSI: usize = 7;
pub const ACL_MISO: usize = 8;
pub const ACL_SS: usize = 9;

/// The rows of a `--lines` file: (time in ps, the ten lines).
pub fn read(csv: &str) -> Vec<(u64, [bool; 10])> {
    let mut rows = csv.lines();
    assert_eq!(
        rows.next(),
        Some("time_ps,RsTx,ampPWM,ampSD,RsRx,PS2_CLK,PS2_DATA,aclSCK,aclMOSI,aclMISO,aclSS"),
        "the header"
    );
    rows.map(|r| {
        let mut f = r.split(',');
        let t = f.next().unwrap().parse().unwrap();
        let mut v = [false; 10];
        for (k, x) in f.enumerate() {
            v[k] = x == "1";
        }
        (t, v)
    })
    .collect()
}

/// One line's changes: (time, level), the first row's level at its time.
pub fn changes(rows: &[(u64, [bool; 10])], line: usize) -> Vec<(u64, bool)> {
    let mut out: Vec<(u64, bool)> = Vec::new();
    for &(t, v) in rows {
        if out.last().map_or(true, |&(_, l)| l != v[line]) {
            out.push((t, v[line]));
        }
    }
    out
}

/// The level of a line at `t` from its changes.
pub fn level_at(changes: &[(u64, bool)], t: u64) -> bool {
    changes.iter().take_while(|c| c.0 <= t).last().map_or(true, |c| c.1)
}

/// The bytes of a UART line (8N1 at `baud`). Every change within a frame must fall on a bit
/// boundary (within 1 % of a bit) and every stop bit must be 1, or this panics.
pub fn uart(changes: &[(u64, bool)], baud: u32) -> Vec<u8> {
    let bit = 1e12 / baud as f64;
    let mut out = Vec::new();
    let mut i = 0;
    while i < changes.len() {
        let (t0, level) = changes[i];
        if level {
            i += 1;
            continue;
        }
        let at = |k: f64| level_at(changes, t0 + (k * bit) as u64);
        assert!(!at(0.5), "a start bit at {t0} ps that does not last half a bit");
        let byte = (0..8).fold(0u8, |b, k| b | (at(k as f64 + 1.5) as u8) << k);
        assert!(at(9.5), "the frame at {t0} ps ({byte:02X}) has a stop bit 0");
        // Every change of the frame on a bit boundary.
        let end = t0 + (9.5 * bit) as u64;
        let mut j = i + 1;
        while j < changes.len() && changes[j].0 < end {
            let bits = (changes[j].0 - t0) as f64 / bit;
            assert!((bits - bits.round()).abs() < 0.01, "a change {bits:.3} bits into the frame at {t0} ps");
            j += 1;
        }
        out.push(byte);
        i = j;
    }
    out
}

/// The bytes of PS/2 device-to-host frames on the clock and data lines: the host reads data
/// at each falling clock edge; a frame is start 0, eight data bits least significant first,
/// odd parity, stop 1. The clock must run at 10-16.7 kHz (each half 25-55 us here: the
/// spec's 60-100 us period) while a frame is sent, the data must not change while the clock
/// is low, and every frame must be whole and well formed, or this panics.
pub fn ps2(clk: &[(u64, bool)], data: &[(u64, bool)]) -> Vec<u8> {
    let us = 1_000_000u64;
    let falls: Vec<u64> = clk.iter().filter(|c| !c.1).map(|c| c.0).collect();
    // The data does not change while the clock is low.
    for w in clk.windows(2) {
        if !w[0].1 {
            assert!(
                !data.iter().any(|d| d.0 > w[0].0 && d.0 < w[1].0),
                "PS2_DATA changed while PS2_CLK was low ({} to {} ps)",
                w[0].0,
                w[1].0
            );
            let low = w[1].0 - w[0].0;
            assert!((25 * us..=55 * us).contains(&low), "PS2_CLK low for {} us", low / us);
        }
    }
    let mut out = Vec::new();
    for frame in falls.chunks(11) {
        assert_eq!(frame.len(), 11, "a frame of {} clocks", frame.len());
        for w in frame.windows(2) {
            let period = w[1] - w[0];
            assert!((60 * us..=100 * us).contains(&period), "a PS/2 clock period of {} us", period / us);
        }
        let bits: Vec<bool> = frame.iter().map(|&t| level_at(data, t)).collect();
        assert!(!bits[0], "a frame at {} ps whose start bit is 1", frame[0]);
        assert!(bits[10], "a frame at {} ps whose stop bit is 0", frame[0]);
        assert_eq!(bits[1..10].iter().filter(|b| **b).count() % 2, 1, "a frame at {} ps with even parity", frame[0]);
        out.push((0..8).fold(0u8, |b, k| b | (bits[k + 1] as u8) << k));
    }
    out
}

/// The transactions on an SPI bus in mode 0 (spec board.md §7: the clock idles low, data is
/// sampled at its rising edge and changes while it is low, most significant bit first, a
/// transaction framed by the select low): (the select's fall, the bytes out, the bytes in).
/// A clock not low at the select's edges, a data line changing while the clock is high or at
/// its rising edge, or a transaction of part of a byte panics.
pub fn spi(rows: &[(u64, [bool; 10])]) -> Vec<(u64, Vec<u8>, Vec<u8>)> {
    let mut out = Vec::new();
    let mut prev = rows[0].1;
    let mut current: Option<(u64, Vec<bool>, Vec<bool>)> = None;
    for &(t, v) in &rows[1..] {
        let (sck, ss) = (v[ACL_SCK], v[ACL_SS]);
        if prev[ACL_SS] && !ss {
            assert!(!sck && !prev[ACL_SCK], "the select fell at {t} ps with the clock high");
            current = Some((t, Vec::new(), Vec::new()));
        }
        if let Some((t0, mosi, miso)) = &mut current {
            // The data lines hold while the clock is high (and at its rising edge).
            for line in [ACL_MOSI, ACL_MISO] {
                if v[line] != prev[line] {
                    assert!(
                        !sck,
                        "{} changed at {t} ps while the clock was high",
                        ["MOSI", "MISO"][(line == ACL_MISO) as usize]
                    );
                }
            }
            if sck && !prev[ACL_SCK] {
                mosi.push(v[ACL_MOSI]);
                miso.push(v[ACL_MISO]);
            }
            if !prev[ACL_SS] && ss {
                assert!(!sck, "the select rose at {t} ps with the clock high");
                assert_eq!(mosi.len() % 8, 0, "a transaction at {t0} ps of {} bits", mosi.len());
                let bytes = |bits: &[bool]| -> Vec<u8> {
                    bits.chunks(8).map(|c| c.iter().fold(0u8, |b, &x| b << 1 | x as u8)).collect()
                };
                out.push((*t0, bytes(mosi), bytes(miso)));
                current = None;
            }
        }
        prev = v;
    }
    out
}
