//! A live board for tests: `botsim board ... --live --port 0` in a child process (killed
//! when dropped), and WebSocket clients that wait for what they expect with a budget.

use std::io::{BufRead, BufReader};
use std::net::TcpStream;

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// How long any wait of these tests may take.
pub const BUDGET: Duration = Duration::from_secs(60);

use super::{board_cache, root};

/// A running `botsim board --live`.
pub struct Live {
    pub child: Child,
    /// The page's address (`http://127.0.0.1:PORT/`).
    pub url: String,
}

impl Live {
    /// Start it with `args` (sources and options; `--live --port 0` are added) and read the
    /// address it prints first.
    pub fn start(args: &[&str]) -> Live {
        Live::start_command("board", args)
    }

    /// The same for another subcommand (`run`: the bot alone).
    pub fn start_command(command: &str, args: &[&str]) -> Live {
        Live::start_in(&root(), command, args)
    }

    /// The same in the folder `dir`.
    pub fn start_in(dir: &std::path::Path, command: &str, args: &[&str]) -> Live {
        let mut child = Command::new(env!("CARGO_BIN_EXE_botsim"))
            .arg(command)
            .args(args)
            .args(["--live", "--port", "0", "-q"])
            .current_dir(dir)
            .env("BOTSIM_CACHE", board_cache())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap();
        let mut out = BufReader::new(child.stdout.take().unwrap());
        let mut url = String::new();
        // The build, if any, comes first: the address is printed when the board runs.
        out.read_line(&mut url).unwrap();
        assert!(url.starts_with("http://127.0.0.1:"), "the first line is {url:?}");
        Live { child, url: url.trim().to_string() }
    }

    /// A WebSocket client on any path of the server.
    pub fn client(&self, path: &str) -> Client {
        let ws_url = format!("{}{}", self.url.replacen("http://", "ws://", 1).trim_end_matches('/'), path);
        let (ws, _) = tungstenite::connect(ws_url).unwrap();
        if let MaybeTlsStream::Plain(s) = ws.get_ref() {
            s.set_read_timeout(Some(Duration::from_millis(100))).unwrap();
        }
        Client { ws, frames: Vec::new() }
    }

    /// Wait for the process to end by itself (after a `stop`), within the budget.
    pub fn wait(&mut self) -> std::process::ExitStatus {
        super::exit_within(&mut self.child, BUDGET, "the live board did not end")
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A page's connection.
pub struct Client {
    pub ws: WebSocket<MaybeTlsStream<TcpStream>>,
    /// PNG frames received so far, each with its `frame` message.
    pub frames: Vec<(Value, Vec<u8>)>,
}

impl Client {
    pub fn send(&mut self, v: Value) {
        self.ws.send(Message::text(v.to_string())).unwrap();
    }

    pub fn send_text(&mut self, t: &str) {
        self.ws.send(Message::text(t.to_string())).unwrap();
    }

    /// The next text message within `wait`, if any (a frame's PNG is kept aside).
    pub fn next(&mut self, wait: Duration) -> Option<Value> {
        let start = Instant::now();
        let mut meta: Option<Value> = None;
        while start.elapsed() < wait {
            match self.ws.read() {
                Ok(Message::Text(t)) => {
                    let v: Value = serde_json::from_str(&t).unwrap();
                    if v["type"] == "frame" {
                        meta = Some(v);
                        continue;
                    }
                    return Some(v);
                }
                Ok(Message::Binary(b)) => {
                    if let Some(m) = meta.take() {
                        self.frames.push((m, b.to_vec()));
                    }
                }
                Ok(_) => {}
                Err(tungstenite::Error::Io(e))
                    if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
                Err(e) => panic!("the connection failed: {e}"),
            }
        }
        None
    }

    /// Read messages until `want` holds for one (returned), within the budget.
    pub fn until(&mut self, what: &str, mut want: impl FnMut(&Value) -> bool) -> Value {
        let start = Instant::now();
        while start.elapsed() < BUDGET {
            if let Some(v) = self.next(Duration::from_millis(200)) {
                if want(&v) {
                    return v;
                }
            }
        }
        panic!("no {what} within {} s", BUDGET.as_secs());
    }

    /// The next `state` message whose fields satisfy `want`.
    pub fn state(&mut self, what: &str, mut want: impl FnMut(&Value) -> bool) -> Value {
        self.until(what, |v| v["type"] == "state" && want(v))
    }

    /// The log entries of the next `log` message that has one satisfying `want`: that one.
    pub fn log_entry(&mut self, what: &str, mut want: impl FnMut(&Value) -> bool) -> Value {
        let mut found = None;
        self.until(what, |v| {
            if v["type"] != "log" {
                return false;
            }
            found = v["entries"].as_array().unwrap().iter().find(|e| want(e)).cloned();
            found.is_some()
        });
        found.unwrap()
    }
}
