//! A headless Chromium driven over the DevTools protocol, with what the page tests do to a
//! page: load it, run a script, click, hold a key or the mouse, type, take a screenshot.
//!
//! The protocol is JSON over one WebSocket (tungstenite): a command is `{id, method, params}`
//! and its answer carries the same `id`; events (`{method, params}`) come between. A crate
//! that generates the whole protocol (headless_chrome) cost a fresh build and the lint stage
//! about four minutes of CPU between them for the nine commands used here (docs/PERFORMANCE.md).
//! Every wait has [`BUDGET`](super::live::BUDGET).
//!
//! ```no_run
//! # use std::path::Path;
//! let page = common::cdp::Page::open(Path::new("/usr/bin/chromium"), "http://127.0.0.1:8080/");
//! page.click("#run");
//! let png: Vec<u8> = page.screenshot();
//! ```

use std::cell::{Cell, RefCell};
use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Instant;

use base64::Engine;
use serde_json::{json, Value};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

use super::live::BUDGET;

/// One page in a headless Chromium of its own (the browser ends when this is dropped).
pub struct Page {
    browser: Child,
    _profile: tempfile::TempDir,
    ws: RefCell<WebSocket<MaybeTlsStream<TcpStream>>>,
    session: String,
    next: Cell<u64>,
    /// Events read while waiting for an answer, by method name.
    events: RefCell<Vec<String>>,
}

/// The window every page test sees (the page lays out the board and the world side by side).
const WINDOW: &str = "--window-size=1480,1040";

impl Page {
    /// Start `chromium` headless and load `url` in a new page, waiting for its load event.
    pub fn open(chromium: &Path, url: &str) -> Page {
        let profile = tempfile::tempdir().unwrap();
        let mut browser = Command::new(chromium)
            .args(["--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-port=0", WINDOW])
            // As a page in a window in front: timers and rendering never throttled.
            .args([
                "--disable-background-timer-throttling",
                "--disable-backgrounding-occluded-windows",
                "--disable-renderer-backgrounding",
                "--disable-dev-shm-usage",
                "--disable-extensions",
                "--disable-background-networking",
                "--disable-sync",
                "--no-first-run",
                "--no-default-browser-check",
                "--force-color-profile=srgb",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg("about:blank")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Chromium prints the browser's WebSocket address on stderr, which is read to its end
        // (a full pipe would stop the browser).
        let (tx, rx) = mpsc::channel();
        let stderr = BufReader::new(browser.stderr.take().unwrap());
        std::thread::spawn(move || {
            for line in stderr.lines().map_while(Result::ok) {
                if let Some(at) = line.strip_prefix("DevTools listening on ") {
                    let _ = tx.send(at.to_string());
                }
            }
        });
        let address = rx.recv_timeout(BUDGET).expect("chromium never said where its DevTools listen");
        let (ws, _) = tungstenite::connect(address.as_str()).unwrap();
        if let MaybeTlsStream::Plain(s) = ws.get_ref() {
            s.set_read_timeout(Some(BUDGET)).unwrap();
        }
        let mut page = Page {
            browser,
            _profile: profile,
            ws: RefCell::new(ws),
            session: String::new(),
            next: Cell::new(1),
            events: RefCell::new(Vec::new()),
        };
        let target = page.call("Target.createTarget", json!({ "url": "about:blank" }));
        let attached = page.call("Target.attachToTarget", json!({ "targetId": target["targetId"], "flatten": true }));
        page.session = attached["sessionId"].as_str().unwrap().to_string();
        page.call("Page.enable", json!({}));
        page.events.borrow_mut().clear();
        page.call("Page.navigate", json!({ "url": url }));
        page.wait_event("Page.loadEventFired");
        page
    }

    /// Send one command (to the page once attached) and wait for its answer: its `result`.
    pub fn call(&self, method: &str, params: Value) -> Value {
        let id = self.next.get();
        self.next.set(id + 1);
        let mut msg = json!({ "id": id, "method": method, "params": params });
        if !self.session.is_empty() {
            msg["sessionId"] = Value::from(self.session.as_str());
        }
        let mut ws = self.ws.borrow_mut();
        ws.send(Message::text(msg.to_string())).unwrap();
        let start = Instant::now();
        loop {
            assert!(start.elapsed() < BUDGET, "chromium did not answer {method}");
            let m = Self::read(&mut ws);
            if m["id"].as_u64() == Some(id) {
                assert!(m["error"].is_null(), "chromium refused {method}: {}", m["error"]);
                return m["result"].clone();
            }
            if let Some(event) = m["method"].as_str() {
                self.events.borrow_mut().push(event.to_string());
            }
        }
    }

    /// Wait for the event `method` (or find it among those read since the last wait).
    fn wait_event(&self, method: &str) {
        let start = Instant::now();
        while !self.events.borrow().iter().any(|e| e == method) {
            assert!(start.elapsed() < BUDGET, "chromium never sent {method}");
            let m = Self::read(&mut self.ws.borrow_mut());
            if let Some(event) = m["method"].as_str() {
                self.events.borrow_mut().push(event.to_string());
            }
        }
        self.events.borrow_mut().clear();
    }

    fn read(ws: &mut WebSocket<MaybeTlsStream<TcpStream>>) -> Value {
        loop {
            match ws.read().expect("the DevTools connection failed (or nothing came within the budget)") {
                Message::Text(t) => return serde_json::from_str(&t).unwrap(),
                Message::Close(_) => panic!("chromium closed the DevTools connection"),
                _ => {}
            }
        }
    }

    /// The value of the expression `js` in the page (a promise awaited when `awaited`).
    pub fn eval(&self, js: &str, awaited: bool) -> Value {
        let r =
            self.call("Runtime.evaluate", json!({ "expression": js, "returnByValue": true, "awaitPromise": awaited }));
        assert!(r["exceptionDetails"].is_null(), "the page threw on {js}: {}", r["exceptionDetails"]);
        r["result"]["value"].clone()
    }

    /// The box of the element `selector` selects, scrolled into view: (x, y, width, height)
    /// in the window.
    pub fn rect(&self, selector: &str) -> (f64, f64, f64, f64) {
        let js = format!(
            "(() => {{ const e = document.querySelector({}); e.scrollIntoViewIfNeeded(); \
             const r = e.getBoundingClientRect(); return [r.x, r.y, r.width, r.height]; }})()",
            Value::from(selector)
        );
        let v = self.eval(&js, false);
        let n = |i: usize| v[i].as_f64().unwrap_or_else(|| panic!("no element {selector}"));
        (n(0), n(1), n(2), n(3))
    }

    /// The middle of the element `selector` selects.
    pub fn midpoint(&self, selector: &str) -> (f64, f64) {
        let (x, y, w, h) = self.rect(selector);
        (x + w / 2.0, y + h / 2.0)
    }

    /// The left mouse button pressed (`down`) or let go at (x, y).
    pub fn mouse(&self, down: bool, x: f64, y: f64) {
        let kind = if down { "mousePressed" } else { "mouseReleased" };
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": kind, "x": x, "y": y, "button": "left", "buttons": u8::from(down), "clickCount": 1 }),
        );
    }

    /// A click in the middle of the element `selector` selects, as the mouse makes it.
    pub fn click(&self, selector: &str) {
        let (x, y) = self.midpoint(selector);
        self.call("Input.dispatchMouseEvent", json!({ "type": "mouseMoved", "x": x, "y": y }));
        self.mouse(true, x, y);
        self.mouse(false, x, y);
    }

    /// The key `name` (its `key` and `code`, e.g. "ArrowLeft") held down or let go.
    pub fn key(&self, name: &str, code: u32, down: bool) {
        let kind = if down { "rawKeyDown" } else { "keyUp" };
        self.call(
            "Input.dispatchKeyEvent",
            json!({ "type": kind, "key": name, "code": name,
                    "windowsVirtualKeyCode": code, "nativeVirtualKeyCode": code }),
        );
    }

    /// `text` typed into the element with the focus, then Enter pressed.
    pub fn type_line(&self, text: &str) {
        for c in text.chars() {
            let t = c.to_string();
            self.call("Input.dispatchKeyEvent", json!({ "type": "keyDown", "key": t, "text": t }));
            self.call("Input.dispatchKeyEvent", json!({ "type": "keyUp", "key": t }));
        }
        let enter = json!({ "key": "Enter", "code": "Enter", "windowsVirtualKeyCode": 13 });
        let mut down = enter.clone();
        down["type"] = "keyDown".into();
        down["text"] = "\r".into();
        self.call("Input.dispatchKeyEvent", down);
        let mut up = enter;
        up["type"] = "keyUp".into();
        self.call("Input.dispatchKeyEvent", up);
    }

    /// What the window shows, as a PNG.
    pub fn screenshot(&self) -> Vec<u8> {
        let r = self.call("Page.captureScreenshot", json!({ "format": "png", "fromSurface": true }));
        base64::engine::general_purpose::STANDARD.decode(r["data"].as_str().unwrap()).unwrap()
    }
}

impl Drop for Page {
    fn drop(&mut self) {
        let _ = self.browser.kill();
        let _ = self.browser.wait();
    }
}
