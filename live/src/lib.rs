//! botsim's live board: a team's design running in botsim, played with from a browser as on
//! the board. [`server::Server`] serves the page ([`page`]) on a local port and speaks
//! [`protocol`] with every page over one WebSocket: the commands (switches, buttons, run,
//! pause, step, speed) come in, the board's state, the bot's samples and the VGA frames go
//! out. It knows nothing of the simulation: `botsim board --live` (src/cli/board/live.rs)
//! runs the board and publishes what it shows.
//!
//! ```no_run
//! use botsim_live::server::Server;
//! use botsim_live::protocol::{BoardView, Command};
//! let hello = serde_json::json!({"design": "demo"});
//! let server = Server::start("127.0.0.1:0".parse().unwrap(), hello).unwrap();
//! println!("{}", server.url());
//! loop {
//!     while let Some((_client, command)) = server.try_command() {
//!         if command == Command::Stop { return; }
//!     }
//!     server.state(BoardView { leds: 1, ..Default::default() });
//!     std::thread::sleep(std::time::Duration::from_millis(50));
//! }
//! ```

pub mod page;
pub mod protocol;
pub mod server;
