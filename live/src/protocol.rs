//! The messages between a live board and its pages: JSON text messages over one WebSocket,
//! and the VGA frames as binary messages (PNG). docs/LIVE.md has the table.
//!
//! ```
//! use botsim_live::protocol::{Button, Command};
//! assert_eq!(Command::parse(r#"{"type":"switch","index":3,"on":true}"#), Ok(vec![Command::Switch { index: 3, on: true }]));
//! // ViDBo's shape: several pins in one message (taken in the order of their names).
//! assert_eq!(
//!     Command::parse(r#"{"gpio":{"SW0":true,"BTNC":false}}"#),
//!     Ok(vec![Command::Button { button: Button::C, down: false }, Command::Switch { index: 0, on: true }])
//! );
//! assert!(Command::parse("{\"type\":\"switch\",\"index\":16,\"on\":true}").unwrap_err().contains("0 to 15"));
//! ```

use serde_json::{json, Value};

/// A push button of the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    C,
    U,
    D,
    L,
    R,
    /// The CPU reset button (active low on the board: pressed pulls it low).
    CpuReset,
}

impl Button {
    /// Every button, in the order of the bits of [`BoardView::buttons`].
    pub const ALL: [Button; 6] = [Button::C, Button::U, Button::D, Button::L, Button::R, Button::CpuReset];

    /// Its name in botsim's stimulus files and options (`btnC`, `btnCpuReset`).
    pub fn name(self) -> &'static str {
        match self {
            Button::C => "btnC",
            Button::U => "btnU",
            Button::D => "btnD",
            Button::L => "btnL",
            Button::R => "btnR",
            Button::CpuReset => "btnCpuReset",
        }
    }

    /// Its name in ViDBo's messages (`BTNC`, `CPU_RESET`).
    pub fn vidbo_name(self) -> &'static str {
        match self {
            Button::C => "BTNC",
            Button::U => "BTNU",
            Button::D => "BTND",
            Button::L => "BTNL",
            Button::R => "BTNR",
            Button::CpuReset => "CPU_RESET",
        }
    }

    /// From either name, in any case.
    pub fn from_name(name: &str) -> Option<Button> {
        Button::ALL
            .into_iter()
            .find(|b| b.name().eq_ignore_ascii_case(name) || b.vidbo_name().eq_ignore_ascii_case(name))
    }

    /// Its bit in [`BoardView::buttons`].
    pub fn bit(self) -> u8 {
        1 << Button::ALL.iter().position(|b| *b == self).unwrap_or(0)
    }
}

/// What a page asks of the board.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Switch `index` (0-15) on or off.
    Switch {
        index: u8,
        on: bool,
    },
    /// All sixteen switches at once.
    Switches(u16),
    /// A button pressed (`down`) or released.
    Button {
        button: Button,
        down: bool,
    },
    /// The bot alone (`botsim run --live`): MotCtl_in from the next sample on.
    Motors(u8),
    /// Run (as fast as the speed allows).
    Run,
    Pause,
    /// Run to the bot's next sample, then pause.
    Step,
    /// Run at `Some(factor)` times real time, or `None`: as fast as it can.
    Speed(Option<f64>),
    /// Send back the inputs so far as a stimulus file (`--stimulus`).
    Save,
    /// End the run (as Ctrl-C does).
    Stop,
    /// A key of the keyboard pressed (`down`) or released, named as the browser's
    /// `KeyboardEvent.code` names it (`KeyA`, `ArrowUp`).
    Key {
        code: String,
        down: bool,
    },
    /// Text sent to the design's USB-UART (its UTF-8 bytes).
    Uart(Vec<u8>),
    /// The board's tilt, in g on x, y and z (flat: 0, 0, 1).
    Tilt([f64; 3]),
}

impl Command {
    /// The commands in one text message: botsim's (`{"type": ...}`) or ViDBo's
    /// (`{"gpio": {"SW3": true}}`, possibly several pins); an error says what is wrong.
    pub fn parse(text: &str) -> Result<Vec<Command>, String> {
        let v: Value = serde_json::from_str(text).map_err(|e| format!("not JSON: {e}"))?;
        let obj = v.as_object().ok_or("expected a JSON object")?;
        if let Some(gpio) = obj.get("gpio") {
            let pins = gpio.as_object().ok_or("`gpio`: expected an object of pins")?;
            return pins.iter().map(|(pin, value)| vidbo_pin(pin, value)).collect();
        }
        let kind = obj.get("type").and_then(Value::as_str).ok_or("expected a `type` (or ViDBo's `gpio`)")?;
        let flag = |name: &str| -> Result<bool, String> {
            match obj.get(name) {
                Some(Value::Bool(b)) => Ok(*b),
                Some(Value::Number(n)) if n.as_u64().is_some_and(|n| n <= 1) => Ok(n.as_u64() == Some(1)),
                _ => Err(format!("`{kind}`: `{name}` must be true or false")),
            }
        };
        let one = match kind {
            "switch" => {
                let index = obj.get("index").and_then(Value::as_u64).filter(|i| *i < 16);
                let index = index.ok_or("`switch`: `index` must be a switch number, 0 to 15")? as u8;
                Command::Switch { index, on: flag("on")? }
            }
            "switches" => {
                let value = word(obj.get("value"), 0xFFFF);
                Command::Switches(value.ok_or("`switches`: `value` must be 0 to 65535 or up to four hex digits")? as u16)
            }
            "button" => {
                let name = obj.get("name").and_then(Value::as_str).unwrap_or("");
                let button = Button::from_name(name).ok_or_else(|| {
                    format!("`button`: no button `{name}` (btnC, btnU, btnD, btnL, btnR, btnCpuReset)")
                })?;
                Command::Button { button, down: flag("down")? }
            }
            "motors" => {
                let value = word(obj.get("value"), 0xFF);
                Command::Motors(value.ok_or("`motors`: `value` must be 0 to 255 or two hex digits")? as u8)
            }
            "key" => {
                let code = obj.get("code").and_then(Value::as_str).filter(|c| !c.is_empty() && c.len() <= 32);
                let code = code.ok_or("`key`: `code` must name a key (as KeyboardEvent.code does: KeyA, Enter)")?;
                Command::Key { code: code.to_string(), down: flag("down")? }
            }
            "uart" => {
                let text = obj.get("text").and_then(Value::as_str).ok_or("`uart`: `text` must be a string")?;
                if text.len() > 4096 {
                    return Err("`uart`: at most 4096 bytes at a time".into());
                }
                Command::Uart(text.as_bytes().to_vec())
            }
            "tilt" => {
                let g = |axis: &str| {
                    obj.get(axis)
                        .and_then(Value::as_f64)
                        .filter(|g| g.is_finite() && g.abs() <= 8.0)
                        .ok_or_else(|| format!("`tilt`: `{axis}` must be a number of g, within +-8"))
                };
                Command::Tilt([g("x")?, g("y")?, g("z")?])
            }
            "run" => Command::Run,
            "pause" => Command::Pause,
            "step" => Command::Step,
            "save" => Command::Save,
            "stop" => Command::Stop,
            "speed" => match obj.get("factor") {
                None | Some(Value::Null) => Command::Speed(None),
                Some(f) => {
                    let f = f.as_f64().filter(|f| f.is_finite() && *f > 0.0 && *f <= 1e6);
                    Command::Speed(Some(
                        f.ok_or("`speed`: `factor` must be a positive number, or null for as fast as it can")?,
                    ))
                }
            },
            other => return Err(format!("no message type `{other}`")),
        };
        Ok(vec![one])
    }
}

/// A value up to `max`: a number, or hex digits (`"0x"` allowed).
fn word(v: Option<&Value>, max: u64) -> Option<u64> {
    match v? {
        Value::Number(n) => n.as_u64(),
        Value::String(s) => u64::from_str_radix(s.trim_start_matches("0x"), 16).ok(),
        _ => None,
    }
    .filter(|v| *v <= max)
}

/// One pin of a ViDBo `gpio` message: `SW0`..`SW15`, `BTNC`.., `CPU_RESET`.
fn vidbo_pin(pin: &str, value: &Value) -> Result<Command, String> {
    let on = match value {
        Value::Bool(b) => *b,
        Value::Number(n) if n.as_u64().is_some_and(|n| n <= 1) => n.as_u64() == Some(1),
        _ => return Err(format!("`gpio`: `{pin}` must be true or false")),
    };
    if let Some(i) = pin.strip_prefix("SW").and_then(|n| n.parse::<u8>().ok()).filter(|i| *i < 16) {
        return Ok(Command::Switch { index: i, on });
    }
    match Button::from_name(pin) {
        Some(button) => Ok(Command::Button { button, down: on }),
        None => Err(format!("`gpio`: no input pin `{pin}` (SW0-SW15, BTNC, BTNU, BTND, BTNL, BTNR, CPU_RESET)")),
    }
}

/// The bot as its last sample showed it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BotView {
    pub sample: u64,
    pub x: u8,
    pub y: u8,
    /// `N`, `NE`, ... as BotInfo says.
    pub heading: String,
    /// `stopped`, `forward`, ...
    pub movement: String,
    pub info: u8,
    pub sensors: u8,
    pub lmdist: u8,
    pub rmdist: u8,
    pub motctl: u8,
}

/// What the board shows and where the run is: the message every page gets on every change.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BoardView {
    pub time_ps: u64,
    /// The run's rate against real time, and whether it runs.
    pub rate: f64,
    pub running: bool,
    /// `None`: as fast as it can.
    pub speed: Option<f64>,
    pub leds: u16,
    pub switches: u16,
    /// Pressed buttons, a bit each in [`Button::ALL`]'s order.
    pub buttons: u8,
    /// Lit segments per digit as a person sees them (index = digit, bit 0 segment a, bit 7
    /// the point), and the same as text (digit 7 first).
    pub digits: [u8; 8],
    pub text: String,
    pub samples: u64,
    pub bot: Option<BotView>,
    /// The design's other bots (a game's monster): each one's path from the top and its last
    /// sample, if it has had one.
    pub others: Vec<(String, Option<BotView>)>,
    /// VGA frames per second of wall time, the last few seconds.
    pub frame_rate: f64,
    /// The bot alone: the MotCtl_in the page set (or the driver gave) for the next sample.
    pub motors: Option<u8>,
    /// Why the run cannot keep the pace asked for, in one line; `None` while it keeps it.
    pub behind: Option<String>,
}

/// A bot's last sample in the `state` message.
fn bot_json(b: &BotView) -> Value {
    json!({
        "sample": b.sample, "x": b.x, "y": b.y, "heading": b.heading, "movement": b.movement,
        "info": b.info, "sensors": b.sensors, "lmdist": b.lmdist, "rmdist": b.rmdist, "motctl": b.motctl,
    })
}

impl BoardView {
    /// botsim's `state` message.
    pub fn to_json(&self) -> Value {
        json!({
            "type": "state",
            "time_ps": self.time_ps,
            "rate": self.rate,
            "running": self.running,
            "speed": self.speed,
            "leds": self.leds,
            "switches": self.switches,
            "buttons": Button::ALL.iter().filter(|b| self.buttons & b.bit() != 0).map(|b| b.name()).collect::<Vec<_>>(),
            "digits": self.digits,
            "text": self.text,
            "samples": self.samples,
            "bot": self.bot.as_ref().map(bot_json),
            "others": self.others.iter().map(|(path, b)| json!({"path": path, "bot": b.as_ref().map(bot_json)})).collect::<Vec<_>>(),
            "frame_rate": self.frame_rate,
            "behind": self.behind,
            "motors": self.motors,
        })
    }

    /// ViDBo's shape: `{"gpio": {"LD0": 1, ..., "SevSegDispl0": "4", ...}}`, the display's
    /// digits as the characters a person reads (`?` for a pattern that is no glyph).
    pub fn to_vidbo(&self) -> Value {
        let mut gpio = serde_json::Map::new();
        for i in 0..16 {
            gpio.insert(format!("LD{i}"), json!(self.leds >> i & 1));
        }
        // The text has digit 7 first, each digit's point after it.
        let mut chars: Vec<char> = Vec::new();
        for c in self.text.chars() {
            if c != '.' {
                chars.push(c);
            }
        }
        for d in 0..8 {
            let c = chars.get(7 - d).copied().unwrap_or(' ');
            gpio.insert(format!("SevSegDispl{d}"), json!(c.to_string()));
        }
        json!({ "gpio": gpio })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_and_what_is_wrong_with_a_bad_one() {
        let ok = |t: &str| Command::parse(t).unwrap();
        assert_eq!(ok(r#"{"type":"switches","value":"00ff"}"#), vec![Command::Switches(0xFF)]);
        assert_eq!(ok(r#"{"type":"switches","value":258}"#), vec![Command::Switches(258)]);
        assert_eq!(
            ok(r#"{"type":"button","name":"btnCpuReset","down":true}"#),
            vec![Command::Button { button: Button::CpuReset, down: true }]
        );
        assert_eq!(ok(r#"{"type":"speed","factor":null}"#), vec![Command::Speed(None)]);
        assert_eq!(ok(r#"{"type":"motors","value":"33"}"#), vec![Command::Motors(0x33)]);
        assert_eq!(ok(r#"{"type":"motors","value":50}"#), vec![Command::Motors(50)]);
        assert_eq!(ok(r#"{"type":"speed","factor":4}"#), vec![Command::Speed(Some(4.0))]);
        for (kind, c) in [
            ("run", Command::Run),
            ("pause", Command::Pause),
            ("step", Command::Step),
            ("save", Command::Save),
            ("stop", Command::Stop),
        ] {
            assert_eq!(ok(&format!("{{\"type\":\"{kind}\"}}")), vec![c]);
        }
        for (bad, says) in [
            ("not json", "not JSON"),
            ("[1,2]", "a JSON object"),
            (r#"{"type":"fly"}"#, "no message type `fly`"),
            (r#"{"type":"button","name":"btnX","down":true}"#, "no button `btnX`"),
            (r#"{"type":"button","name":"btnC"}"#, "`down` must be true or false"),
            (r#"{"type":"speed","factor":-1}"#, "positive number"),
            (r#"{"type":"motors","value":256}"#, "0 to 255"),
            (r#"{"type":"switches","value":"fffff"}"#, "four hex digits"),
            (r#"{"gpio":{"LD3":true}}"#, "no input pin `LD3`"),
            (r#"{"gpio":{"SW1":"yes"}}"#, "`SW1` must be true or false"),
        ] {
            let e = Command::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn vidbo_sees_the_leds_and_the_digits_as_read() {
        let v = BoardView { leds: 0b101, text: "4040  . 2".into(), ..Default::default() };
        let g = &v.to_vidbo()["gpio"];
        assert_eq!((g["LD0"].as_u64(), g["LD1"].as_u64(), g["LD2"].as_u64()), (Some(1), Some(0), Some(1)));
        assert_eq!(
            (g["SevSegDispl7"].as_str(), g["SevSegDispl0"].as_str(), g["SevSegDispl1"].as_str()),
            (Some("4"), Some("2"), Some(" "))
        );
    }
}
