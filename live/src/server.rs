//! The web server of a live board: one TCP port (127.0.0.1 by default) that serves the page
//! (GET of any path but the assets') and accepts a WebSocket upgrade on any path, as ViDBo's
//! server does. Each client has a thread of its own: it reads the client's messages and
//! hands the commands to the simulation through a channel, and it sends what the simulation
//! last published. The simulation never waits for a client: it only replaces the newest
//! state and frame, and appends to the log; a slow client skips intermediate states and
//! frames (each state is whole), and gets every log entry (of the last [`LOG_KEEP`]: a page
//! that connects late gets those).

use std::collections::HashMap;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use tungstenite::{Message, WebSocket};

use crate::page;
use crate::protocol::{BoardView, Command};

/// A client, numbered from 1 in the order they connect.
pub type ClientId = u64;

/// What the simulation last published.
#[derive(Default)]
struct Published {
    /// Bumped at every publication.
    seq: u64,
    /// What a client gets first: the design, the world.
    hello: Value,
    state: BoardView,
    state_seq: u64,
    /// The newest VGA frame (PNG) and what it is.
    frame: Option<(u64, Arc<Vec<u8>>, Value)>,
    /// Entries every client gets all of, in order (the bot's samples, the inputs applied).
    /// (Kept as JSON text, the last [`LOG_KEEP`] of them; `log_dropped` before those.)
    log: Vec<String>,
    log_dropped: usize,
    /// Replies for one client (an error, a saved stimulus).
    replies: HashMap<ClientId, Vec<Value>>,
    /// The run is over: clients say so and close.
    closed: bool,
}

struct Shared {
    published: Mutex<Published>,
    clients: AtomicU64,
    connected: AtomicU64,
}

/// A running server; dropping it closes every client.
pub struct Server {
    addr: SocketAddr,
    shared: Arc<Shared>,
    commands: Receiver<(ClientId, Command)>,
    stop: Arc<AtomicBool>,
}

/// How often a client thread looks for something new when nothing wakes it, and how long a
/// read waits for a client's message before it looks.
const POLL: Duration = Duration::from_millis(20);
/// The most log entries the server keeps (a page connecting late gets these; the oldest
/// go first): about 30 MB, an hour and a half of a board at real time, or minutes of the
/// bot alone at `--timing fast`.
pub const LOG_KEEP: usize = 200_000;
/// The most log entries one message carries.
const LOG_BATCH: usize = 512;
/// The longest an HTTP request head may be, and how long it may take to arrive.
const HEAD_MAX: usize = 16 * 1024;
const HEAD_WAIT: Duration = Duration::from_secs(5);

impl Server {
    /// Listen on `addr` (port 0: any free port). `hello` (the design, the world) is what
    /// every client gets first, as a `hello` message: given here, so that no client can
    /// connect before it exists.
    pub fn start(addr: SocketAddr, hello: Value) -> std::io::Result<Server> {
        let listener = TcpListener::bind(addr)?;
        let addr = listener.local_addr()?;
        let shared = Arc::new(Shared {
            published: Mutex::new(Published { hello, ..Published::default() }),
            clients: AtomicU64::new(0),
            connected: AtomicU64::new(0),
        });
        let (tx, commands) = channel();
        let stop = Arc::new(AtomicBool::new(false));
        let (s, st) = (shared.clone(), stop.clone());
        std::thread::Builder::new().name("live-accept".into()).spawn(move || accept(listener, s, tx, st))?;
        Ok(Server { addr, shared, commands, stop })
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Clients connected now.
    pub fn clients(&self) -> u64 {
        self.shared.connected.load(Ordering::Relaxed)
    }

    /// The next command of any client, if one is waiting.
    pub fn try_command(&self) -> Option<(ClientId, Command)> {
        self.commands.try_recv().ok()
    }

    /// Wait up to `wait` for a command.
    pub fn command_within(&self, wait: Duration) -> Option<(ClientId, Command)> {
        self.commands.recv_timeout(wait).ok()
    }

    fn publish(&self, f: impl FnOnce(&mut Published)) {
        let mut p = self.shared.published.lock().unwrap_or_else(|e| e.into_inner());
        f(&mut p);
        p.seq += 1;
    }

    /// The board now.
    pub fn state(&self, state: BoardView) {
        self.publish(|p| {
            p.state = state;
            p.state_seq += 1;
        });
    }

    /// A VGA frame (PNG) and what it is (`{"width", "height", "time_ps", "sample"}`).
    pub fn frame(&self, png: Vec<u8>, meta: Value) {
        self.publish(|p| {
            let seq = p.frame.as_ref().map_or(1, |f| f.0 + 1);
            p.frame = Some((seq, Arc::new(png), meta));
        });
    }

    /// An entry every client gets (in order, all of them).
    pub fn log(&self, entry: Value) {
        self.publish(|p| {
            p.log.push(entry.to_string());
            if p.log.len() > LOG_KEEP {
                let drop = LOG_KEEP / 4;
                p.log.drain(..drop);
                p.log_dropped += drop;
            }
        });
    }

    /// A message for one client.
    pub fn reply(&self, client: ClientId, message: Value) {
        self.publish(|p| p.replies.entry(client).or_default().push(message));
    }

    /// The run is over: every client is told (`{"type": "closed"}`) and closed.
    pub fn close(&self) {
        self.publish(|p| p.closed = true);
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.close();
        self.stop.store(true, Ordering::Relaxed);
        // Wake the accepting thread.
        let _ = TcpStream::connect_timeout(&self.addr, Duration::from_millis(200));
    }
}

fn accept(listener: TcpListener, shared: Arc<Shared>, tx: Sender<(ClientId, Command)>, stop: Arc<AtomicBool>) {
    for stream in listener.incoming() {
        if stop.load(Ordering::Relaxed) {
            return;
        }
        let Ok(stream) = stream else { continue };
        let (s, t) = (shared.clone(), tx.clone());
        let _ = std::thread::Builder::new().name("live-client".into()).spawn(move || {
            let _ = serve(stream, s, t);
        });
    }
}

/// One connection: a page or an asset, or a WebSocket client.
fn serve(stream: TcpStream, shared: Arc<Shared>, tx: Sender<(ClientId, Command)>) -> std::io::Result<()> {
    stream.set_read_timeout(Some(HEAD_WAIT))?;
    let head = peek_head(&stream)?;
    let upgrade = head.lines().any(|l| {
        let l = l.to_ascii_lowercase();
        l.starts_with("upgrade:") && l.contains("websocket")
    });
    if !upgrade {
        return http(stream, &head);
    }
    // The path it asked for (ViDBo's front ends are told apart by it); the head was peeked.
    let path = head.split_whitespace().nth(1).unwrap_or("/").to_string();
    let ws = tungstenite::accept(stream).map_err(|e| std::io::Error::other(e.to_string()))?;
    let id = shared.clients.fetch_add(1, Ordering::Relaxed) + 1;
    shared.connected.fetch_add(1, Ordering::Relaxed);
    let vidbo = path.to_ascii_lowercase().contains("vidbo");
    let r = client(ws, id, vidbo, &shared, &tx);
    shared.connected.fetch_sub(1, Ordering::Relaxed);
    // Its replies go with it.
    shared.published.lock().unwrap_or_else(|e| e.into_inner()).replies.remove(&id);
    r
}

/// The request head (up to the blank line), read without taking it from the stream.
fn peek_head(stream: &TcpStream) -> std::io::Result<String> {
    let start = Instant::now();
    let mut buf = vec![0u8; HEAD_MAX];
    loop {
        let n = stream.peek(&mut buf)?;
        if let Some(end) = buf[..n].windows(4).position(|w| w == b"\r\n\r\n") {
            return Ok(String::from_utf8_lossy(&buf[..end]).into_owned());
        }
        if n == 0 || n == buf.len() || start.elapsed() > HEAD_WAIT {
            return Err(std::io::Error::new(std::io::ErrorKind::InvalidData, "no request head"));
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// A plain HTTP request: the page, its script and style; anything else is the page too
/// (one page serves the board), but for a missing asset.
fn http(mut stream: TcpStream, head: &str) -> std::io::Result<()> {
    // Take the head off the stream.
    let mut sink = vec![0u8; head.len() + 4];
    stream.read_exact(&mut sink)?;
    let mut words = head.split_whitespace();
    let (method, path) = (words.next().unwrap_or(""), words.next().unwrap_or("/"));
    let path = path.split('?').next().unwrap_or("/");
    let (status, kind, body): (&str, &str, &[u8]) = match (method, path) {
        ("GET" | "HEAD", "/app.js") => ("200 OK", "text/javascript; charset=utf-8", page::SCRIPT.as_bytes()),
        ("GET" | "HEAD", "/style.css") => ("200 OK", "text/css; charset=utf-8", page::STYLE.as_bytes()),
        ("GET" | "HEAD", p)
            if p.ends_with(".js") || p.ends_with(".css") || p.ends_with(".ico") || p.ends_with(".png") =>
        {
            ("404 Not Found", "text/plain; charset=utf-8", b"not found\n")
        }
        ("GET" | "HEAD", _) => ("200 OK", "text/html; charset=utf-8", page::HTML.as_bytes()),
        _ => ("405 Method Not Allowed", "text/plain; charset=utf-8", b"GET only\n"),
    };
    let header = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n",
        body.len()
    );
    stream.write_all(header.as_bytes())?;
    if method != "HEAD" {
        stream.write_all(body)?;
    }
    stream.flush()
}

/// What a client has been sent.
#[derive(Default)]
struct Sent {
    /// The publication it has seen last.
    seq: u64,
    state_seq: u64,
    frame: u64,
    log: usize,
}

fn client(
    mut ws: WebSocket<TcpStream>,
    id: ClientId,
    vidbo: bool,
    shared: &Shared,
    tx: &Sender<(ClientId, Command)>,
) -> std::io::Result<()> {
    let io = |e: tungstenite::Error| std::io::Error::other(e.to_string());
    ws.get_ref().set_read_timeout(Some(POLL))?;
    let mut sent = Sent::default();
    let mut vidbo = vidbo;
    // The hello first, then everything published.
    let hello = {
        let p = shared.published.lock().unwrap_or_else(|e| e.into_inner());
        let mut h = p.hello.clone();
        if let Some(o) = h.as_object_mut() {
            o.insert("type".into(), json!("hello"));
            o.insert("client".into(), json!(id));
        }
        h
    };
    ws.send(Message::text(hello.to_string())).map_err(io)?;
    loop {
        // A message from the client, if one came.
        match ws.read() {
            Ok(Message::Text(t)) => {
                if t.contains("\"gpio\"") {
                    vidbo = true;
                }
                match Command::parse(&t) {
                    Ok(cmds) => {
                        for c in cmds {
                            if tx.send((id, c)).is_err() {
                                return Ok(());
                            }
                        }
                    }
                    Err(e) => ws.send(Message::text(json!({"type": "error", "message": e}).to_string())).map_err(io)?,
                }
            }
            Ok(Message::Binary(_)) => {
                let e = json!({"type": "error", "message": "binary messages are not commands: send JSON text"});
                ws.send(Message::text(e.to_string())).map_err(io)?;
            }
            Ok(Message::Close(_)) => return Ok(()),
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
            Err(tungstenite::Error::ConnectionClosed | tungstenite::Error::AlreadyClosed) => return Ok(()),
            Err(e) => return Err(io(e)),
        }
        // What was published since.
        let (out, frame, closed) = {
            let mut p = shared.published.lock().unwrap_or_else(|e| e.into_inner());
            sent.seq = p.seq;
            let mut out: Vec<String> = Vec::new();
            // (`sent.log` counts every entry ever logged, the dropped ones too.)
            let from = sent.log.max(p.log_dropped) - p.log_dropped;
            if from < p.log.len() {
                for chunk in p.log[from..].chunks(LOG_BATCH) {
                    out.push(format!("{{\"type\":\"log\",\"entries\":[{}]}}", chunk.join(",")));
                }
                sent.log = p.log_dropped + p.log.len();
            }
            if sent.state_seq != p.state_seq {
                sent.state_seq = p.state_seq;
                out.push(p.state.to_json().to_string());
                if vidbo {
                    out.push(p.state.to_vidbo().to_string());
                }
            }
            if let Some(r) = p.replies.remove(&id) {
                out.extend(r.iter().map(Value::to_string));
            }
            let frame = match &p.frame {
                Some((seq, png, meta)) if *seq != sent.frame => {
                    sent.frame = *seq;
                    Some((png.clone(), meta.clone()))
                }
                _ => None,
            };
            (out, frame, p.closed)
        };
        for m in out {
            ws.send(Message::text(m)).map_err(io)?;
        }
        if let Some((png, mut meta)) = frame {
            if let Some(o) = meta.as_object_mut() {
                o.insert("type".into(), json!("frame"));
                o.insert("bytes".into(), json!(png.len()));
            }
            ws.send(Message::text(meta.to_string())).map_err(io)?;
            ws.send(Message::binary(png.as_ref().clone())).map_err(io)?;
        }
        if closed {
            ws.send(Message::text(json!({"type": "closed"}).to_string())).map_err(io)?;
            let _ = ws.close(None);
            let _ = ws.flush();
            return Ok(());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A page that connects after more than [`LOG_KEEP`] entries gets the newest ones, in
    /// order, each once; the hello comes first.
    #[test]
    fn a_late_page_gets_the_newest_log_entries_in_order() {
        let server = Server::start("127.0.0.1:0".parse().unwrap(), json!({"design": "test"})).unwrap();
        let total = LOG_KEEP + LOG_KEEP / 2 + 7;
        for i in 0..total {
            server.log(json!({"kind": "sample", "sample": i}));
        }
        let url = server.url().replacen("http://", "ws://", 1);
        let (mut ws, _) = tungstenite::connect(url).unwrap();
        let first: Value = serde_json::from_str(ws.read().unwrap().to_text().unwrap()).unwrap();
        assert_eq!((first["type"].as_str(), first["design"].as_str()), (Some("hello"), Some("test")));
        let mut got: Vec<u64> = Vec::new();
        let start = Instant::now();
        while got.last() != Some(&(total as u64 - 1)) {
            assert!(start.elapsed() < Duration::from_secs(60), "only {} entries came", got.len());
            let m: Value = serde_json::from_str(ws.read().unwrap().to_text().unwrap()).unwrap();
            if m["type"] == "log" {
                got.extend(m["entries"].as_array().unwrap().iter().map(|e| e["sample"].as_u64().unwrap()));
            }
        }
        assert!(got.len() <= LOG_KEEP && got.len() >= LOG_KEEP * 3 / 4, "{}", got.len());
        assert!(got.windows(2).all(|w| w[1] == w[0] + 1), "in order, each once");
    }
}
