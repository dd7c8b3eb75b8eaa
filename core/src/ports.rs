//! BotSim 2.0's world_if ports (spec/botsim.md §8.2), under the names `rtl/world_if.v` and
//! `rtl/bot_pgm.psm` give them. world_if decodes `port_id[3:0]`: the numbers alias every 16.
//! A test checks these against both files.

/// Read: MotCtl_in.
pub const PRD_MOTCTL_IN: u8 = 0x0;
/// Write: the LocX holding register.
pub const PWR_LOCX: u8 = 0x1;
/// Write: the LocY holding register.
pub const PWR_LOCY: u8 = 0x2;
/// Write: the BotInfo holding register.
pub const PWR_BOTINFO: u8 = 0x3;
/// Write: the Sensors holding register.
pub const PWR_SENSORS: u8 = 0x4;
/// Write: the LMDist holding register.
pub const PWR_LMDIST: u8 = 0x5;
/// Write: the RMDist holding register.
pub const PWR_RMDIST: u8 = 0x6;
/// Read/write: MapX, the map column.
pub const PWR_COLADR: u8 = 0x8;
/// Read/write: MapY, the map row.
pub const PWR_ROWADR: u8 = 0x9;
/// Read: the map value at (MapX, MapY).
pub const PRD_LOCINFO: u8 = 0xA;
/// Write: toggle load_sys_regs (written twice: LocX/LocY/Sensors/BotInfo load together).
pub const PRW_LOADREGS: u8 = 0xC;
/// Write: toggle load_dist_regs.
pub const PRW_LDMOTDIST: u8 = 0xD;
/// Write: toggle upd_sysregs (written twice: the 2-clock pulse).
pub const PRW_UPDSYSREGS: u8 = 0xE;

/// Every port with its name, in the order above.
pub const ALL: [(&str, u8); 13] = [
    ("PRD_MOTCTL_IN", PRD_MOTCTL_IN),
    ("PWR_LOCX", PWR_LOCX),
    ("PWR_LOCY", PWR_LOCY),
    ("PWR_BOTINFO", PWR_BOTINFO),
    ("PWR_SENSORS", PWR_SENSORS),
    ("PWR_LMDIST", PWR_LMDIST),
    ("PWR_RMDIST", PWR_RMDIST),
    ("PWR_COLADR", PWR_COLADR),
    ("PWR_ROWADR", PWR_ROWADR),
    ("PRD_LOCINFO", PRD_LOCINFO),
    ("PRW_LOADREGS", PRW_LOADREGS),
    ("PRW_LDMOTDIST", PRW_LDMOTDIST),
    ("PRW_UPDSYSREGS", PRW_UPDSYSREGS),
];

#[cfg(test)]
mod tests {
    use super::ALL;

    /// The hex value written right after the first `key` in `text` (`= 4'hX` or `, 0X`).
    fn value_after(text: &str, key: &str) -> Option<u8> {
        let rest = &text[text.find(key)? + key.len()..];
        let digits: String = rest
            .trim_start_matches([' ', '=', ','])
            .trim_start_matches("4'h")
            .chars()
            .take_while(|c| c.is_ascii_hexdigit())
            .collect();
        u8::from_str_radix(&digits, 16).ok()
    }

    #[test]
    fn the_same_numbers_as_world_if_v_and_bot_pgm_psm() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let world_if = std::fs::read_to_string(root.join("rtl/world_if.v")).unwrap();
        let firmware = std::fs::read_to_string(root.join("rtl/bot_pgm.psm")).unwrap();
        for (name, port) in ALL {
            assert_eq!(value_after(&world_if, &format!("{name} ")), Some(port), "{name} in world_if.v");
            assert_eq!(value_after(&firmware, &format!("CONSTANT {name},")), Some(port), "{name} in bot_pgm.psm");
        }
    }
}
